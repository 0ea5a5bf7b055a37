#include "hotmesh/io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <algorithm>
#include <string>
#include <system_error>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io {
namespace {

std::filesystem::path temporary_beside(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = target;
  tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return tmp;
}

void sync_to_disk(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_beside(target_)) {
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    throw InputError::in(target_.string(), std::string("cannot create output file: ") + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::commit() {
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  if (!written || out_.fail()) {
    throw InputError::in(target_.string(), "could not write the output file (disk full?)");
  }
  sync_to_disk(temporary_);
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) throw InputError::in(target_.string(), "cannot replace the output file: " + ec.message());
  committed_ = true;
}

AtomicPath::AtomicPath(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_beside(target_)) {}

AtomicPath::~AtomicPath() {
  if (committed_) return;
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicPath::commit() {
  sync_to_disk(temporary_);
  std::error_code ec;
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) throw InputError::in(target_.string(), "cannot replace the output file: " + ec.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& target, std::string_view content) {
  AtomicFile file(target);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

namespace {

/// A temporary file `file` of the output `name` whose writer no longer runs.
bool stale_temporary_of(const std::string& file, const std::string& name) {
  const std::string prefix = name + ".tmp-";
  if (file.rfind(prefix, 0) != 0) return false;
  const std::string rest = file.substr(prefix.size());
  const auto dash = rest.find('-');
  if (dash == 0 || dash > 9 || dash == std::string::npos || rest.find_first_not_of("0123456789-") != std::string::npos) {
    return false;
  }
  const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dash)));
  const bool alive = pid == ::getpid() || ::kill(pid, 0) == 0 || errno == EPERM;
  return !alive;
}

}  // namespace

void remove_stale_temporaries(const std::filesystem::path& folder, std::span<const std::string> names) {
  for (const auto& name : names) {  // a name may be in a subfolder ("polyMesh/points")
    const std::filesystem::path output = folder / name;
    const std::string file_name = output.filename().string();
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(output.parent_path(), ec)) {
      if (!stale_temporary_of(entry.path().filename().string(), file_name)) continue;
      std::error_code ignored;
      std::filesystem::remove(entry.path(), ignored);
    }
  }
}

std::string read_file(const std::filesystem::path& path) {
  require_input_file(path);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError::in(path.string(), std::string("cannot open: ") + std::strerror(errno));
  const std::streamoff size = in.tellg();
  std::string content(static_cast<std::size_t>(std::max<std::streamoff>(size, 0)), '\0');
  in.seekg(0);
  in.read(content.data(), static_cast<std::streamsize>(content.size()));
  if (in.gcount() != static_cast<std::streamsize>(content.size())) {
    throw InputError::in(path.string(), "read error");
  }
  return content;
}

}  // namespace hotmesh::io
