// Tests of `hotmesh serve`'s bound on heavy work (issue 46 item 11; app/serve/heavy_work.hpp):
// at most --heavy-requests heavy requests (every POST and download) compute at once, at most
// --heavy-queue wait for them, more are answered 503 with Retry-After, and light requests are
// served meanwhile. No timing: the first heavy request, an upload, is held in the service's
// CAD check (the child `hotmesh cad`, stopped at its start by the test's fault library until
// the test creates a file), and the others are sent once /api/health says where it stands.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <string>
#include <thread>

#include "faults.hpp"
#include "serve_client.hpp"
#include "serve_process.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using test::Api;
using test::expect_error;
using test::Json;
using test::Reply;

/// A 2D table without CAD: a curve request that is heavy work and needs no model.
const Json kCurve = {{"csv", "x,y,dx,dy\n0,0,0,0\n1,0,0,0.1\n"}, {"samples", 2}};

/// The server with these heavy-work options, its CAD checks held until `release` exists.
test::ServeProcess held_server(const std::filesystem::path& release, const std::string& heavy, const std::string& queue) {
  return test::ServeProcess({"--heavy-requests", heavy, "--heavy-queue", queue},
                            test::fault_environment({.hold_cad_check = release.string()}));
}

/// Waits (as long as it takes: the test's own timeout bounds it) until /api/health reports
/// `running` heavy requests and `waiting` in the queue.
void wait_for_heavy_work(Api& api, int running, int waiting) {
  for (;;) {
    const Reply health = api.get("/api/health");
    ASSERT_EQ(health.status, 200) << health.text;
    const Json& work = health.body["heavy_work"];
    if (work["running"] == running && work["waiting"] == waiting) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

/// The upload of the duct's CAD file, on a thread of its own (held in its CAD check).
std::future<Reply> upload_in_background(int port) {
  const std::string step = test::read_text(std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples/duct3d/duct.step");
  return std::async(std::launch::async, [port, step] { return Api(port).upload("duct.step", step, "mm"); });
}

TEST(ServeHeavyWork, AHeavyRequestBeyondTheLimitGets503WithRetryAfterWhileHealthAnswers) {
  test::TempDir dir;
  test::ServeProcess server = held_server(dir / "release", "1", "0");
  Api api(server.port());
  std::future<Reply> upload = upload_in_background(server.port());
  wait_for_heavy_work(api, 1, 0);

  const Reply busy = api.post("/api/curves", kCurve);
  expect_error(busy, 503, "the service is busy: 1 heavy request(s) are being computed (--heavy-requests)");
  ASSERT_EQ(busy.headers.count("Retry-After"), 1u);
  EXPECT_EQ(busy.headers.find("Retry-After")->second, "5");
  const Reply health = api.get("/api/health");  // light work is served meanwhile
  EXPECT_EQ(health.status, 200);
  EXPECT_EQ(health.body["heavy_work"], (Json{{"limit", 1}, {"queue", 0}, {"running", 1}, {"waiting", 0}}));
  EXPECT_EQ(api.get("/api/models").status, 200);

  test::write_text(dir / "release", "");
  EXPECT_EQ(upload.get().status, 201);
  EXPECT_EQ(api.post("/api/curves", kCurve).status, 201);
  EXPECT_EQ(server.stop(SIGTERM), 0) << server.log();
}

TEST(ServeHeavyWork, HeavyRequestsWaitInTheQueueUntilASlotIsFree) {
  test::TempDir dir;
  test::ServeProcess server = held_server(dir / "release", "1", "1");
  Api api(server.port());
  std::future<Reply> upload = upload_in_background(server.port());
  wait_for_heavy_work(api, 1, 0);
  std::future<Reply> queued =
      std::async(std::launch::async, [port = server.port()] { return Api(port).post("/api/curves", kCurve); });
  wait_for_heavy_work(api, 1, 1);
  expect_error(api.post("/api/curves", kCurve), 503, "and 1 wait (--heavy-queue)");  // the queue is full

  test::write_text(dir / "release", "");
  EXPECT_EQ(upload.get().status, 201);
  EXPECT_EQ(queued.get().status, 201);
  wait_for_heavy_work(api, 0, 0);
  EXPECT_EQ(server.stop(SIGTERM), 0) << server.log();
}

}  // namespace
}  // namespace hotmesh::app
