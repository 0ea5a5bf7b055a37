// hotmesh serve: the error every API route answers a bad request with. It carries the HTTP
// status (4xx: something in the request is wrong) and a message that names the field, file or
// limit and says what is wrong; the HTTP layer sends it as {"status", "error", "message"}.
#pragma once

#include <stdexcept>
#include <string>

namespace hotmesh::app::serve {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message, int retry_after = 0)
      : std::runtime_error(message), status_(status), retry_after_(retry_after) {}
  int status() const { return status_; }
  /// Seconds after which the client may try again (the Retry-After header); 0 for none.
  int retry_after() const { return retry_after_; }

  static ApiError bad_request(const std::string& message) { return {400, message}; }
  static ApiError forbidden(const std::string& message) { return {403, message}; }
  static ApiError not_found(const std::string& message) { return {404, message}; }
  static ApiError too_large(const std::string& message) { return {413, message}; }
  static ApiError unsupported_type(const std::string& message) { return {415, message}; }
  /// Well-formed, but the geometry cannot be made of it (faces not rotational, nodes off the
  /// curve, ...): hotmesh::InputError from the kernel.
  static ApiError unprocessable(const std::string& message) { return {422, message}; }
  /// The request is fine but the service has no room for it now (heavy_work.hpp).
  static ApiError busy(const std::string& message, int retry_after) { return {503, message, retry_after}; }

 private:
  int status_;
  int retry_after_;
};

/// The reason phrase of an HTTP status ("Bad Request", ...).
const char* status_reason(int status);

}  // namespace hotmesh::app::serve
