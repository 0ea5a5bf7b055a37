// hotmesh serve: one client connection, from its first byte to its close, under bounds that
// hold for the whole request head rather than for each read. A client that sends its request
// line and headers one byte at a time (slowloris) holds only its own connection, for at most
// ConnectionLimits::head_timeout, and never a worker: the head is read into a buffer before
// the request is handed to the HTTP library, which then reads it from that buffer.
// cpp-httplib stays inside http_connection.cpp and http_server.cpp.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>

namespace httplib {
class Stream;
}

namespace hotmesh::app::serve {

struct ConnectionLimits {
  /// The request line and every header must have arrived this long after the server started
  /// waiting for the request (connection accepted, or previous answer sent): else 408.
  std::chrono::milliseconds head_timeout{10'000};
  /// Request line and headers together, in bytes: above, 431.
  std::size_t max_head_bytes = 32 * 1024;
  /// A kept-alive connection with no byte of a next request for this long is closed.
  std::chrono::milliseconds idle_timeout{5'000};
  /// Each read of a body and each write of an answer.
  std::chrono::milliseconds io_timeout{10'000};
  /// Requests on one connection; the last answer says "Connection: close".
  std::size_t max_requests = 100;
};

/// Answers one request whose head is complete in `stream`: reads the rest, writes the answer.
/// `last`: the answer must close the connection; sets `close` when the request asked for it.
/// False when the connection cannot go on.
using RequestProcessor = std::function<bool(httplib::Stream& stream, bool last, bool& close)>;

/// Serves the requests of the connected socket `fd` one after another, then closes it. The
/// answers to a head too slow (408) or too large (431) are JSON errors like the API's; the
/// connection is closed after them. `stopping` is polled while waiting for a client, so that
/// a stopping server does not wait for slow clients.
void serve_connection(int fd, const ConnectionLimits& limits, const std::function<bool()>& stopping,
                      const RequestProcessor& process);

/// Called while a request is processed (on its thread): the connection is closed after the
/// answer, for example when the request was refused before its body was read.
void close_connection_after_answer();

}  // namespace hotmesh::app::serve
