// hotmesh serve: a private folder for uploaded CAD files: made with mkdtemp (mode 0700, a
// fresh random name under the system's temporary folder), removed with its content when the
// service ends. Each file in it is removed when the request that wrote it ends, however it ends.
#pragma once

#include <atomic>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <utility>

namespace hotmesh::app::serve {

/// A file of the private folder, removed when this object goes.
class PrivateFile {
 public:
  explicit PrivateFile(std::filesystem::path path) : path_(std::move(path)) {}
  PrivateFile(PrivateFile&& other) noexcept : path_(std::exchange(other.path_, {})) {}
  PrivateFile& operator=(PrivateFile&&) = delete;
  ~PrivateFile() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove(path_, ignored);
  }

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

class PrivateFolder {
 public:
  /// Throws hotmesh::InputError if the folder cannot be made.
  PrivateFolder();
  PrivateFolder(const PrivateFolder&) = delete;
  PrivateFolder& operator=(const PrivateFolder&) = delete;
  ~PrivateFolder();

  const std::filesystem::path& path() const { return path_; }

  /// Writes `content` to a new file "upload-N<extension>" (readable by this user only), which
  /// lives as long as the object returned. Thread-safe.
  PrivateFile write(std::string_view extension, std::string_view content);

 private:
  std::filesystem::path path_;
  std::atomic<unsigned long> count_{0};
};

}  // namespace hotmesh::app::serve
