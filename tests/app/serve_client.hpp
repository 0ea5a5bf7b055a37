// hotmesh tests: a JSON client of `hotmesh serve` (cpp-httplib's) for the API tests: each
// answer as status, parsed JSON body and headers, and the check of an error answer.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace hotmesh::test {

using Json = nlohmann::json;

/// A response: status and JSON body (null if the body is not JSON).
struct Reply {
  int status = 0;
  Json body;
  std::string text;
  httplib::Headers headers;
};

class Api {
 public:
  explicit Api(int port) : client_("127.0.0.1", port) { client_.set_read_timeout(60); }

  Reply get(const std::string& path, const httplib::Headers& headers = {}) {
    return reply(client_.Get(path.c_str(), headers));
  }
  Reply del(const std::string& path) { return reply(client_.Delete(path.c_str())); }
  Reply post(const std::string& path, const Json& body, const httplib::Headers& headers = {}) {
    return post_text(path, body.dump(), "application/json", headers);
  }
  Reply post_text(const std::string& path, const std::string& body, const std::string& type,
                  const httplib::Headers& headers = {}) {
    return reply(client_.Post(path.c_str(), headers, body, type.c_str()));
  }
  Reply upload(const std::string& filename, const std::string& content, const std::string& unit = "mm",
               const httplib::Headers& headers = {}) {
    httplib::MultipartFormDataItems items{{"file", content, filename, "application/octet-stream"}, {"unit", unit, "", ""}};
    return reply(client_.Post("/api/models", headers, items));
  }
  httplib::Client& client() { return client_; }

  static Reply reply(const httplib::Result& result) {
    if (!result) throw std::runtime_error("no response: " + httplib::to_string(result.error()));
    Reply r{result->status, Json(), result->body, result->headers};
    if (result->get_header_value("Content-Type").starts_with("application/json")) r.body = Json::parse(result->body);
    return r;
  }

 private:
  httplib::Client client_;
};

/// An error reply has the status, the reason and a message holding `text`.
inline void expect_error(const Reply& r, int status, const std::string& text) {
  EXPECT_EQ(r.status, status) << r.text;
  ASSERT_TRUE(r.body.is_object()) << r.text;
  EXPECT_EQ(r.body["status"], status);
  EXPECT_TRUE(r.body["error"].is_string());
  EXPECT_THAT(r.body["message"].get<std::string>(), ::testing::HasSubstr(text));
}

}  // namespace hotmesh::test
