// hotmesh fuzz: OpenFOAM polyMesh folders (ASCII, binary, gzipped) as `hotmesh deform`, `info`
// and `convert` read them: read_mesh of the folder (read_foam, then the validation every mesh
// gets), then the moved points written back in the input's form (the points unmoved). The
// input is the folder's files, each after a line `//> NAME` (a comment to OpenFOAM), NAME one
// of points, faces, owner, neighbour, boundary, with `.gz` for a gzipped file: its content is
// compressed here, unless it is gzip data already (it starts with the gzip magic bytes), so
// that mutations reach both the text and the gzip stream. The files are written in memory
// (fuzz_support's memory_folder), those of the last input that this one lacks removed.
#include <zlib.h>

#include <algorithm>
#include <array>
#include <string>

#include <spdlog/spdlog.h>

#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/mesh_files.hpp"

namespace {

constexpr std::array<std::string_view, 5> kFiles{"points", "faces", "owner", "neighbour", "boundary"};
constexpr std::string_view kMarker = "//> ";

/// `content` gzipped (fast: the fuzzer's own compression is not under test).
std::string gzipped(std::string_view content) {
  uLongf size = compressBound(static_cast<uLong>(content.size())) + 32;
  std::string out(size, '\0');
  z_stream z{};
  deflateInit2(&z, 1, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(content.data()));
  z.avail_in = static_cast<uInt>(content.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(out.size() - z.avail_out);
  deflateEnd(&z);
  return out;
}

/// Writes the file `name` (a marker's word) with `content`, if it is one of the folder's.
void write_file(const std::filesystem::path& folder, std::string_view name, std::string_view content) {
  const bool gz = name.ends_with(".gz");
  const std::string_view base = gz ? name.substr(0, name.size() - 3) : name;
  if (std::find(kFiles.begin(), kFiles.end(), base) == kFiles.end()) return;
  std::filesystem::remove(folder / (std::string(base) + (gz ? "" : ".gz")));  // the other form, if the input has both
  if (gz && !content.starts_with("\x1f\x8b")) {
    hotmesh::fuzz::write_bytes(folder / name, gzipped(content));
  } else {
    hotmesh::fuzz::write_bytes(folder / name, content);
  }
}

/// Writes the input's files into `folder`, after removing those of the last input.
void write_folder(std::string_view input, const std::filesystem::path& folder) {
  for (const std::string_view base : kFiles) {
    std::filesystem::remove(folder / base);
    std::filesystem::remove(folder / (std::string(base) + ".gz"));
  }
  std::string_view name;
  std::size_t start = 0;
  for (std::size_t at = 0; at <= input.size();) {
    const std::size_t eol = std::min(input.find('\n', at), input.size());
    if (at == input.size() || input.substr(at).starts_with(kMarker)) {
      if (!name.empty()) write_file(folder, name, input.substr(start, at - start));
      if (at == input.size()) break;
      name = input.substr(at + kMarker.size(), eol - at - kMarker.size());
      start = std::min(eol + 1, input.size());
    }
    at = eol + 1;
    if (at > input.size()) at = input.size();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path folder = [] {
    spdlog::set_level(spdlog::level::off);  // the validation's notes
    const auto path = hotmesh::fuzz::memory_folder() / "polyMesh";
    std::filesystem::create_directories(path);
    std::filesystem::create_directories(hotmesh::fuzz::memory_folder() / "out");
    return path;
  }();
  write_folder(hotmesh::fuzz::as_text(data, size), folder);
  try {
    const hotmesh::io::LoadedMesh loaded = hotmesh::io::read_mesh(folder);
    loaded.write_back->write(hotmesh::fuzz::memory_folder() / "out", loaded.mesh.points, {});
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), folder.string());
  }
  return 0;
}
