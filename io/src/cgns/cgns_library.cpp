// hotmesh io: the thin layer over the CGNS library (see cgns_library.hpp).
#include "cgns/cgns_library.hpp"

#include <cgns_io.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <system_error>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::cgns {

namespace {
std::recursive_mutex library_mutex;
/// Set in the child of check_in_child, whose only thread has the library to itself: the
/// mutex it inherits is held by a thread of the parent (that no longer exists there).
bool in_checking_child = false;
}  // namespace

std::unique_lock<std::recursive_mutex> library_lock() {
  if (in_checking_child) return {};
  return std::unique_lock<std::recursive_mutex>(library_mutex);
}

namespace {
/// A node's data type as cgio_get_data_type writes it: two characters and a NUL from HDF5,
/// but from a damaged ADF file the whole 32-character field, unterminated (fuzz_cgns).
using DataType = std::array<char, 64>;
bool get_data_type(int cgio, double id, DataType& type) {
  type.fill('\0');
  if (cgio_get_data_type(cgio, id, type.data()) != CGIO_ERR_NONE) return false;
  type[CGIO_MAX_DATATYPE_LENGTH] = '\0';
  return true;
}

/// A node's dimensions as cgio_get_dimensions writes them: at most CGIO_MAX_DIMENSIONS, but
/// room for as many as a damaged ADF file's two hexadecimal digits of a count can say.
using Dimensions = std::array<cgsize_t, 256>;

/// The bytes of one value of a node's data type ("I4", "R8", "C1", ...; "MT" and "LK" none).
std::int64_t value_bytes(std::string_view type) {
  if (type == "MT" || type == "LK") return 0;
  if (type == "C1" || type == "B1") return 1;
  if (type == "X8") return 16;
  if (type.size() == 2 && type[1] == '4') return type[0] == 'X' ? 8 : 4;
  return 8;
}

/// Walks the node tree below `id` (of cgio file `cgio`), not following links, and throws
/// InputError naming the first node whose declared data is larger than `limit` bytes, or that
/// lies deeper than kMaxDepth.
void check_declared_sizes(const std::string& file, int cgio, double id, const std::string& path, int depth,
                          std::int64_t limit, std::uintmax_t file_size) {
  constexpr int kMaxDepth = 64;  // a CGNS tree is about 8 deep
  if (depth > kMaxDepth) {
    throw InputError::in(file, fmt::format("node {} lies more than {} nodes deep: the file is damaged", path, kMaxDepth));
  }
  int link = 0;
  if (cgio_is_link(cgio, id, &link) == CGIO_ERR_NONE && link > 0) return;  // the library reads its target as a file
  DataType type{};
  int count = 0;
  Dimensions dimensions{};
  if (get_data_type(cgio, id, type) &&
      cgio_get_dimensions(cgio, id, &count, dimensions.data()) == CGIO_ERR_NONE && count > 0 &&
      count <= CGIO_MAX_DIMENSIONS) {
    std::int64_t bytes = value_bytes(type.data());
    for (int d = 0; d < count && bytes > 0; ++d) {
      const cgsize_t n = dimensions[static_cast<std::size_t>(d)];
      constexpr std::int64_t kMost = std::numeric_limits<std::int64_t>::max();
      bytes = n <= 0 ? 0 : (bytes > kMost / n ? kMost : bytes * n);  // saturated: 2^63 - 1 means "or more"
    }
    if (bytes > limit) {
      throw InputError::in(file, fmt::format("node {} declares {} values of type {} ({} bytes), more than a file of {} "
                                             "bytes can hold: the file is damaged",
                                             path, fmt::join(dimensions.begin(), dimensions.begin() + count, " x "),
                                             type.data(), bytes, file_size));
    }
  }
  int children = 0;
  if (cgio_number_children(cgio, id, &children) != CGIO_ERR_NONE || children <= 0) return;
  constexpr int kBatch = 64;
  std::array<double, kBatch> ids{};
  for (int start = 1; start <= children; start += kBatch) {
    int got = 0;
    if (cgio_children_ids(cgio, id, start, kBatch, &got, ids.data()) != CGIO_ERR_NONE) return;
    got = std::clamp(got, 0, kBatch);
    struct Release {  // the batch's ids, also when a child throws
      int cgio;
      const std::array<double, kBatch>& ids;
      int got;
      ~Release() {
        for (int k = 0; k < got; ++k) cgio_release_id(cgio, ids[static_cast<std::size_t>(k)]);
      }
    } release{cgio, ids, got};
    for (int k = 0; k < got; ++k) {
      char name[CGIO_MAX_NAME_LENGTH + 1] = {};
      if (cgio_get_name(cgio, ids[static_cast<std::size_t>(k)], name) != CGIO_ERR_NONE) name[0] = '?';
      check_declared_sizes(file, cgio, ids[static_cast<std::size_t>(k)], path + "/" + name, depth + 1, limit, file_size);
    }
    if (got < kBatch) return;
  }
}

/// Checks, before the library reads the file's tree into memory (cg_open reads every node but
/// the large arrays), that no node declares more data than the file can hold: the library
/// allocates what a node declares (one changed digit of an ADF dimension asked for 512 MB in
/// the fuzz runs) and only then finds the data missing. An ADF file stores its data as it is;
/// HDF5 data may be compressed (deflate: at most 1032 to 1), hence its margin.
void check_declared_sizes(const std::string& file) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error) return;  // cg_open says why it cannot read it
  int cgio = 0;
  if (cgio_open_file(file.c_str(), CGIO_MODE_READ, CGIO_FILE_NONE, &cgio) != CGIO_ERR_NONE) return;  // likewise
  struct Close {
    int cgio;
    ~Close() { cgio_close_file(cgio); }
  } close{cgio};
  int type = CGIO_FILE_NONE;
  if (cgio_get_file_type(cgio, &type) != CGIO_ERR_NONE) return;
  const auto bytes = static_cast<std::int64_t>(size);
  const std::int64_t limit = type == CGIO_FILE_ADF || type == CGIO_FILE_ADF2 ? bytes : 1032 * bytes + (std::int64_t{1} << 20);
  double root = 0;
  if (cgio_get_root_id(cgio, &root) != CGIO_ERR_NONE) return;
  check_declared_sizes(file, cgio, root, "", 0, limit, size);
}
}  // namespace

File::File(const std::filesystem::path& path, int mode) : lock_(library_lock()), name_(path.string()) {
  if (mode == CG_MODE_WRITE) cg_set_file_type(CG_FILE_HDF5);
  if (mode == CG_MODE_READ || mode == CG_MODE_MODIFY) {
    require_input_file(path);
    int file_type = CG_FILE_NONE;
    if (cg_is_cgns(name_.c_str(), &file_type) != CG_OK) {
      throw InputError::in(name_, "not a CGNS file (neither HDF5 nor ADF, or no CGNSLibraryVersion node)");
    }
    check_declared_sizes(name_);
  }
  int fn = 0;
  if (cg_open(name_.c_str(), mode, &fn) != CG_OK) {
    const std::string message = std::string("cannot open the CGNS file: ") + cg_get_error();
    // The library numbers the file before it reads the file's tree, and keeps it open when
    // that fails (a descriptor and the nodes read so far, each time: fuzz_cgns ran out of
    // descriptors); closing the number frees them.
    if (fn > 0) cg_close(fn);
    throw InputError::in(name_, message);
  }
  fn_ = fn;
}

File::~File() {
  if (fn_ >= 0) cg_close(fn_);
}

void File::close() {
  const int fn = fn_;
  fn_ = -1;
  if (cg_close(fn) != CG_OK) throw InputError::in(name_, std::string("cannot close the CGNS file: ") + cg_get_error());
}

void File::check(int status, std::string_view what) const {
  if (status == CG_OK) return;
  std::string message(what);
  message.append(": ").append(cg_get_error());
  throw InputError::in(name_, message);
}

void check_in_child(const std::string& file, const std::function<void()>& read) {
  // The child's refusal, its InputError's text, comes back through a pipe: the parent then
  // refuses the file without running the library on it (the library's faults on damaged files
  // are not all crashes: some only overwrite its heap, fuzz_cgns).
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe");
  // Held across the fork: no other thread is inside the library when the child copies it.
  const std::unique_lock<std::recursive_mutex> lock = library_lock();
  const pid_t child = ::fork();
  if (child < 0) {
    const int error = errno;
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    throw std::system_error(error, std::generic_category(), "fork, to read " + file + " in a child process");
  }
  if (child == 0) {
    ::close(pipe_fds[0]);
    in_checking_child = true;
    spdlog::default_logger_raw()->set_level(spdlog::level::off);  // the parent warns, when it reads the file again
    int code = 0;
    try {
      read();
    } catch (const InputError& e) {
      const std::string_view message = e.what();
      for (std::size_t at = 0; at < message.size();) {
        const ssize_t n = ::write(pipe_fds[1], message.data() + at, message.size() - at);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        at += static_cast<std::size_t>(n);
      }
      code = 1;
    } catch (...) {  // anything else: the parent reads the file again and meets it itself
    }
    ::_exit(code);
  }
  ::close(pipe_fds[1]);
  std::string message;
  for (;;) {
    char buffer[4096];
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    if (message.size() < 256 * 1024) message.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) throw std::system_error(errno, std::generic_category(), "waitpid");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 1 && !message.empty()) throw InputError(message);
  const std::string how = WIFSIGNALED(status)
                              ? fmt::format("signal {}, {}", WTERMSIG(status), ::strsignal(WTERMSIG(status)))
                              : fmt::format("exit code {}", WEXITSTATUS(status));
  throw InputError::in(file, fmt::format("the CGNS library (or HDF5 beneath it) crashed reading it ({}): the file is "
                                         "damaged, or not one the library can read",
                                         how));
}

std::int64_t StoredArray::values() const {
  if (dimensions.empty()) return 0;
  std::int64_t n = 1;
  for (const cgsize_t d : dimensions) {
    if (d <= 0) return 0;
    if (n > std::numeric_limits<std::int64_t>::max() / d) return std::numeric_limits<std::int64_t>::max();
    n *= d;
  }
  return n;
}

std::string StoredArray::shape() const {
  if (dimensions.empty()) return "no";
  return fmt::format("{}", fmt::join(dimensions, " x "));
}

namespace {
/// The library's handle of the file for the node-level (cgio) calls.
int cgio_of(const File& file) {
  int cgio = 0;
  file.check(cg_get_cgio(file.fn(), &cgio), "reading the file's nodes");
  return cgio;
}
}  // namespace

std::optional<StoredArray> stored_array(const File& file, double parent, const std::string& path) {
  const int cgio = cgio_of(file);
  double id = parent;
  if (!path.empty() && cgio_get_node_id(cgio, parent, path.c_str(), &id) != CGIO_ERR_NONE) return std::nullopt;
  StoredArray stored;
  DataType type{};
  int count = 0;
  Dimensions dimensions{};
  const bool ok = get_data_type(cgio, id, type) &&
                  cgio_get_dimensions(cgio, id, &count, dimensions.data()) == CGIO_ERR_NONE && count >= 0 &&
                  count <= CGIO_MAX_DIMENSIONS;
  if (!path.empty()) cgio_release_id(cgio, id);
  if (!ok) return std::nullopt;
  stored.type = type.data();
  stored.dimensions.assign(dimensions.begin(), dimensions.begin() + count);
  return stored;
}

void check_point_set(const File& file, double parent, const char* name, int index_dimension, std::int64_t points,
                     std::string_view where) {
  const std::optional<StoredArray> stored = stored_array(file, parent, name);
  if (!stored) throw InputError::in(file.name(), fmt::format("{}: its {} cannot be read", where, name));
  const bool integers = stored->type == "I4" || stored->type == "I8";
  const std::vector<cgsize_t> expected{index_dimension, static_cast<cgsize_t>(points)};
  if (!integers || stored->dimensions != expected) {
    throw InputError::in(file.name(), fmt::format("{}: its {} stores {} values of type {}, where {} x {} integers are "
                                                  "expected ({} per point of the zone, {} points)",
                                                  where, name, stored->shape(), stored->type, index_dimension, points,
                                                  index_dimension, points));
  }
}

OneToOne read_one_to_one(const File& file, int base, int zone, int connection, int index_dimension,
                         std::string_view zone_name) {
  OneToOne c;
  double id = 0;
  file.check(cg_1to1_id(file.fn(), base, zone, connection, &id),
             fmt::format("zone '{}': reading 1-to-1 connection {}", zone_name, connection));
  Label name{};
  if (cgio_get_name(cgio_of(file), id, name) != CGIO_ERR_NONE) name[0] = '\0';
  const std::string where = fmt::format("zone '{}' connection '{}'", zone_name, name);
  check_point_set(file, id, "PointRange", index_dimension, 2, where);
  check_point_set(file, id, "PointRangeDonor", index_dimension, 2, where);
  Label donor{};
  file.check(cg_1to1_read(file.fn(), base, zone, connection, name, donor, c.range.data(), c.donor_range.data(),
                          c.transform.data()),
             fmt::format("zone '{}': reading 1-to-1 connection {}", zone_name, connection));
  c.name = name;
  c.donor = donor;
  return c;
}

std::string family_name_here() {
  Label family{};
  if (cg_famname_read(family) != CG_OK) return {};  // CG_NODE_NOT_FOUND: no family
  return family;
}

std::string bc_family(const File& file, int base, int zone, int bc) {
  if (cg_goto(file.fn(), base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", bc, "end") != CG_OK) return {};
  return family_name_here();
}

}  // namespace hotmesh::io::cgns
