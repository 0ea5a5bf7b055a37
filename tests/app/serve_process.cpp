// hotmesh tests: `hotmesh serve` as a child process (see serve_process.hpp).
#include "serve_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace hotmesh::test {

namespace {

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

}  // namespace

ServeProcess::ServeProcess(const std::vector<std::string>& arguments,
                           const std::map<std::string, std::string>& environment) {
  static int counter = 0;
  log_ = std::filesystem::temp_directory_path() /
         ("hotmesh-serve-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".log");
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  std::vector<std::string> argv_text{HOTMESH_EXE, "serve", "--port", "0"};
  argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    ::dup2(pipe_fds[1], STDOUT_FILENO);
    const int log = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (log >= 0) ::dup2(log, STDERR_FILENO);
    for (const auto& [key, value] : environment) ::setenv(key.c_str(), value.c_str(), 1);
    std::vector<char*> argv;
    for (auto& word : argv_text) argv.push_back(word.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  stdout_fd_ = pipe_fds[0];

  // The first line: "hotmesh serve: listening on http://127.0.0.1:PORT/".
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (line.find('\n') == std::string::npos) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{stdout_fd_, POLLIN, 0};
    if (left.count() <= 0 || ::poll(&p, 1, static_cast<int>(left.count())) <= 0) {
      stop(SIGKILL);
      throw std::runtime_error("hotmesh serve did not start listening in 30 s; log:\n" + log());
    }
    char buffer[256];
    const ssize_t n = ::read(stdout_fd_, buffer, sizeof buffer);
    if (n <= 0) {
      stop(SIGKILL);
      throw std::runtime_error("hotmesh serve exited before listening; log:\n" + log());
    }
    line.append(buffer, static_cast<std::size_t>(n));
  }
  const auto at = line.find("listening on http://");
  const auto slash = line.find('/', at == std::string::npos ? 0 : at + 20);
  const auto colon = line.rfind(':', slash);
  if (at == std::string::npos || slash == std::string::npos || colon == std::string::npos || colon < at + 20) {
    stop(SIGKILL);
    throw std::runtime_error("unexpected first line of hotmesh serve: " + line);
  }
  port_ = std::stoi(line.substr(colon + 1, slash - colon - 1));
}

ServeProcess::~ServeProcess() {
  if (running()) stop(SIGKILL);
  if (stdout_fd_ >= 0) ::close(stdout_fd_);
  std::error_code ignored;
  std::filesystem::remove(log_, ignored);
}

std::string ServeProcess::log() const {
  std::ifstream in(log_);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

long ServeProcess::rss_kib() const {
  std::ifstream in("/proc/" + std::to_string(pid_) + "/status");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

bool ServeProcess::running() const { return pid_ > 0 && exit_code_ < 0; }

int ServeProcess::stop(int signal) {
  if (!running()) return exit_code_;
  ::kill(pid_, signal);
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (::waitpid(pid_, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  exit_code_ = exit_code_of(status);
  return exit_code_;
}

}  // namespace hotmesh::test
