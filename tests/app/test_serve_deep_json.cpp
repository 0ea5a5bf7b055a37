// Tests that `hotmesh serve` refuses JSON bodies nested deeper than any request of the API
// needs, and lives on. A body of one field holding "[[[[...]]]]" 1 000 000 levels deep (2 MB,
// far below the body limit) made the server write the value into its message recursively
// and overflow the stack of the thread serving it: a segmentation fault that ended the
// service for every client. (Seen with the fuzz target of the service's JSON bodies,
// fuzz/fuzz_serve_json.cpp, on inputs larger than it generates itself; docs/fuzzing.md.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <signal.h>

#include <nlohmann/json.hpp>
#include <string>

#include "serve_process.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;

std::string nested(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

TEST(ServeDeepJson, NestedBodiesAreRefusedAndTheServerLives) {
  test::ServeProcess server;
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(60);
  const std::string deep = nested(1'000'000);
  // Fields whose refusal writes the value into the message: an axis, a count, a number.
  for (const std::string& field : {R"("axis": {"origin": )" + deep + R"(, "direction": [0, 0, 1]})",
                                   R"("samples": )" + deep, R"("degree": )" + deep}) {
    const auto r = client.Post("/api/curves", R"({"csv": "x,y,dx,dy\n", )" + field + "}", "application/json");
    ASSERT_TRUE(r) << field.substr(0, 20) << ": no answer (" << httplib::to_string(r.error()) << ")\n" << server.log();
    EXPECT_EQ(r->status, 400) << field.substr(0, 20) << ": " << r->body;
    EXPECT_THAT(r->body, HasSubstr("deeper than 32 levels")) << field.substr(0, 20);
  }
  // The nesting the API uses passes.
  const auto r = client.Post("/api/curves", R"({"csv": "x,y,dx,dy\n0,0,0,0\n1,0,0,0.1\n", "samples": 2})",
                             "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201) << r->body;
  EXPECT_TRUE(server.running());
  EXPECT_EQ(server.stop(SIGTERM), 0) << server.log();
}

}  // namespace
}  // namespace hotmesh::app
