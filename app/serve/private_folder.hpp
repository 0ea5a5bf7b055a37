// hotmesh serve: a private folder for uploaded CAD files: made with mkdtemp (mode 0700, a
// fresh random name under the system's temporary folder), removed with its content when the
// service ends.
#pragma once

#include <atomic>
#include <filesystem>
#include <string_view>

namespace hotmesh::app::serve {

class PrivateFolder {
 public:
  /// Throws hotmesh::InputError if the folder cannot be made.
  PrivateFolder();
  PrivateFolder(const PrivateFolder&) = delete;
  PrivateFolder& operator=(const PrivateFolder&) = delete;
  ~PrivateFolder();

  const std::filesystem::path& path() const { return path_; }

  /// Writes `content` to a new file "upload-N<extension>" (readable by this user only) and
  /// returns its path. Thread-safe.
  std::filesystem::path write(std::string_view extension, std::string_view content);

 private:
  std::filesystem::path path_;
  std::atomic<unsigned long> count_{0};
};

}  // namespace hotmesh::app::serve
