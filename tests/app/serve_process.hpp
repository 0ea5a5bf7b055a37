// hotmesh tests: `hotmesh serve` as a child process on a free loopback port, and HTTP clients
// for it. The server is started with --port 0 and the port read from the line it prints; its
// stderr goes to a log file that failed tests show. stop() sends a signal and returns the exit
// code, so tests see a clean shutdown (and, in the sanitizer build, a leak-free one).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace hotmesh::test {

class ServeProcess {
 public:
  /// Starts `hotmesh serve --port 0` with `arguments`; `environment` entries are set in the
  /// child (e.g. TMPDIR). Throws std::runtime_error if it does not listen within 30 s.
  explicit ServeProcess(const std::vector<std::string>& arguments = {},
                        const std::map<std::string, std::string>& environment = {});
  ServeProcess(const ServeProcess&) = delete;
  ServeProcess& operator=(const ServeProcess&) = delete;
  ~ServeProcess();

  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  /// The server's stderr so far.
  std::string log() const;
  /// Resident memory of the server, from /proc/<pid>/status (VmRSS), in KiB.
  long rss_kib() const;
  bool running() const;

  /// Sends `signal`, waits (up to 30 s, then SIGKILL) and returns the exit code, or 128 +
  /// the signal that ended it.
  int stop(int signal);

 private:
  pid_t pid_ = -1;
  int port_ = 0;
  int stdout_fd_ = -1;
  std::filesystem::path log_;
  int exit_code_ = -1;
};

}  // namespace hotmesh::test
