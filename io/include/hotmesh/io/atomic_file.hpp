// hotmesh io: every output file is written atomically. Content goes to a temporary file
// beside the target; only commit() renames it over the target, so a reader (or a crash
// midway) never sees a half-written file and an earlier valid file stays in place.
#pragma once

#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>

namespace hotmesh::io {

class AtomicFile {
 public:
  /// Opens a temporary file beside `target`. Throws hotmesh::InputError if it cannot.
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Removes the temporary file unless commit() succeeded.
  ~AtomicFile();

  std::ostream& stream() { return out_; }
  const std::filesystem::path& target() const { return target_; }

  /// Flushes, syncs to disk and renames over the target. Throws hotmesh::InputError on
  /// failure (disk full, permissions), leaving the target as it was.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// The same for a file that a library writes itself by name (the CGNS library): it writes
/// temporary(); commit() syncs it and renames it over the target. The destructor removes the
/// temporary file unless commit() succeeded.
class AtomicPath {
 public:
  explicit AtomicPath(std::filesystem::path target);
  AtomicPath(const AtomicPath&) = delete;
  AtomicPath& operator=(const AtomicPath&) = delete;
  ~AtomicPath();

  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& target() const { return target_; }
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

/// Writes `content` to `target` atomically.
void write_file_atomically(const std::filesystem::path& target, std::string_view content);

/// Removes the temporary files that a killed run left beside the outputs `names` in `folder`
/// (`<name>.tmp-<pid>-<n>` of a process that no longer runs; those of a live process stay).
/// A name may lie in a subfolder of `folder` ("polyMesh/points").
void remove_stale_temporaries(const std::filesystem::path& folder, std::span<const std::string> names);

/// Reads a whole file. Throws hotmesh::InputError naming the file if it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace hotmesh::io
