// hotmesh serve: the HTTP/1.1 front of the geometry service (cpp-httplib): the JSON API under
// /api/ (docs/service.md) and the inspection page at /. Every error is a JSON body {"status",
// "error", "message"}; bodies above the limit get 413. Each connection has a thread of its own
// that waits on the client under whole-head bounds (http_connection.hpp); the work of at most
// `threads` requests runs at once, of them at most `heavy_requests` heavy ones (heavy_work.hpp).
// Requests whose Host or Origin is not the service's are refused (host_policy.hpp). cpp-httplib stays inside http_server.cpp and http_connection.cpp.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "service/service.hpp"

namespace hotmesh::app::serve {

struct HttpOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;          ///< 0: any free port (bind() tells which)
  std::size_t threads = 8;       ///< requests worked on at once
  std::size_t connections = 64;  ///< connections served at once (one thread each, mostly waiting)
  std::chrono::milliseconds head_timeout{10'000};  ///< for a request line and its headers
  std::vector<std::string> allowed_hosts;          ///< names besides the machine's (--allow-host)
  std::size_t heavy_requests = 2;  ///< heavy requests computed at once (heavy_work.hpp)
  std::size_t heavy_queue = 8;     ///< heavy requests waiting for them; more get 503
};

class HttpServer {
 public:
  HttpServer(GeometryService& service, HttpOptions options);
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;
  ~HttpServer();

  /// Binds the listening socket and returns its port. Throws hotmesh::InputError if it cannot
  /// (address in use, not an address of this machine, ...) or an allowed host is malformed.
  int bind();
  /// The HOST:PORT values of the Host header the server answers to (once bound).
  std::vector<std::string> hosts() const;
  /// Serves until stop(); false if the listener failed.
  bool run();
  /// Stops listening and lets the workers finish their requests; callable from any thread.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hotmesh::app::serve
