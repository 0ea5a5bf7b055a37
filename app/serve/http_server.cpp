// hotmesh serve: routes of the HTTP API and the page, on cpp-httplib (see http_server.hpp and
// docs/service.md). Handlers only translate: the body to JSON, GeometryService's answer or
// error to a response.
#include "serve/http_server.hpp"

#include <httplib.h>
#include <sys/socket.h>
#include <spdlog/spdlog.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <exception>
#include <iterator>
#include <new>
#include <optional>
#include <semaphore>
#include <string_view>
#include <utility>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/core/text.hpp"
#include "service/api_error.hpp"
#include "serve/heavy_work.hpp"
#include "serve/host_policy.hpp"
#include "serve/http_connection.hpp"
#include "serve/web_assets.hpp"

namespace hotmesh::app::serve {

const char* status_reason(int status) {
  switch (status) {
    case 200: return "OK";
    case 201: return "Created";
    case 204: return "No Content";
    case 400: return "Bad Request";
    case 403: return "Forbidden";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 408: return "Request Timeout";
    case 413: return "Payload Too Large";
    case 414: return "URI Too Long";
    case 415: return "Unsupported Media Type";
    case 422: return "Unprocessable Entity";
    case 431: return "Request Header Fields Too Large";
    case 500: return "Internal Server Error";
    case 503: return "Service Unavailable";
    case 507: return "Insufficient Storage";
    default: return status < 500 ? "Client Error" : "Server Error";
  }
}

namespace {

using httplib::Request;
using httplib::Response;

/// JSON text; invalid UTF-8 (which a client may send in names) is replaced, never thrown on.
std::string json_text(const Json& value) { return value.dump(-1, ' ', false, Json::error_handler_t::replace); }

void send_json(Response& res, int status, const Json& body) {
  res.status = status;
  res.set_content(json_text(body), "application/json");
}

/// A file as an attachment under its own name.
void send_download(Response& res, Download file) {
  res.set_header("Content-Disposition", fmt::format("attachment; filename=\"{}\"", file.filename));
  res.status = 200;
  res.set_content(std::move(file.content), file.content_type.c_str());
}

void send_error(Response& res, int status, const std::string& message) {
  send_json(res, status, {{"status", status}, {"error", status_reason(status)}, {"message", message}});
}

using Workers = std::counting_semaphore<>;

/// A worker held for as long as the object lives.
class WorkerSlot {
 public:
  explicit WorkerSlot(Workers& workers) : workers_(workers) { workers_.acquire(); }
  WorkerSlot(const WorkerSlot&) = delete;
  WorkerSlot& operator=(const WorkerSlot&) = delete;
  ~WorkerSlot() { workers_.release(); }

 private:
  Workers& workers_;
};

/// Runs a handler on one of the `workers`, after taking a heavy slot for heavy work (`heavy`
/// not null: it may wait in the queue, holding no worker, or be refused with 503), turning
/// what it throws into a JSON error: ApiError as it says, hotmesh::InputError (a user problem
/// the kernel found) as 422, anything else as 500.
template <class Handler>
httplib::Server::Handler guarded(Workers& workers, HeavyWork* heavy, Handler handler) {
  return [&workers, heavy, handler](const Request& req, Response& res) {
    try {
      std::optional<HeavyWork::Slot> heavy_slot;
      if (heavy != nullptr) heavy_slot.emplace(*heavy);
      const WorkerSlot slot(workers);
      handler(req, res);
    } catch (const ApiError& e) {
      if (e.retry_after() > 0) res.set_header("Retry-After", std::to_string(e.retry_after()));
      send_error(res, e.status(), e.what());
    } catch (const InputError& e) {
      send_error(res, 422, e.what());
    } catch (const std::bad_alloc&) {
      spdlog::error("{} {}: out of memory", req.method, req.path);
      send_error(res, 507, "the server ran out of memory for this request");
    } catch (const std::exception& e) {
      spdlog::error("{} {}: internal error: {}", req.method, req.path, e.what());
      send_error(res, 500, fmt::format("internal error: {}", e.what()));
    } catch (...) {
      spdlog::error("{} {}: internal error", req.method, req.path);
      send_error(res, 500, "internal error");
    }
  };
}

/// The media type of the body, in lower case, without parameters ("application/json").
std::string media_type(const Request& req) {
  const std::string type = req.get_header_value("Content-Type");
  return ascii_lower(trim(std::string_view(type).substr(0, type.find(';')), " \t"));
}

/// Why a body of media type `type` is not taken by a JSON route.
std::string not_json_message(const std::string& type, std::string_view also = {}) {
  return fmt::format("{}: send JSON (Content-Type: application/json){}",
                     type.empty() ? "the body has no Content-Type" : fmt::format("the body is {}", type.substr(0, 100)),
                     also);
}

/// The body of a JSON route: only with Content-Type application/json. A page elsewhere can
/// post text/plain or a form to the service without the browser asking it first; JSON it can
/// post only after a CORS check, which the service never grants. `also` names another type the
/// route takes.
Json json_body(const Request& req, std::string_view also = {}) {
  const std::string type = media_type(req);
  if (type != "application/json") throw ApiError::unsupported_type(not_json_message(type, also));
  return parse_object(req.body);
}

std::string id_of(const Request& req) { return req.matches[1].str(); }

constexpr std::string_view kIdSegment = "/([A-Za-z0-9]+)";

/// Whether `path` fits a route pattern: literal segments, and kIdSegment for an id.
/// (std::regex is avoided here: GCC 12 warns inside it at -O1 with sanitizers.)
bool route_matches(std::string_view pattern, std::string_view path) {
  while (!pattern.empty() && !path.empty()) {
    const auto pattern_end = std::min(pattern.find('/', 1), pattern.size());
    const auto path_end = std::min(path.find('/', 1), path.size());
    const std::string_view want = pattern.substr(0, pattern_end), got = path.substr(0, path_end);
    if (want == kIdSegment) {
      const bool id = got.size() > 1 && std::all_of(got.begin() + 1, got.end(), [](char c) {
                        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
                      });
      if (!id) return false;
    } else if (want != got) {
      return false;
    }
    pattern.remove_prefix(pattern_end);
    path.remove_prefix(path_end);
  }
  return pattern.empty() && path.empty();
}

/// cpp-httplib's server with connections served by serve_connection: the request head is read
/// under whole-head bounds before the library parses it.
class BoundedServer : public httplib::Server {
 public:
  ConnectionLimits limits;

 private:
  bool process_and_close_socket(socket_t sock) override {
    serve_connection(
        sock, limits, [this] { return svr_sock_ == INVALID_SOCKET; },
        [this](httplib::Stream& stream, bool last, bool& close) { return process_request(stream, last, close, nullptr); });
    return true;
  }
};

}  // namespace

struct HttpServer::Impl {
  Impl(GeometryService& s, HttpOptions o)
      : service(s),
        options(std::move(o)),
        workers(static_cast<std::ptrdiff_t>(std::max<std::size_t>(options.threads, 1))),
        heavy(options.heavy_requests, options.heavy_queue) {}

  /// Heavy work (heavy_work.hpp) or light.
  enum class Work { light, heavy };

  void add(const std::string& method, const std::string& pattern, httplib::Server::Handler handler,
           Work work = Work::light) {
    auto known = std::find_if(routes.begin(), routes.end(), [&](const auto& r) { return r.first == pattern; });
    if (known == routes.end()) {
      routes.emplace_back(pattern, std::vector<std::string>{});
      known = std::prev(routes.end());
    }
    known->second.push_back(method);
    HeavyWork* gate = work == Work::heavy ? &heavy : nullptr;
    if (method == "GET") server.Get(pattern, guarded(workers, gate, std::move(handler)));
    if (method == "POST") server.Post(pattern, guarded(workers, gate, std::move(handler)));
    if (method == "DELETE") server.Delete(pattern, guarded(workers, gate, std::move(handler)));
  }

  void add_routes();
  void add_page();
  /// Completes responses that the library or no route produced (404, 405, 413, ...).
  httplib::Server::HandlerResponse complete_error(const Request& req, Response& res) const;
  /// Refuses, before its body is read, a request from a page that is not the service's, and a
  /// multipart body posted to a JSON route.
  httplib::Server::HandlerResponse refuse_foreign(const Request& req, Response& res) const;

  GeometryService& service;
  HttpOptions options;
  Workers workers;
  HeavyWork heavy;
  std::optional<HostPolicy> hosts;  ///< made once the port is known
  BoundedServer server;
  std::vector<std::pair<std::string, std::vector<std::string>>> routes;  ///< pattern, methods
};

void HttpServer::Impl::add_routes() {
  GeometryService& s = service;
  const Work heavy_work = Work::heavy;
  add("GET", "/api/health", [&s, this](const Request&, Response& res) {
    Json health = s.health();
    health["heavy_work"] = heavy.status();
    send_json(res, 200, health);
  });
  add("GET", "/api/files", [&s](const Request&, Response& res) { send_json(res, 200, s.files()); });
  add("GET", "/api/models", [&s](const Request&, Response& res) { send_json(res, 200, s.models()); });
  add("POST", "/api/models", [&s](const Request& req, Response& res) {
    if (media_type(req) == "multipart/form-data") {
      if (!req.has_file("file")) throw ApiError::bad_request("file: required (the CAD file, as form field 'file')");
      const httplib::MultipartFormData file = req.get_file_value("file");
      const std::string unit = req.has_file("unit") ? req.get_file_value("unit").content : std::string("m");
      send_json(res, 201, s.load_upload(file.filename, file.content, unit));
    } else {
      send_json(res, 201, s.load_path(json_body(req, ", or a CAD file as multipart/form-data")));
    }
  }, heavy_work);
  add("GET", R"(/api/models/([A-Za-z0-9]+))", [&s](const Request& req, Response& res) {
    send_json(res, 200, s.model(id_of(req)));
  });
  add("DELETE", R"(/api/models/([A-Za-z0-9]+))", [&s](const Request& req, Response& res) {
    s.delete_model(id_of(req));
    send_json(res, 200, {{"deleted", id_of(req)}});
  });
  add("GET", R"(/api/models/([A-Za-z0-9]+)/faces)", [&s](const Request& req, Response& res) {
    send_json(res, 200, s.faces(id_of(req)));
  });
  add("POST", R"(/api/models/([A-Za-z0-9]+)/mode)", [&s](const Request& req, Response& res) {
    send_json(res, 200, s.faces_mode(id_of(req), json_body(req)));
  }, heavy_work);
  add("POST", R"(/api/models/([A-Za-z0-9]+)/meridional)", [&s](const Request& req, Response& res) {
    send_json(res, 201, s.meridional(id_of(req), json_body(req)));
  }, heavy_work);
  add(
      "POST", "/api/curves",
      [&s](const Request& req, Response& res) { send_json(res, 201, s.create_curve(json_body(req))); }, heavy_work);
  add("GET", R"(/api/curves/([A-Za-z0-9]+))", [&s](const Request& req, Response& res) {
    res.status = 200;
    res.set_content(s.curve(id_of(req)), "application/json");
  });
  add("DELETE", R"(/api/curves/([A-Za-z0-9]+))", [&s](const Request& req, Response& res) {
    s.delete_curve(id_of(req));
    send_json(res, 200, {{"deleted", id_of(req)}});
  });
  add("POST", R"(/api/curves/([A-Za-z0-9]+)/project)", [&s](const Request& req, Response& res) {
    send_json(res, 200, s.project(id_of(req), json_body(req)));
  }, heavy_work);
  add("GET", R"(/api/curves/([A-Za-z0-9]+)/download)", [&s](const Request& req, Response& res) {
    if (!req.has_param("format")) throw ApiError::bad_request("format: required: ?format=step, iges or csv");
    send_download(res, s.download(id_of(req), req.get_param_value("format")));
  }, heavy_work);
  add("POST", "/api/surfaces", [&s](const Request& req, Response& res) {
    send_json(res, 201, s.create_surface(json_body(req)));
  }, heavy_work);
  add("GET", R"(/api/surfaces/([A-Za-z0-9]+))", [&s](const Request& req, Response& res) {
    res.status = 200;
    res.set_content(s.surface(id_of(req)), "application/json");
  });
  add("DELETE", R"(/api/surfaces/([A-Za-z0-9]+))", [&s](const Request& req, Response& res) {
    s.delete_surface(id_of(req));
    send_json(res, 200, {{"deleted", id_of(req)}});
  });
  add("GET", R"(/api/surfaces/([A-Za-z0-9]+)/download)", [&s](const Request& req, Response& res) {
    if (!req.has_param("format")) throw ApiError::bad_request("format: required: ?format=step or iges");
    send_download(res, s.surface_download(id_of(req), req.get_param_value("format")));
  }, heavy_work);
}

void HttpServer::Impl::add_page() {
  for (const WebAsset& asset : web_assets()) {
    const std::string path = fmt::format("/{}", asset.name);
    auto send = [asset](const Request&, Response& res) {
      res.status = 200;
      res.set_header("Content-Security-Policy",
                     "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'");
      res.set_content(std::string(asset.content), std::string(asset.content_type).c_str());
    };
    add("GET", path, send);
    if (asset.name == "index.html") add("GET", "/", send);
  }
}

httplib::Server::HandlerResponse HttpServer::Impl::complete_error(const Request& req, Response& res) const {
  if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;  // a handler's own answer
  // No route took the request: 404 from the library, or 400 for a method no route has (PUT).
  const bool unrouted = res.status == 404 || (res.status == 400 && req.method != "GET" && req.method != "POST" &&
                                              req.method != "DELETE" && !req.method.empty());
  if (unrouted) {
    for (const auto& [pattern, methods] : routes) {
      if (!route_matches(pattern, req.path)) continue;
      res.set_header("Allow", fmt::format("{}", fmt::join(methods, ", ")));
      send_error(res, 405, fmt::format("{} {}: use {}", req.method, req.path, fmt::join(methods, " or ")));
      return httplib::Server::HandlerResponse::Handled;
    }
    send_error(res, 404, fmt::format("no route {} {} (the API is under /api/, see docs/service.md)", req.method, req.path));
  } else if (res.status == 413) {
    const std::string type = req.get_header_value("Content-Type");
    send_error(res, 413, type.starts_with("application/x-www-form-urlencoded")
                             ? "form-encoded bodies are limited to 8 KiB: send JSON (Content-Type: application/json)"
                             : fmt::format("the body is larger than the limit of {} bytes (hotmesh serve --max-body)",
                                           service.limits().max_body_bytes));
  } else if (res.status == 400 && media_type(req) == "multipart/form-data") {
    send_error(res, 400, fmt::format("{} {}: the multipart/form-data body cannot be read (its boundary or parts are "
                                     "malformed): send the file as curl -F file=@NAME does",
                                     req.method, req.path));
  } else {
    send_error(res, res.status, fmt::format("{} {}: {}", req.method, req.path, status_reason(res.status)));
  }
  return httplib::Server::HandlerResponse::Handled;
}

httplib::Server::HandlerResponse HttpServer::Impl::refuse_foreign(const Request& req, Response& res) const {
  auto header = [&req](const char* name) {
    return req.has_header(name) ? std::optional<std::string>(req.get_header_value(name)) : std::nullopt;
  };
  try {
    hosts->check(header("Host"), header("Origin"));
    // A multipart body on a JSON route: 415 before cpp-httplib parses it (a malformed one was
    // its bare 400). Only POST /api/models takes multipart (uploads).
    const std::string type = media_type(req);
    const bool json_route = req.path != "/api/models" && std::any_of(routes.begin(), routes.end(), [&](const auto& r) {
      return route_matches(r.first, req.path) &&
             std::find(r.second.begin(), r.second.end(), "POST") != r.second.end();
    });
    if (req.method == "POST" && type == "multipart/form-data" && json_route) {
      throw ApiError::unsupported_type(not_json_message(type));
    }
    return httplib::Server::HandlerResponse::Unhandled;
  } catch (const ApiError& e) {
    spdlog::warn("{} {}: refused: {}", req.method, req.path, e.what());
    send_error(res, e.status(), e.what());
    res.set_header("Connection", "close");
    close_connection_after_answer();  // the body, if any, was not read
    return httplib::Server::HandlerResponse::Handled;
  }
}

HttpServer::HttpServer(GeometryService& service, HttpOptions options)
    : impl_(std::make_unique<Impl>(service, std::move(options))) {
  Impl& i = *impl_;
  const std::size_t connections = std::max<std::size_t>(i.options.connections, 1);
  i.server.new_task_queue = [connections] { return new httplib::ThreadPool(connections); };
  i.server.limits.head_timeout = i.options.head_timeout;
  i.server.set_payload_max_length(service.limits().max_body_bytes);
  i.server.set_tcp_nodelay(true);  // small JSON answers on kept-alive connections: no Nagle delay
  // What the answers' Keep-Alive header announces: serve_connection keeps to it.
  i.server.set_keep_alive_max_count(i.server.limits.max_requests);
  i.server.set_keep_alive_timeout(std::chrono::duration_cast<std::chrono::seconds>(i.server.limits.idle_timeout).count());
  const auto io_seconds = std::chrono::duration_cast<std::chrono::seconds>(i.server.limits.io_timeout).count();
  i.server.set_read_timeout(io_seconds);  // the sockets' own timeouts, behind serve_connection's
  i.server.set_write_timeout(io_seconds);
  // SO_REUSEADDR only: the library's default SO_REUSEPORT would let another process bind the
  // same port and take a share of the connections.
  i.server.set_socket_options([](int sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  i.server.set_default_headers({{"X-Content-Type-Options", "nosniff"}, {"Cache-Control", "no-store"}});
  i.add_routes();
  i.add_page();
  i.server.set_pre_routing_handler([&i](const Request& req, Response& res) { return i.refuse_foreign(req, res); });
  i.server.set_error_handler(httplib::Server::HandlerWithResponse(
      [&i](const Request& req, Response& res) { return i.complete_error(req, res); }));
  i.server.set_exception_handler([](const Request& req, Response& res, std::exception_ptr) {
    spdlog::error("{} {}: internal error", req.method, req.path);
    send_error(res, 500, "internal error");
  });
  i.server.set_logger([](const Request& req, const Response& res) {
    if (res.status >= 500) {
      spdlog::error("{} {} -> {}", req.method, req.path, res.status);
    } else {
      spdlog::debug("{} {} -> {}", req.method, req.path, res.status);
    }
  });
}

HttpServer::~HttpServer() = default;

int HttpServer::bind() {
  const HttpOptions& o = impl_->options;
  [[maybe_unused]] const HostPolicy names_checked(o.bind, 80, o.allowed_hosts);  // a bad --allow-host: before listening
  const int port = o.port == 0 ? impl_->server.bind_to_any_port(o.bind) : (impl_->server.bind_to_port(o.bind, o.port) ? o.port : -1);
  if (port < 0) {
    throw InputError(fmt::format("cannot listen on {} port {}: the address is not one of this machine's or the port "
                                 "is in use",
                                 o.bind, o.port));
  }
  impl_->hosts.emplace(o.bind, port, o.allowed_hosts);
  return port;
}

std::vector<std::string> HttpServer::hosts() const {
  if (!impl_->hosts) return {};
  return {impl_->hosts->hosts().begin(), impl_->hosts->hosts().end()};
}

bool HttpServer::run() { return impl_->server.listen_after_bind(); }

void HttpServer::stop() { impl_->server.stop(); }

}  // namespace hotmesh::app::serve
