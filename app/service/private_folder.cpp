// hotmesh serve: the private folder for uploads (see private_folder.hpp).
#include "service/private_folder.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"
#include "service/api_error.hpp"

namespace hotmesh::app::serve {

PrivateFolder::PrivateFolder() {
  std::error_code error;
  std::filesystem::path base = std::filesystem::temp_directory_path(error);
  if (error) base = "/tmp";
  std::string pattern = (base / "hotmesh-serve-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw InputError(fmt::format("cannot make a private folder for uploads under {}: {}", base.string(),
                                 std::strerror(errno)));
  }
  path_ = pattern;
}

PrivateFolder::~PrivateFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

PrivateFile PrivateFolder::write(std::string_view extension, std::string_view content) {
  const std::filesystem::path file = path_ / fmt::format("upload-{}{}", ++count_, extension);
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, S_IRUSR | S_IWUSR);
  if (fd < 0) throw ApiError(507, fmt::format("cannot store the upload: {}", std::strerror(errno)));
  PrivateFile stored(file);
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  const bool written = done == content.size();
  const bool closed = ::close(fd) == 0;
  if (!written || !closed) throw ApiError(507, "cannot store the upload: the disk is full or not writable");
  return stored;
}

}  // namespace hotmesh::app::serve
