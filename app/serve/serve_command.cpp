// hotmesh serve [--port P] [--bind ADDR] [--root DIR] ...: the geometry service over HTTP with
// its inspection page (docs/service.md). Runs until SIGINT or SIGTERM, then stops listening,
// lets the requests under way finish, removes its upload folder and exits with code 0.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <pthread.h>
#include <signal.h>

#include <fmt/ranges.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.hpp"
#include "hotmesh/core/input_error.hpp"
#include "serve/http_server.hpp"
#include "service/service.hpp"

namespace hotmesh::app {

namespace {

struct Options {
  int port = 8080;
  std::string bind = "127.0.0.1";
  std::string root;
  std::size_t threads = 8;
  std::size_t max_connections = 64;
  std::size_t heavy_requests = 2;
  std::size_t heavy_queue = 8;
  double header_timeout = 10;
  std::vector<std::string> allowed_hosts;
  std::size_t max_body_mib = 64;
  std::size_t max_nodes = 100'000;
};

/// SIGINT and SIGTERM blocked in this thread and every thread started after it (the server's
/// workers); a watcher thread takes them with sigtimedwait and stops the server.
class SignalStop {
 public:
  SignalStop() {
    sigemptyset(&signals_);
    sigaddset(&signals_, SIGINT);
    sigaddset(&signals_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals_, &previous_);
  }
  SignalStop(const SignalStop&) = delete;
  SignalStop& operator=(const SignalStop&) = delete;
  ~SignalStop() {
    done_ = true;
    if (watcher_.joinable()) watcher_.join();
    pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
  }

  void watch(serve::HttpServer& server) {
    watcher_ = std::thread([this, &server] {
      while (!done_) {
        const timespec wait{0, 200'000'000};
        const int signal = sigtimedwait(&signals_, nullptr, &wait);
        if (signal == SIGINT || signal == SIGTERM) {
          spdlog::info("hotmesh serve: {} received, stopping", signal == SIGINT ? "SIGINT" : "SIGTERM");
          stopped_ = true;
          server.stop();
          return;
        }
      }
    });
  }

  bool stopped() const { return stopped_; }

 private:
  sigset_t signals_{};
  sigset_t previous_{};
  std::thread watcher_;
  std::atomic<bool> done_{false};
  std::atomic<bool> stopped_{false};
};

int run_serve(const Options& o) {
  serve::ServiceLimits limits;
  limits.max_body_bytes = o.max_body_mib << 20;
  limits.max_nodes = o.max_nodes;
  limits.max_points = std::max(limits.max_points, o.max_nodes);
  limits.cad_check.hotmesh = std::filesystem::read_symlink("/proc/self/exe");  // this program
  SignalStop signals;  // before any thread starts, so that all of them inherit the mask
  serve::GeometryService service(o.root.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.root), limits);
  const auto header_timeout = std::chrono::milliseconds(std::lround(o.header_timeout * 1000));
  serve::HttpServer server(service, {o.bind, o.port, o.threads, o.max_connections, header_timeout, o.allowed_hosts,
                                     o.heavy_requests, o.heavy_queue});
  const int port = server.bind();
  const std::string host = o.bind.find(':') != std::string::npos ? "[" + o.bind + "]" : o.bind;
  std::cout << "hotmesh serve: listening on http://" << host << ":" << port << "/" << std::endl;
  spdlog::info("answering requests for Host {}", fmt::join(server.hosts(), ", "));
  if (o.heavy_requests >= o.threads) {
    spdlog::warn("--heavy-requests {} is not below --threads {}: heavy requests can take every worker and delay light "
                 "ones",
                 o.heavy_requests, o.threads);
  }
  if (o.root.empty()) {
    spdlog::info("no --root: CAD files can be uploaded, none is read from disk");
  } else {
    spdlog::info("--root {}: CAD files below it can be loaded by path", o.root);
  }
  if (o.bind != "127.0.0.1" && o.bind != "::1" && o.bind != "localhost") {
    spdlog::warn("listening on {}: other machines can reach the service (no authentication, no TLS)", o.bind);
  }
  signals.watch(server);
  const bool ok = server.run();
  if (!signals.stopped()) {
    spdlog::error("hotmesh serve: the listener stopped unexpectedly");
    return 1;
  }
  spdlog::info("hotmesh serve: stopped{}", ok ? "" : " (listener closed)");
  return 0;
}

}  // namespace

Command add_serve_command(CLI::App& parent) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(
      "serve", "Geometry service over HTTP (JSON API and an inspection page at /); stops on SIGINT/SIGTERM");
  cmd->add_option("--port", options->port, "TCP port; 0 picks a free one (printed on stdout)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--bind", options->bind, "Address to listen on; anything but loopback exposes the service")
      ->capture_default_str();
  cmd->add_option("--root", options->root,
                  "Folder whose CAD files may be loaded by path (nothing outside it is read); none: uploads only")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--allow-host", options->allowed_hosts,
                  "Another name the service is reached by (NAME or NAME:PORT; repeatable): requests for other "
                  "Host names are refused");
  cmd->add_option("--threads", options->threads, "Requests worked on at once")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--heavy-requests", options->heavy_requests,
                  "Heavy requests (every POST and download: CAD loads, curves, surfaces, projections) computed at "
                  "once, within --threads; light ones (health, lists, what is kept) are served meanwhile")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--heavy-queue", options->heavy_queue,
                  "Heavy requests that wait for one of --heavy-requests; more are answered 503 with Retry-After")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  cmd->add_option("--max-connections", options->max_connections,
                  "Connections served at once (a slow client holds one, never a worker)")
      ->check(CLI::Range(1, 512))
      ->capture_default_str();
  cmd->add_option("--header-timeout", options->header_timeout,
                  "Seconds a request line and its headers may take to arrive (else 408)")
      ->check(CLI::Range(0.1, 300.0))
      ->capture_default_str();
  cmd->add_option("--max-body", options->max_body_mib, "Largest request body, upload or CAD file, in MiB")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--max-nodes", options->max_nodes, "Most FEM nodes in one table (and points in one projection)")
      ->check(CLI::Range(2, 100'000'000))
      ->capture_default_str();
  return [options] { return run_serve(*options); };
}

}  // namespace hotmesh::app
