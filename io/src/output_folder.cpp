// hotmesh io: guards on output folders and files.
#include "hotmesh/io/output_folder.hpp"

#include <algorithm>
#include <system_error>

#include "hotmesh/geometry/input_error.hpp"

namespace hotmesh::io {
namespace {

std::filesystem::path resolved(const std::filesystem::path& p) {
  std::error_code ec;
  auto r = std::filesystem::weakly_canonical(std::filesystem::absolute(p), ec);
  return ec ? std::filesystem::absolute(p).lexically_normal() : r;
}

bool is_inside(const std::filesystem::path& file, const std::filesystem::path& folder) {
  const auto f = resolved(file);
  const auto d = resolved(folder);
  auto [end, unused] = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
  return end == d.end();
}

}  // namespace

void prepare_output_folder(const std::filesystem::path& folder, std::span<const std::filesystem::path> inputs,
                           bool force) {
  std::error_code ec;
  if (std::filesystem::exists(folder, ec) && !std::filesystem::is_directory(folder, ec)) {
    throw InputError::in(folder.string(), "the output folder is a file; choose another folder with -o");
  }
  if (!force) {
    for (const auto& input : inputs) {
      if (is_inside(input, folder)) {
        throw InputError::in(folder.string(),
                             "the output folder holds the input " + input.string() +
                                 "; choose another folder with -o, or pass --force to write there anyway");
      }
    }
  }
  std::filesystem::create_directories(folder, ec);
  if (ec) throw InputError::in(folder.string(), "cannot create the output folder: " + ec.message());
}

void refuse_overwriting_input(const std::filesystem::path& output, std::span<const std::filesystem::path> inputs) {
  const auto out = resolved(output);
  for (const auto& input : inputs) {
    if (resolved(input) == out) {
      throw InputError::in(output.string(), "this output would replace an input file; hotmesh never overwrites its inputs");
    }
  }
}

}  // namespace hotmesh::io
