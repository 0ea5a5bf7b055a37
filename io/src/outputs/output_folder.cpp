// hotmesh io: guards on output folders and files.
#include "hotmesh/io/output_folder.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <utility>
#include <system_error>

#include "hotmesh/core/input_error.hpp"

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

OutputFolder::OutputFolder(OutputFolder&& other) noexcept
    : folder_(std::move(other.folder_)), created_(std::exchange(other.created_, {})) {}

OutputFolder& OutputFolder::operator=(OutputFolder&& other) noexcept {
  if (this != &other) {
    OutputFolder old(std::move(*this));
    folder_ = std::move(other.folder_);
    created_ = std::exchange(other.created_, {});
  }
  return *this;
}

OutputFolder::~OutputFolder() {
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) {
    std::error_code ec;
    if (!std::filesystem::is_empty(*it, ec) || ec || !std::filesystem::remove(*it, ec)) break;
  }
}

OutputFolder prepare_output_folder(const std::filesystem::path& folder, std::span<const std::filesystem::path> inputs,
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
  OutputFolder result;
  result.folder_ = folder;
  std::filesystem::path start = std::filesystem::absolute(folder).lexically_normal();
  if (!start.has_filename()) start = start.parent_path();  // "out/"
  for (std::filesystem::path missing = start; missing.has_relative_path() && !std::filesystem::exists(missing, ec);
       missing = missing.parent_path()) {
    result.created_.push_back(missing);
  }
  std::reverse(result.created_.begin(), result.created_.end());
  std::filesystem::create_directories(folder, ec);
  if (ec) throw InputError::in(folder.string(), "cannot create the output folder: " + ec.message());
  // Writable? Found now, not after the first hours of work.
  const std::filesystem::path probe = folder / (".hotmesh-write-check-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    throw InputError::in(folder.string(), std::string("cannot write in the output folder: ") + std::strerror(errno) +
                                              "; choose another folder with -o");
  }
  ::close(fd);
  std::filesystem::remove(probe, ec);
  return result;
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
