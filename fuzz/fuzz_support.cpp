// hotmesh fuzz: what the libFuzzer targets share (see fuzz_support.hpp).
#include "fuzz_support.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>

namespace hotmesh::fuzz {

namespace {

/// Owns a folder of this process, <parent>/<pid>: made empty on first use, removed when the
/// process ends normally (after a crash it stays, until fuzz.sh removes it).
class WorkFolder {
 public:
  explicit WorkFolder(const std::filesystem::path& parent) : path_(parent / std::to_string(::getpid())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  ~WorkFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace

const std::filesystem::path& work_folder() {
  static const WorkFolder folder(HOTMESH_FUZZ_WORK);
  return folder.path();
}

const std::filesystem::path& memory_folder() {
  static const WorkFolder folder = [] {
    std::error_code ec;
    const bool shm = std::filesystem::is_directory("/dev/shm", ec);
    return WorkFolder(shm ? std::filesystem::path("/dev/shm/hotmesh-fuzz") : work_folder() / "memory");
  }();
  return folder.path();
}

void write_bytes(const std::filesystem::path& file, std::string_view content) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", file.c_str());
    std::abort();
  }
}

std::filesystem::path source_file(std::string_view relative) {
  return std::filesystem::path(HOTMESH_SOURCE_DIR) / relative;
}

std::filesystem::path use_private_temporary_folder() {
  const std::filesystem::path folder = work_folder() / "tmp";
  std::filesystem::create_directories(folder);
  ::setenv("TMPDIR", folder.c_str(), 1);
  return folder;
}

void require_no_files_left(const std::filesystem::path& folder) {
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::fprintf(stderr, "fuzz: the request left %s behind\n", entry.path().c_str());
    std::abort();
  }
}

void require_named(std::string_view message, std::string_view source) {
  if (message.find(source) != std::string_view::npos) return;
  std::fprintf(stderr, "fuzz: the input was refused with a message that does not name '%.*s':\n%.*s\n",
               static_cast<int>(source.size()), source.data(), static_cast<int>(message.size()), message.data());
  std::abort();
}

}  // namespace hotmesh::fuzz
