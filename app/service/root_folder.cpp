// hotmesh serve: reading files below --root only (see root_folder.hpp).
#include "service/root_folder.hpp"

#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <system_error>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/core/text.hpp"
#include "service/api_error.hpp"

namespace hotmesh::app::serve {

namespace {

namespace fs = std::filesystem;

/// Closes a file descriptor on scope exit.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

/// openat2 with RESOLVE_BENEATH: the path may not leave `dir` by "..", an absolute path or a
/// symbolic link. -1 with errno ENOSYS where the kernel (or a sandbox) does not offer it.
int openat2_beneath(int dir, const char* relative, int flags) {
#ifdef SYS_openat2
  open_how how{};
  how.flags = static_cast<decltype(how.flags)>(static_cast<unsigned int>(flags));
  how.resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS;
  return static_cast<int>(::syscall(SYS_openat2, dir, relative, &how, sizeof how));
#else
  errno = ENOSYS;
  return -1;
#endif
}

/// Without openat2: each component opened below the previous one with O_NOFOLLOW, so no
/// symbolic link is followed at all (ELOOP for one).
int open_without_links(int dir, const fs::path& relative, int flags) {
  int current = ::dup(dir);
  for (auto it = relative.begin(); current >= 0 && it != relative.end(); ++it) {
    const bool last = std::next(it) == relative.end();
    const int part_flags = last ? flags | O_NOFOLLOW : O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC;
    const int next = ::openat(current, it->c_str(), part_flags);
    const int saved = errno;
    ::close(current);
    errno = saved;
    current = next;
  }
  return current;
}

}  // namespace

std::string lower_extension(std::string_view name) {
  const auto dot = name.rfind('.');
  const auto slash = name.find_last_of("/\\");
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return {};
  return ascii_lower(name.substr(dot));
}

RootFolder::RootFolder(const fs::path& root) {
  std::error_code error;
  path_ = fs::canonical(root, error);
  if (error || !fs::is_directory(path_, error)) {
    throw InputError(fmt::format("--root {}: not a folder ({})", root.string(),
                                 error ? error.message() : std::string("not a directory")));
  }
  fd_ = ::open(path_.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) throw InputError(fmt::format("--root {}: cannot open: {}", root.string(), std::strerror(errno)));
}

RootFolder::~RootFolder() {
  if (fd_ >= 0) ::close(fd_);
}

int RootFolder::open_beneath(const std::string& relative) const {
  constexpr int kFlags = O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK;
  const int fd = openat2_beneath(fd_, relative.c_str(), kFlags);
  if (fd >= 0 || (errno != ENOSYS && errno != EPERM)) return fd;
  return open_without_links(fd_, fs::path(relative), kFlags);
}

std::string RootFolder::read(std::string_view requested, std::size_t max_bytes) const {
  if (requested.empty()) throw ApiError::bad_request("path: empty");
  if (requested.find('\0') != std::string_view::npos) throw ApiError::bad_request("path: holds a NUL byte");
  fs::path path{std::string(requested)};
  for (const fs::path& part : path) {
    if (part == "..") throw ApiError::forbidden(fmt::format("path {}: '..' is not allowed; give a path inside the root", requested));
  }
  if (path.is_absolute()) {
    const fs::path normal = path.lexically_normal();
    const auto [end, _] = std::mismatch(path_.begin(), path_.end(), normal.begin(), normal.end());
    if (end != path_.end()) throw ApiError::forbidden(fmt::format("path {}: outside the root folder", requested));
    path = normal.lexically_relative(path_);
    if (path.empty() || path == ".") throw ApiError::bad_request(fmt::format("path {}: is the root folder itself", requested));
  }
  const std::string relative = path.lexically_normal().string();

  Descriptor file(open_beneath(relative));
  if (file.get() < 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR) throw ApiError::not_found(fmt::format("path {}: no such file in the root folder", requested));
    if (error == EXDEV || error == ELOOP) {
      throw ApiError::forbidden(fmt::format("path {}: a symbolic link leads out of the root folder", requested));
    }
    if (error == EACCES) throw ApiError::forbidden(fmt::format("path {}: permission denied", requested));
    throw ApiError::bad_request(fmt::format("path {}: cannot open: {}", requested, std::strerror(error)));
  }
  struct stat info {};
  if (::fstat(file.get(), &info) != 0 || !S_ISREG(info.st_mode)) {
    throw ApiError::bad_request(fmt::format("path {}: not a regular file", requested));
  }
  const auto size = static_cast<std::size_t>(info.st_size);
  if (size > max_bytes) {
    throw ApiError::too_large(fmt::format("path {}: {} bytes, more than the limit of {} bytes", requested, size, max_bytes));
  }
  std::string content(size, '\0');
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(file.get(), content.data() + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  content.resize(done);
  return content;
}

std::vector<RootFolder::Entry> RootFolder::list(const std::vector<std::string>& extensions, std::size_t limit,
                                                int depth) const {
  std::vector<Entry> entries;
  std::error_code error;
  fs::recursive_directory_iterator it(path_, fs::directory_options::skip_permission_denied, error);
  for (; !error && it != fs::recursive_directory_iterator() && entries.size() < limit; it.increment(error)) {
    const fs::directory_entry& entry = *it;
    const std::string name = entry.path().filename().string();
    if (name.starts_with(".") || entry.is_symlink(error)) {
      if (entry.is_directory(error)) it.disable_recursion_pending();
      continue;
    }
    if (entry.is_directory(error)) {
      if (it.depth() >= depth) it.disable_recursion_pending();
      continue;
    }
    if (!entry.is_regular_file(error)) continue;
    const std::string ext = lower_extension(name);
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) continue;
    entries.push_back({entry.path().lexically_relative(path_).generic_string(), entry.file_size(error)});
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.path < b.path; });
  return entries;
}

}  // namespace hotmesh::app::serve
