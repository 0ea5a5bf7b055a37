// hotmesh fuzz: CalculiX input decks (.inp) with their *INCLUDE files, as `hotmesh fem --inp`
// and a case's `calculix: {inp: ...}` read them: read_inp, then the model's kind and the nodes
// of every node set and surface (what `hotmesh fem` lists). The input is the deck and the
// files it may include: a line starting with `**>` (a comment to CalculiX) ends one file and
// starts the next, `1.inp` to `7.inp` beside `deck.inp`, so that mutations reach includes of
// any shape (loops, diamonds, data lines continued in another file); they are written in
// memory (fuzz_support's memory_folder), three times faster than on disk. The deck's limits
// (InpLimits) are small ones, so that each input is read in milliseconds; the program's own
// are tested in tests/io/test_calculix_damage.cpp.
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/calculix.hpp"

namespace {

constexpr std::size_t kMaxFiles = 8;  // deck.inp, 1.inp ... 7.inp

std::filesystem::path file_name(std::size_t k) { return k == 0 ? "deck.inp" : std::to_string(k) + ".inp"; }

/// Writes the input's files into `folder`, and removes those of the last input it lacks.
void write_files(std::string_view input, const std::filesystem::path& folder) {
  std::size_t k = 0;
  std::size_t start = 0;
  for (std::size_t at = 0; at < input.size();) {
    const std::size_t eol = std::min(input.find('\n', at), input.size());
    if (input.substr(at).starts_with("**>") && k + 1 < kMaxFiles) {
      hotmesh::fuzz::write_bytes(folder / file_name(k++), input.substr(start, at - start));
      start = std::min(eol + 1, input.size());
    }
    at = eol + 1;
  }
  hotmesh::fuzz::write_bytes(folder / file_name(k++), input.substr(start));
  for (; k < kMaxFiles; ++k) std::filesystem::remove(folder / file_name(k));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path folder = [] {
    const auto path = hotmesh::fuzz::memory_folder() / "inp";
    std::filesystem::create_directories(path);
    return path;
  }();
  hotmesh::io::InpLimits limits;
  limits.includes = 64;
  limits.lines = 20'000;
  limits.set_members = 100'000;
  write_files(hotmesh::fuzz::as_text(data, size), folder);
  try {
    const hotmesh::io::InpDeck deck = hotmesh::io::read_inp(folder / "deck.inp", limits);
    try {
      deck.kind();
    } catch (const hotmesh::InputError& e) {
      hotmesh::fuzz::require_named(e.what(), folder.string());
    }
    for (const auto* sets : {&deck.nsets, &deck.surfaces}) {
      for (const auto& [name, set] : *sets) {
        deck.set_nodes(name);
        deck.set_place(name);
      }
    }
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), folder.string());
  }
  return 0;
}
