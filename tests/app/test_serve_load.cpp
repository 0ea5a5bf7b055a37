// Tests of `hotmesh serve` under load and abuse: 1,000 requests from 8 concurrent clients on
// loopback (CAD work, reconstructions, projections, downloads and bad requests mixed) all
// answered as expected with the server's memory bounded; malformed JSON, CSV and multipart
// bodies always answered with a 4xx JSON error, never a crash (curves and surfaces).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "cone_nodes.hpp"
#include "serve_process.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using Json = nlohmann::json;

std::string cone_file() { return test::read_text(test::data_path("cad/OCC8842_cone_CATIA.igs")); }

/// The request mix of one client: request i of client c, with the status it must get.
struct Call {
  std::string method;
  std::string path;
  std::string body;
  int status;
};

Call call(int i, const std::string& model, const std::string& curve) {
  const Json reconstruct = {{"model", model}, {"faces", {1, 2}}, {"csv", test::cone_nodes(21)}, {"samples", 50}};
  switch (i % 8) {
    case 0: return {"GET", "/api/health", "", 200};
    case 1: return {"POST", "/api/curves", reconstruct.dump(), 201};
    case 2: return {"POST", "/api/models/" + model + "/meridional", Json{{"faces", {1, 2}}}.dump(), 201};
    case 3: return {"POST", "/api/curves/" + curve + "/project", Json{{"points", {{30.0, -75.0}, {10.0, -20.0}}}}.dump(), 200};
    case 4: return {"GET", "/api/curves/" + curve + "/download?format=csv", "", 200};
    case 5: return {"GET", "/api/models/" + model + "/faces", "", 200};
    case 6: return {"POST", "/api/curves", "{\"csv\": 12", 400};
    default: return {"GET", "/api/curves/" + curve, "", 200};
  }
}

/// The server's environment: under AddressSanitizer a smaller quarantine of freed memory, which
/// would otherwise grow the resident memory by up to 256 MiB and hide what the server keeps.
std::map<std::string, std::string> server_environment() {
  std::map<std::string, std::string> environment;
#if HOTMESH_TEST_UNDER_ASAN
  const char* options = std::getenv("ASAN_OPTIONS");
  environment["ASAN_OPTIONS"] = std::string(options ? options : "") + ":quarantine_size_mb=8";
#endif
  return environment;
}

TEST(ServeLoad, ThousandRequestsFromEightClientsWithBoundedMemory) {
  test::ServeProcess server({"--threads", "8"}, server_environment());
  httplib::Client setup("127.0.0.1", server.port());
  setup.set_read_timeout(60);
  httplib::MultipartFormDataItems upload{{"file", cone_file(), "cone.igs", ""}, {"unit", "mm", "", ""}};
  const auto loaded = setup.Post("/api/models", upload);
  ASSERT_TRUE(loaded && loaded->status == 201);
  const std::string model = Json::parse(loaded->body)["model"];
  const Json reconstruct = {{"model", model}, {"faces", {1, 2}}, {"csv", test::cone_nodes(21)}};
  const auto made = setup.Post("/api/curves", reconstruct.dump(), "application/json");
  ASSERT_TRUE(made && made->status == 201);
  const std::string curve = Json::parse(made->body)["curve"];

  auto run = [&](int client, int count, std::atomic<int>& failures, std::vector<std::string>& errors) {
    httplib::Client http("127.0.0.1", server.port());
    http.set_keep_alive(true);
    http.set_tcp_nodelay(true);
    http.set_read_timeout(60);
    for (int i = 0; i < count; ++i) {
      const Call c = call(i + client, model, curve);
      const auto result = c.method == "GET" ? http.Get(c.path.c_str())
                                            : http.Post(c.path.c_str(), c.body, "application/json");
      const bool ok = result && result->status == c.status && !result->body.empty();
      if (!ok) {
        ++failures;
        if (errors.size() < 5) {
          errors.push_back(c.method + " " + c.path + ": " +
                           (result ? std::to_string(result->status) + " " + result->body.substr(0, 200)
                                   : httplib::to_string(result.error())));
        }
      }
    }
  };

  // Warm-up: fills the curve store to its capacity (64: 80 curves are made), so that later
  // curves replace older ones.
  std::atomic<int> warm_failures{0};
  std::vector<std::string> warm_errors;
  run(0, 320, warm_failures, warm_errors);
  ASSERT_EQ(warm_failures, 0) << warm_errors.front();
  const long warm = server.rss_kib();
  ASSERT_GT(warm, 0);

  constexpr int kClients = 8;
  constexpr int kPerClient = 125;
  std::atomic<int> failures{0};
  std::vector<std::vector<std::string>> errors(kClients);
  std::atomic<bool> running{true};
  std::atomic<long> peak{warm};
  std::thread monitor([&] {
    while (running) {
      peak = std::max(peak.load(), server.rss_kib());
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) clients.emplace_back([&, c] { run(c, kPerClient, failures, errors[static_cast<std::size_t>(c)]); });
  for (auto& t : clients) t.join();
  running = false;
  monitor.join();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  EXPECT_EQ(failures, 0) << [&] {
    std::string text;
    for (const auto& list : errors) {
      for (const auto& e : list) text += e + "\n";
    }
    return text;
  }();
  const long after = server.rss_kib();
  RecordProperty("requests_per_second", static_cast<int>(kClients * kPerClient / seconds));
  RecordProperty("rss_warm_kib", static_cast<int>(warm));
  RecordProperty("rss_peak_kib", static_cast<int>(peak.load()));
  std::printf("%d requests in %.2f s; RSS warm %ld KiB, peak %ld KiB, after %ld KiB\n", kClients * kPerClient, seconds,
              warm, peak.load(), after);
  EXPECT_LT(peak.load(), 2 * warm) << "memory grew under load";
  EXPECT_LT(after, 2 * warm);
  EXPECT_EQ(server.stop(SIGTERM), 0) << server.log();
}

/// Bodies a broken or hostile client may send.
std::vector<std::string> malformed_json() {
  std::vector<std::string> bodies{"",
                                  "{",
                                  "}",
                                  "null",
                                  "[]",
                                  "\"text\"",
                                  "{\"csv\": }",
                                  "{\"csv\": \"x\", }",
                                  "{\"csv\": NaN}",
                                  "{\"degree\": 1e999}",
                                  "{\"degree\": -9223372036854775809}",
                                  "{\"degree\": 18446744073709551616}",
                                  "{\"faces\": [1e308, -1, 0]}",
                                  "{\"model\": {}, \"faces\": {}}",
                                  "{\"csv\": \"\\ud800\"}",
                                  "{\"csv\": \"\xff\xfe\", \"csv_name\": \"\xc3\x28\"}",
                                  "{\"\xff\": 1}",
                                  std::string("{\"csv\": \"a\0b\"}", 15),
                                  "{\"axis\": {\"origin\": [1, 2, 3], \"direction\": [\"a\", null, {}]}}"};
  bodies.push_back(std::string(100000, '[') + std::string(100000, ']'));  // deep nesting
  bodies.push_back("{\"a\":" + std::string(50000, '{'));
  std::mt19937 random(7);
  for (int i = 0; i < 40; ++i) {
    std::string noise(static_cast<std::size_t>(random() % 2000), '\0');
    for (char& c : noise) c = static_cast<char>(random() & 0xff);
    bodies.push_back(noise);
  }
  return bodies;
}

std::vector<std::string> malformed_csv() {
  std::vector<std::string> tables{"",
                                  "\n\n\n",
                                  "x,y,dx,dy\n",
                                  "x,y,dx,dy\n1,2,3\n",
                                  "x,y,dx,dy\n1,2,3,4,5\n",
                                  "x,y,dx,dy\nnan,0,0,0\n1,1,0,0\n",
                                  "x,y,dx,dy\ninf,0,0,0\n1,1,0,0\n",
                                  "x,y,dx,dy\n1e400,0,0,0\n1,1,0,0\n",
                                  "x,x,y,dx,dy\n1,1,1,1,1\n",
                                  "r,z,dr,dz\n-1,0,0,0\n2,2,0,0\n",
                                  "x,y,dx,dy\n0,0,0,0\n0,0,0,0\n0,0,0,0\n",
                                  "x,y,dx,dy\n0,0,0,0\n0,0,1,1\n",
                                  "x,y,dx,dy\n" + std::string(200000, '1') + ",0,0,0\n",
                                  "id,x,y,dx,dy\n99999999999999999999,0,0,0,0\n1,1,0,0,0\n",
                                  "x;y;dx;dy\n0;0;0;0\n",
                                  std::string("x,y,dx,dy\n0,0\0,0,0\n", 20)};
  std::mt19937 random(11);
  for (int i = 0; i < 40; ++i) {
    std::string noise = "x,y,dx,dy\n";
    const std::string alphabet = "0123456789.,-+eE\n\r#\" xyn";
    for (std::size_t k = 0; k < 300; ++k) noise += alphabet[random() % alphabet.size()];
    tables.push_back(noise);
  }
  return tables;
}

TEST(ServeRobustness, MalformedJsonCsvAndMultipartNeverCrashTheServer) {
  test::ServeProcess server;
  httplib::Client http("127.0.0.1", server.port());
  http.set_read_timeout(60);
  int answered = 0;
  auto expect_client_error = [&](const httplib::Result& result, const std::string& what) {
    ASSERT_TRUE(result) << what << ": no answer (" << httplib::to_string(result.error()) << ")\n" << server.log();
    EXPECT_GE(result->status, 400) << what;
    EXPECT_LT(result->status, 500) << what << ": " << result->body;
    const Json body = Json::parse(result->body, nullptr, false);
    EXPECT_TRUE(body.is_object() && body.contains("message")) << what << ": " << result->body;
    ++answered;
  };
  const std::vector<std::string> routes{"/api/curves", "/api/models", "/api/curves/c1/project",
                                        "/api/models/m1/meridional", "/api/surfaces"};
  for (const std::string& body : malformed_json()) {
    for (const std::string& route : routes) {
      expect_client_error(http.Post(route.c_str(), body, "application/json"), "JSON to " + route);
    }
  }
  // The tables also to a surface on the cone's faces (a model is needed to get to the table).
  httplib::MultipartFormDataItems upload{{"file", cone_file(), "cone.igs", ""}, {"unit", "mm", "", ""}};
  const auto loaded = http.Post("/api/models", upload);
  ASSERT_TRUE(loaded && loaded->status == 201);
  const std::string model = Json::parse(loaded->body)["model"];
  for (const std::string& table : malformed_csv()) {
    const Json request = {{"csv", table}, {"csv_name", "t.csv"}};
    const auto result = http.Post("/api/curves", request.dump(-1, ' ', false, Json::error_handler_t::replace),
                                  "application/json");
    expect_client_error(result, "CSV " + table.substr(0, 40));
    const Json surface = {{"model", model}, {"faces", {1, 2}}, {"csv", table}, {"csv_name", "t.csv"}};
    expect_client_error(http.Post("/api/surfaces", surface.dump(-1, ' ', false, Json::error_handler_t::replace),
                                  "application/json"),
                        "surface CSV " + table.substr(0, 40));
  }
  // Multipart bodies with broken boundaries, no file name, junk parts.
  const std::vector<std::pair<std::string, std::string>> multipart{
      {"multipart/form-data; boundary=xyz", "--xyz\r\nContent-Disposition: form-data; name=\"file\"\r\n\r\nabc"},
      {"multipart/form-data; boundary=xyz", "--abc\r\n\r\n--abc--"},
      {"multipart/form-data", "--xyz\r\n"},
      {"multipart/form-data; boundary=xyz",
       "--xyz\r\nContent-Disposition: form-data; name=\"file\"\r\n\r\nISO-10303-21;\r\n--xyz--\r\n"},
      {"multipart/form-data; boundary=xyz",
       "--xyz\r\nContent-Disposition: form-data; name=\"file\"; filename=\"a.step\"\r\n\r\nISO-10303-21;\r\n--xyz--\r\n"},
      {"multipart/form-data; boundary=xyz",
       "--xyz\r\nContent-Disposition: form-data; name=\"file\"; filename=\"../../a.igs\"\r\n\r\n\x01\x02\r\n--xyz--\r\n"},
      {"application/octet-stream", std::string(1000, '\x7f')}};
  for (const auto& [type, body] : multipart) expect_client_error(http.Post("/api/models", body, type.c_str()), type);
  EXPECT_GT(answered, 300);
  const auto health = http.Get("/api/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(server.stop(SIGTERM), 0) << server.log();
}

}  // namespace
}  // namespace hotmesh::app
