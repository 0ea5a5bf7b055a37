// hotmesh serve: reading a CAD file in a child process first (cad_check.hpp).
#include "service/cad_check.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "hotmesh/core/input_error.hpp"

extern char** environ;

namespace hotmesh::app::serve {
namespace {

/// The child's stderr, at most this much (one message naming the file).
constexpr std::size_t kMaxMessage = 64 * 1024;

/// Closes a descriptor when it goes.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

/// The child's message: from its line that starts "error " (without that word) to the end of
/// its continuation lines (a list of the file's problems, each indented).
std::string error_message(const std::string& output) {
  std::string message;
  bool inside = false;
  for (std::size_t start = 0; start < output.size();) {
    const std::size_t end = std::min(output.find('\n', start), output.size());
    const std::string_view line(output.data() + start, end - start);
    if (!inside && line.starts_with("error ")) {
      message = line.substr(6);
      inside = true;
    } else if (inside && line.starts_with("  ")) {
      message.append("\n").append(line);
    } else if (inside) {
      break;
    }
    start = end + 1;
  }
  return message;
}

}  // namespace

void check_cad_in_child(const CadCheck& check, const std::filesystem::path& file, geometry::LengthUnit unit) {
  if (check.hotmesh.empty()) return;
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe");
  Descriptor read_end{pipe_fds[0]};
  Descriptor write_end{pipe_fds[1]};

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, write_end.fd, STDERR_FILENO);
  // The service blocks SIGINT and SIGTERM in every thread (it waits for them): not the child.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);

  const std::string exe = check.hotmesh.string();
  const std::string path = file.string();
  std::vector<std::string> words{exe, "-q", "cad", path, "--unit", geometry::to_string(unit)};
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  pid_t child = -1;
  const int spawned = ::posix_spawn(&child, exe.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) throw std::system_error(spawned, std::generic_category(), "cannot start " + exe);
  ::close(write_end.fd);
  write_end.fd = -1;

  // Its message, until it ends or the time is up.
  std::string output;
  const auto deadline = std::chrono::steady_clock::now() + check.time_limit;
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd wait{read_end.fd, POLLIN, 0};
    const int ready = ::poll(&wait, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    char buffer[4096];
    const ssize_t n = ::read(read_end.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the child has ended (or closed its stderr)
    if (output.size() < kMaxMessage) output.append(buffer, static_cast<std::size_t>(n));
  }
  if (timed_out) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) {
    throw InputError::in(path, "reading it took longer than " + std::to_string(check.time_limit.count()) +
                                   " s: is it the boundary of a part, or a whole assembly?");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  // The child's own message names the file and what is wrong; a sanitizer's report of what
  // OpenCASCADE abandoned may follow it and is not the user's business.
  const std::string message = error_message(output);
  if (!message.empty()) throw InputError(message);
  throw InputError::in(path, WIFSIGNALED(status)
                                 ? "OpenCASCADE's reader crashed on it (signal " + std::to_string(WTERMSIG(status)) + ")"
                                 : "it cannot be read (the reading process ended with code " +
                                       std::to_string(WEXITSTATUS(status)) + ")");
}

}  // namespace hotmesh::app::serve
