// hotmesh serve: the HTTP/1.1 front of the geometry service (cpp-httplib, a pool of worker
// threads): the JSON API under /api/ (docs/service.md) and the inspection page at /. Every
// error is a JSON body {"status", "error", "message"}; bodies above the limit get 413.
// cpp-httplib stays inside http_server.cpp.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "serve/service.hpp"

namespace hotmesh::app::serve {

struct HttpOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;          ///< 0: any free port (bind() tells which)
  std::size_t threads = 8;  ///< worker threads, each serving one connection at a time
};

class HttpServer {
 public:
  HttpServer(GeometryService& service, HttpOptions options);
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;
  ~HttpServer();

  /// Binds the listening socket and returns its port. Throws hotmesh::InputError if it cannot
  /// (address in use, not an address of this machine, ...).
  int bind();
  /// Serves until stop(); false if the listener failed.
  bool run();
  /// Stops listening and lets the workers finish their requests; callable from any thread.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hotmesh::app::serve
