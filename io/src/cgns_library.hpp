// hotmesh io (private): the CGNS mid-level library (cgnslib.h) behind a thin layer: an open
// file that closes itself, and checks that turn the library's error codes into
// hotmesh::InputError naming the file and what was being read. Only io/src/cgns_*.cpp
// include this header; cgnslib.h stays out of hotmesh's public headers.
// The library keeps global state (open files, the last error, the file type to write): an
// open File holds a process-wide lock, so threads use it one at a time.
#pragma once

#include <cgnslib.h>

#include <filesystem>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace hotmesh::io::cgns {

/// An open CGNS file (HDF5 or ADF, as the library finds it); closed by the destructor.
class File {
 public:
  /// Opens `path` in `mode` (CG_MODE_READ, CG_MODE_MODIFY, or CG_MODE_WRITE: a new HDF5
  /// file); an InputError names the file if the library cannot open it as CGNS.
  File(const std::filesystem::path& path, int mode);
  ~File();
  File(const File&) = delete;
  File& operator=(const File&) = delete;

  int fn() const { return fn_; }
  const std::string& name() const { return name_; }
  /// Throws InputError "file: <what>: <library message>" if `status` is not CG_OK.
  void check(int status, std::string_view what) const;
  /// Closes the file now (the writers do, to see errors of the final flush).
  void close();

 private:
  std::unique_lock<std::recursive_mutex> lock_;
  std::string name_;
  int fn_ = -1;
};

/// A name as the library returns it (33 chars, NUL-terminated).
using Label = char[33];

/// The FamilyName_t child of the node cg_goto() last reached, or "" if it has none.
std::string family_name_here();
/// The FamilyName of BC `bc` of zone `zone` of base `base`, or "".
std::string bc_family(const File& file, int base, int zone, int bc);

}  // namespace hotmesh::io::cgns
