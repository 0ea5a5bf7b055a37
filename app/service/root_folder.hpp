// hotmesh serve: the folder `--root` whose files the service may read, and nothing outside it.
// A requested path is relative to the root (or absolute and inside it); it may not hold "..".
// The file is opened beneath the root's directory handle with openat2(RESOLVE_BENEATH), so no
// symbolic link can lead out of it (where the kernel lacks openat2, every component is opened
// with O_NOFOLLOW: no symbolic link is followed at all). Only regular files are read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace hotmesh::app::serve {

class RootFolder {
 public:
  /// Throws hotmesh::InputError if `root` is not a readable folder.
  explicit RootFolder(const std::filesystem::path& root);
  RootFolder(const RootFolder&) = delete;
  RootFolder& operator=(const RootFolder&) = delete;
  ~RootFolder();

  const std::filesystem::path& path() const { return path_; }  ///< canonical

  /// The content of the file at `requested` below the root. ApiError 400 for an empty path or
  /// one holding a NUL byte, 403 for a path with "..", an absolute path outside the root, or a
  /// symbolic link leading out of it, 404 for no such file, 400 for a folder or other
  /// non-regular file, 413 for a file larger than `max_bytes`.
  std::string read(std::string_view requested, std::size_t max_bytes) const;

  struct Entry {
    std::string path;  ///< relative to the root, with '/'
    std::uintmax_t bytes = 0;
  };
  /// Regular files below the root whose extension is one of `extensions` (lower case, with
  /// the dot), sorted, at most `limit`, down to `depth` folders; symbolic links and hidden
  /// files and folders are left out.
  std::vector<Entry> list(const std::vector<std::string>& extensions, std::size_t limit, int depth) const;

 private:
  int open_beneath(const std::string& relative) const;

  std::filesystem::path path_;
  int fd_ = -1;
};

/// The lower-case extension of a file name, with its dot ("" if none).
std::string lower_extension(std::string_view name);

}  // namespace hotmesh::app::serve
