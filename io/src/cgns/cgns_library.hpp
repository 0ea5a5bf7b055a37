// hotmesh io (private): the CGNS mid-level library (cgnslib.h) behind a thin layer: an open
// file that closes itself, and checks that turn the library's error codes into
// hotmesh::InputError naming the file and what was being read. Only io/src/cgns_*.cpp
// include this header; cgnslib.h stays out of hotmesh's public headers.
// The library keeps global state (open files, the last error, the file type to write): an
// open File holds a process-wide lock, so threads use it one at a time.
//
// The library trusts the file's counts. Its reads of an array (a point set, a section's
// connectivity and offsets) copy the whole array the file stores into the caller's buffer,
// whatever the counts it reported elsewhere say; and damaged HDF5 metadata can make it, or
// HDF5, fault. So the readers check what a node stores (stored_array) before they size a
// buffer for a library read, and read_cgns and describe_cgns read an untrusted file in a child
// process first (check_in_child).
#pragma once

#include <cgnslib.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hotmesh::io::cgns {

/// The process-wide lock on the library's global state (File holds it while open); the
/// node-level calls (cgns_io.h) share that state and take it too.
std::unique_lock<std::recursive_mutex> library_lock();

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

/// Runs `read` (which reads `file` with the library) in a child process first, with the
/// library to itself. Returns when the child read the file (the caller then reads it again);
/// throws the child's InputError when it refused the file, and InputError naming `file` when
/// it died instead (a fault inside the CGNS or HDF5 library on a damaged file: SIGSEGV,
/// SIGABRT, or under a sanitizer its report). So the caller's process runs the library only
/// on files the child read.
void check_in_child(const std::string& file, const std::function<void()>& read);

/// An array a node of the file stores, as the file declares it: what a library read of the
/// node copies into the caller's buffer.
struct StoredArray {
  std::string type;                 ///< "I4", "I8", "R4", "R8", "C1", "MT" (no data), ...
  std::vector<cgsize_t> dimensions;
  /// The number of values: the product of the dimensions (0 without data), saturated at
  /// INT64_MAX.
  std::int64_t values() const;
  /// "3 x 2"
  std::string shape() const;
};
/// The array stored at node `path` below node `parent` (a child's name, or names joined by
/// '/'; "" for `parent` itself), or nullopt if there is no such node.
std::optional<StoredArray> stored_array(const File& file, double parent, const std::string& path);

/// Checks point set `name` (PointRange, PointList, PointRangeDonor, ...) of node `parent`
/// before the library reads it into a buffer of index_dimension x points values: the file
/// must store exactly that, as integers. Throws InputError "file: <where>: its <name> stores
/// ..." otherwise.
void check_point_set(const File& file, double parent, const char* name, int index_dimension, std::int64_t points,
                     std::string_view where);

/// A GridConnectivity1to1_t as cg_1to1_read gives it, its two ranges checked to be stored as
/// ranges of `index_dimension` (the zone's) first.
struct OneToOne {
  std::string name, donor;
  std::array<cgsize_t, 6> range{}, donor_range{};
  std::array<int, 3> transform{};
};
OneToOne read_one_to_one(const File& file, int base, int zone, int connection, int index_dimension,
                         std::string_view zone_name);

/// The FamilyName_t child of the node cg_goto() last reached, or "" if it has none.
std::string family_name_here();
/// The FamilyName of BC `bc` of zone `zone` of base `base`, or "".
std::string bc_family(const File& file, int base, int zone, int bc);

}  // namespace hotmesh::io::cgns
