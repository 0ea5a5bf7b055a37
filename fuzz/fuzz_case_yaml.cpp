// hotmesh fuzz: case files (YAML), as `hotmesh deform` reads them. The case lies in an empty
// folder, so every file it names relative to itself is missing and reported as such.
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = [] {
    const auto folder = hotmesh::fuzz::work_folder() / "case";
    std::filesystem::create_directories(folder);
    return folder / "case.yaml";
  }();
  try {
    hotmesh::io::parse_case(hotmesh::fuzz::as_text(data, size), file);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), file.string());
  }
  return 0;
}
