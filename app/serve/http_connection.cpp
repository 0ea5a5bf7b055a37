// hotmesh serve: one client connection under whole-head bounds (see http_connection.hpp).
#include "serve/http_connection.hpp"

#include <httplib.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>

#include "service/api_error.hpp"
#include "service/json_fields.hpp"

namespace hotmesh::app::serve {

namespace {

using Clock = std::chrono::steady_clock;

thread_local bool t_close_after_answer = false;

/// Longest single wait, so that a stopping server is noticed while a client is slow.
constexpr std::chrono::milliseconds kPollSlice{200};
constexpr std::size_t kReadChunk = 4096;

/// What the connection has received and not yet handed on: `bytes` from `offset`.
struct Received {
  std::string bytes;
  std::size_t offset = 0;

  std::string_view unread() const { return std::string_view(bytes).substr(offset); }
  void consume(std::size_t n) {
    offset += n;
    if (offset == bytes.size()) {
      bytes.clear();
      offset = 0;
    }
  }
};

/// Waits up to `timeout` for `events` on `fd`; true if they came.
bool wait_for(int fd, short events, std::chrono::milliseconds timeout) {
  pollfd p{fd, events, 0};
  int n = 0;
  do {
    n = ::poll(&p, 1, static_cast<int>(std::max<long long>(timeout.count(), 0)));
  } while (n < 0 && errno == EINTR);
  return n > 0;
}

/// Appends up to `limit` bytes read from `fd` to `in`; the count read, 0 at the end of the
/// stream, < 0 on error (EINTR and EAGAIN come back as -1 with errno set).
ssize_t receive(int fd, Received& in, std::size_t limit) {
  const std::size_t old = in.bytes.size();
  in.bytes.resize(old + limit);
  const ssize_t n = ::recv(fd, in.bytes.data() + old, limit, 0);
  in.bytes.resize(old + static_cast<std::size_t>(std::max<ssize_t>(n, 0)));
  return n;
}

/// The connection as cpp-httplib reads and writes it: first what was received already (the
/// head, perhaps the start of the body), then the socket, each read and write bounded by
/// `io_timeout`.
class ConnectionStream final : public httplib::Stream {
 public:
  ConnectionStream(int fd, Received& received, std::chrono::milliseconds io_timeout)
      : fd_(fd), received_(received), io_timeout_(io_timeout) {}

  bool is_readable() const override { return !received_.unread().empty() || wait_for(fd_, POLLIN, io_timeout_); }
  bool is_writable() const override { return wait_for(fd_, POLLOUT, io_timeout_); }

  ssize_t read(char* ptr, std::size_t size) override {
    if (received_.unread().empty()) {
      if (!wait_for(fd_, POLLIN, io_timeout_)) return -1;
      if (size >= kReadChunk) return retrying([&] { return ::recv(fd_, ptr, size, 0); });
      const ssize_t n = retrying([&] { return receive(fd_, received_, kReadChunk); });
      if (n <= 0) return n;
    }
    const std::string_view unread = received_.unread();
    const std::size_t n = std::min(size, unread.size());
    std::memcpy(ptr, unread.data(), n);
    received_.consume(n);
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, std::size_t size) override {
    if (!is_writable()) return -1;
    return retrying([&] { return ::send(fd_, ptr, size, MSG_NOSIGNAL); });
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override { address_of(::getpeername, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address_of(::getsockname, ip, port); }
  int socket() const override { return fd_; }

 private:
  template <class Call>
  static ssize_t retrying(Call call) {
    ssize_t n = 0;
    do {
      n = call();
    } while (n < 0 && errno == EINTR);
    return n;
  }

  template <class Query>
  void address_of(Query query, std::string& ip, int& port) const {
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    char host[NI_MAXHOST] = "";
    char service[NI_MAXSERV] = "";
    if (query(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0 ||
        ::getnameinfo(reinterpret_cast<sockaddr*>(&address), length, host, sizeof host, service, sizeof service,
                      NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
      return;
    }
    ip = host;
    port = std::atoi(service);
  }

  int fd_;
  Received& received_;
  std::chrono::milliseconds io_timeout_;
};

enum class Head { complete, closed, idle, too_slow, too_large, stopping };

/// Reads until `received` holds a whole request head (up to the blank line), within the
/// limits, counting from `start`.
Head read_head(int fd, Received& received, const ConnectionLimits& limits, Clock::time_point start,
               const std::function<bool()>& stopping) {
  static constexpr std::string_view kEnd = "\r\n\r\n";
  std::size_t searched = 0;  // bytes of the unread part already searched for kEnd
  for (;;) {
    const std::string_view unread = received.unread();
    const std::size_t end = unread.find(kEnd, searched);
    if (end != std::string_view::npos) {
      return end + kEnd.size() <= limits.max_head_bytes ? Head::complete : Head::too_large;
    }
    if (unread.size() > limits.max_head_bytes) return Head::too_large;
    searched = unread.size() >= kEnd.size() ? unread.size() - (kEnd.size() - 1) : 0;

    const bool waiting = unread.empty();  // for the first byte of the request
    const Clock::time_point deadline = start + (waiting ? std::min(limits.idle_timeout, limits.head_timeout)
                                                        : limits.head_timeout);
    const Clock::time_point now = Clock::now();
    if (now >= deadline) return waiting ? Head::idle : Head::too_slow;
    if (stopping()) return Head::stopping;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now) + std::chrono::milliseconds(1);
    if (!wait_for(fd, POLLIN, std::min(left, kPollSlice))) continue;
    const ssize_t n = receive(fd, received, std::min(kReadChunk, limits.max_head_bytes + 1 - unread.size()));
    if (n == 0) return Head::closed;
    if (n < 0 && errno != EINTR && errno != EAGAIN) return Head::closed;
  }
}

/// A JSON error answer that closes the connection, sent without waiting on the client.
void refuse(int fd, int status, const std::string& message) {
  const std::string body =
      Json{{"status", status}, {"error", status_reason(status)}, {"message", message}}.dump();
  const std::string answer = fmt::format(
      "HTTP/1.1 {} {}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n"
      "X-Content-Type-Options: nosniff\r\nCache-Control: no-store\r\n\r\n{}",
      status, status_reason(status), body.size(), body);
  [[maybe_unused]] const ssize_t ignored = ::send(fd, answer.data(), answer.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
}

/// Closes a connection whose client may still be sending (a refused request's body, headers
/// above the bound): reads and drops what comes for up to a second, so that the client, done
/// sending, reads the answer rather than a reset (closing with unread data resets).
void close_lingering(int fd) {
  ::shutdown(fd, SHUT_WR);
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(1);
  char buffer[16 * 1024];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0 || !wait_for(fd, POLLIN, left) || ::recv(fd, buffer, sizeof buffer, 0) <= 0) break;
  }
}

}  // namespace

void close_connection_after_answer() { t_close_after_answer = true; }

void serve_connection(int fd, const ConnectionLimits& limits, const std::function<bool()>& stopping,
                      const RequestProcessor& process) {
  Received received;
  bool unread = false;  // the client may still be sending: close lingering
  for (std::size_t left = limits.max_requests; left > 0; --left) {
    const Head head = read_head(fd, received, limits, Clock::now(), stopping);
    if (head == Head::too_slow) {
      refuse(fd, 408,
             fmt::format("the request line and headers took longer than {} s to arrive",
                         std::chrono::duration<double>(limits.head_timeout).count()));
    } else if (head == Head::too_large) {
      refuse(fd, 431, fmt::format("the request line and headers are larger than {} bytes", limits.max_head_bytes));
      unread = true;
    }
    if (head != Head::complete) break;
    ConnectionStream stream(fd, received, limits.io_timeout);
    bool close = false;
    t_close_after_answer = false;
    const bool ok = process(stream, left == 1, close);
    unread = t_close_after_answer;
    if (!ok || close || t_close_after_answer) break;
  }
  if (unread) close_lingering(fd);
  ::shutdown(fd, SHUT_RDWR);
  ::close(fd);
}

}  // namespace hotmesh::app::serve
