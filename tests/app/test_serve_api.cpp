// Tests of `hotmesh serve`'s JSON API, route by route: the happy path with checked values (the
// CATIA cone and its FEM nodes: the deflected curve is known in closed form; a 2D wall on the CAD
// edges of a channel drawn by gmsh) and every error path with its status and a message that says
// what is wrong. The server runs as a child process on a free loopback port (serve_process.hpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <signal.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "channel_step.hpp"
#include "cone_nodes.hpp"
#include "occt_fixtures.hpp"
#include "run_command.hpp"
#include "serve_client.hpp"
#include "serve_process.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using test::Api;
using test::expect_error;
using test::Json;
using test::Reply;

std::string cone_file() { return test::read_text(test::data_path("cad/OCC8842_cone_CATIA.igs")); }

class ServeApi : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(root_.path() / "parts");
    test::write_text(root_ / "parts/cone.igs", cone_file());
    test::write_text(root_ / "parts/bad.step", "this is not STEP\n");
    test::write_text(root_ / "notes.txt", "notes\n");
    test::write_text(root_ / ".hidden.step", "x");
    test::write_text(root_ / "nodes.csv", test::cone_nodes(5));
    std::filesystem::create_symlink(test::data_path("cad/OCC8842_cone_Ideas.igs"), root_ / "outside.igs");
    server_ = std::make_unique<test::ServeProcess>(std::vector<std::string>{"--root", root_.path().string()});
    api_ = std::make_unique<Api>(server_->port());
  }

  void TearDown() override {
    api_.reset();
    EXPECT_EQ(server_->stop(SIGTERM), 0) << server_->log();
  }

  /// The cone loaded by path: model id.
  std::string load_cone() {
    const Reply r = api_->post("/api/models", {{"path", "parts/cone.igs"}, {"unit", "mm"}});
    EXPECT_EQ(r.status, 201) << r.text;
    return r.body["model"];
  }

  Json cone_curve_request(const std::string& model) {
    return {{"model", model}, {"faces", {1, 2}}, {"csv", test::cone_nodes(21)}, {"csv_name", "cone.csv"}};
  }

  test::TempDir root_;
  std::unique_ptr<test::ServeProcess> server_;
  std::unique_ptr<Api> api_;
};

TEST_F(ServeApi, HealthReportsVersionRootAndLimits) {
  const Reply r = api_->get("/api/health");
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.body["status"], "ok");
  EXPECT_EQ(r.body["root"], true);
  EXPECT_EQ(r.body["limits"]["max_nodes"], 100000);
  EXPECT_EQ(r.body["limits"]["max_body_bytes"], 64 << 20);
}

TEST_F(ServeApi, FilesListsCadFilesAndTablesBelowTheRootOnly) {
  const Reply r = api_->get("/api/files");
  ASSERT_EQ(r.status, 200);
  std::vector<std::string> paths;
  for (const auto& f : r.body["files"]) paths.push_back(f["path"]);
  // Not notes.txt (not CAD), not .hidden.step, not the symbolic link leading out.
  EXPECT_THAT(paths, ::testing::ElementsAre("nodes.csv", "parts/bad.step", "parts/cone.igs"));
  EXPECT_EQ(r.body["files"][2]["kind"], "cad");
  EXPECT_EQ(r.body["files"][0]["kind"], "table");
}

TEST_F(ServeApi, LoadsCadByPathBelowTheRoot) {
  const Reply r = api_->post("/api/models", {{"path", "parts/cone.igs"}, {"unit", "mm"}});
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["name"], "parts/cone.igs");
  EXPECT_EQ(r.body["source"], "root");
  EXPECT_EQ(r.body["unit"], "mm");
  ASSERT_EQ(r.body["faces"].size(), 3u);
  EXPECT_EQ(r.body["faces"][0]["kind"], "revolution");
  EXPECT_EQ(r.body["faces"][0]["axis"]["origin"], Json::array({0.0, 0.0, 80.0}));
  EXPECT_EQ(r.body["faces"][2]["kind"], "plane");
  // An absolute path inside the root is the same file.
  const Reply absolute = api_->post("/api/models", {{"path", (root_ / "parts/cone.igs").string()}});
  EXPECT_EQ(absolute.status, 201) << absolute.text;
  EXPECT_EQ(absolute.body["unit"], "m");
}

TEST_F(ServeApi, NoPathOutsideTheRootIsRead) {
  expect_error(api_->post("/api/models", {{"path", "../outside.igs"}}), 403, "'..' is not allowed");
  expect_error(api_->post("/api/models", {{"path", "parts/../../x.igs"}}), 403, "'..' is not allowed");
  expect_error(api_->post("/api/models", {{"path", "/etc/passwd"}}), 403, "outside the root folder");
  expect_error(api_->post("/api/models", {{"path", test::data_path("cad/OCC8842_cone_Ideas.igs").string()}}), 403,
               "outside the root folder");
  expect_error(api_->post("/api/models", {{"path", "outside.igs"}}), 403, "symbolic link leads out of the root");
  expect_error(api_->post("/api/models", {{"path", "missing.igs"}}), 404, "no such file in the root folder");
  expect_error(api_->post("/api/models", {{"path", "parts"}}), 400, "not a regular file");
  expect_error(api_->post("/api/models", {{"path", ""}}), 400, "path: empty");
  expect_error(api_->post("/api/models", {{"path", std::string("parts/cone.igs\0x", 16)}}), 400, "NUL byte");
  expect_error(api_->post("/api/models", {{"path", "notes.txt"}}), 415, "not a CAD file");
  expect_error(api_->post("/api/models", Json::object()), 400, "path: required");
  expect_error(api_->post("/api/models", {{"path", 7}}), 400, "path: expected a string");
  expect_error(api_->post("/api/models", {{"path", "parts/cone.igs"}, {"unit", "furlong"}}), 400,
               "unknown length unit 'furlong'");
  expect_error(api_->post("/api/models", {{"path", "parts/cone.igs"}, {"colour", "red"}}), 400,
               "unknown key \"colour\"");
}

TEST_F(ServeApi, ACorruptCadFileIsNamedAsTheClientKnowsIt) {
  const Reply r = api_->post("/api/models", {{"path", "parts/bad.step"}});
  expect_error(r, 422, "parts/bad.step");
  EXPECT_THAT(r.body["message"].get<std::string>(), Not(HasSubstr("hotmesh-serve-")));  // not the private copy
}

TEST_F(ServeApi, UploadsCadFiles) {
  const Reply r = api_->upload("my cone.igs", cone_file());
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["name"], "my cone.igs");
  EXPECT_EQ(r.body["source"], "upload");
  EXPECT_EQ(r.body["faces"].size(), 3u);
  expect_error(api_->upload("cone.txt", cone_file()), 415, "'cone.txt' is not a CAD file");
  expect_error(api_->upload("empty.step", ""), 400, "'empty.step' is empty");
  expect_error(api_->upload("cone.igs", cone_file(), "parsec"), 400, "unknown length unit");
  expect_error(api_->upload("junk.step", std::string(5000, '\x01')), 422, "junk.step");
  httplib::MultipartFormDataItems no_file{{"unit", "mm", "", ""}};
  const auto missing = api_->client().Post("/api/models", no_file);
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 400);
  EXPECT_THAT(missing->body, HasSubstr("file: required"));
}

TEST_F(ServeApi, ListsGetsAndDeletesModels) {
  const std::string id = load_cone();
  const Reply list = api_->get("/api/models");
  ASSERT_EQ(list.status, 200);
  ASSERT_EQ(list.body["models"].size(), 1u);
  EXPECT_EQ(list.body["models"][0]["model"], id);
  EXPECT_EQ(list.body["models"][0]["face_count"], 3);
  const Reply one = api_->get("/api/models/" + id);
  EXPECT_EQ(one.status, 200);
  EXPECT_EQ(one.body["faces"].size(), 3u);
  const Reply faces = api_->get("/api/models/" + id + "/faces");
  EXPECT_EQ(faces.status, 200);
  EXPECT_EQ(faces.body["faces"], one.body["faces"]);
  expect_error(api_->get("/api/models/m999"), 404, "no model 'm999'");
  expect_error(api_->get("/api/models/m999/faces"), 404, "no model 'm999'");
  EXPECT_EQ(api_->del("/api/models/" + id).status, 200);
  expect_error(api_->get("/api/models/" + id), 404, "no model");
  expect_error(api_->del("/api/models/" + id), 404, "no model");
}

TEST_F(ServeApi, MeridionalCurveOfFaces) {
  const std::string id = load_cone();
  const Reply r = api_->post("/api/models/" + id + "/meridional", {{"faces", {1, 2}}, {"samples", 10}});
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["kind"], "meridional");
  EXPECT_EQ(r.body["frame"], "rz");
  EXPECT_EQ(r.body["model"], id);
  EXPECT_TRUE(r.body["deformed"].is_null());
  // (r, z) about the axis through the apex: from the base rim (60, -150) to the apex (0, 0).
  const Json& samples = r.body["undeformed"]["samples"];
  ASSERT_GE(samples.size(), 11u);
  EXPECT_NEAR(samples.front()[1].get<double>(), 60.0, 1e-6);
  EXPECT_NEAR(samples.front()[2].get<double>(), -150.0, 1e-6);
  EXPECT_NEAR(samples.back()[1].get<double>(), 0.0, 1e-6);
  EXPECT_EQ(r.body["undeformed"]["degree"], 1);
  EXPECT_EQ(r.body["undeformed"]["knots"].size(), r.body["undeformed"]["poles"].size() + 2);

  const std::string path = "/api/models/" + id + "/meridional";
  expect_error(api_->post(path, Json::object()), 400, "faces: required");
  expect_error(api_->post(path, {{"faces", "1,2"}}), 400, "expected an array of face ids");
  expect_error(api_->post(path, {{"faces", {1, 1}}}), 400, "face 1 is listed twice");
  expect_error(api_->post(path, {{"faces", {9}}}), 400, "the model has 3 faces; there is no face 9");
  expect_error(api_->post(path, {{"faces", {3}}}), 422, "axis");  // a plane alone has none
  expect_error(api_->post(path, {{"faces", {1}}, {"axis", {{"origin", {0, 0, 0}}, {"direction", {0, 0, 0}}}}}), 400,
               "axis");
  expect_error(api_->post(path, {{"faces", {1}}, {"axis", {{"origin", {0, 0}}}}}), 400, "axis: expected");
  expect_error(api_->post(path, {{"faces", {1}}, {"samples", 1}}), 400, "samples: expected an integer from 2");
  expect_error(api_->post("/api/models/m77/meridional", {{"faces", {1}}}), 404, "no model 'm77'");
}

// Issue 45: how faces are taken, as hotmesh deform and check take them. The forward-facing step
// (planes and one cylinder fillet, written with OpenCASCADE) is surfaces, the reason naming the
// first plane, and forcing meridional is refused; the fillet alone and the cone's faces turn
// about one axis; a typed axis is the one the faces must turn about.
TEST_F(ServeApi, FacesAreMeridionalOnlyWhenEveryOneTurnsAboutOneAxis) {
  test::TempDir dir;
  geometry::test::write_forward_facing_step(dir / "step.step");
  const Reply loaded = api_->upload("step.step", test::read_text(dir / "step.step"), "mm");
  ASSERT_EQ(loaded.status, 201) << loaded.text;
  const std::string path = "/api/models/" + loaded.body["model"].get<std::string>() + "/mode";

  const Reply step = api_->post(path, {{"faces", {1, 2, 3, 4}}});
  ASSERT_EQ(step.status, 200) << step.text;
  EXPECT_EQ(step.body["mode"], "surface");
  EXPECT_EQ(step.body["faces"], Json({1, 2, 3, 4}));
  EXPECT_TRUE(step.body["axis"].is_null());
  EXPECT_EQ(step.body["profiles"], 0);
  const std::string reason = step.body["reason"];
  EXPECT_THAT(reason, HasSubstr("face 1 (plane) is not a surface of revolution about the axis (10, 1, 0) along (0, 0, 1)"));
  EXPECT_THAT(reason, Not(HasSubstr("step")));  // no file name, least of all the service's copy's
  expect_error(api_->post(path, {{"faces", {1, 2, 3, 4}}, {"mode", "meridional"}}), 422,
               "mode meridional: step.step: face 1 (plane) is not a surface of revolution");
  const Reply forced = api_->post(path, {{"faces", {2}}, {"mode", "surface"}});
  ASSERT_EQ(forced.status, 200) << forced.text;
  EXPECT_EQ(forced.body["mode"], "surface");
  EXPECT_TRUE(forced.body["reason"].is_null());

  const Reply fillet = api_->post(path, {{"faces", {2}}});
  ASSERT_EQ(fillet.status, 200) << fillet.text;
  EXPECT_EQ(fillet.body["mode"], "meridional");
  EXPECT_EQ(fillet.body["profiles"], 1);
  EXPECT_TRUE(fillet.body["reason"].is_null());
  const Json& axis = fillet.body["axis"];
  EXPECT_NEAR(axis["origin"][0].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(axis["origin"][1].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(axis["direction"][2].get<double>()), 1.0, 1e-12);
  const Json z_axis = {{"origin", {0, 0, 0}}, {"direction", {0, 0, 1}}};
  const Reply about_z = api_->post(path, {{"faces", {2}}, {"axis", z_axis}});
  ASSERT_EQ(about_z.status, 200) << about_z.text;
  EXPECT_EQ(about_z.body["mode"], "surface");
  EXPECT_THAT(about_z.body["reason"].get<std::string>(),
              HasSubstr("face 2 (cylinder) is not a surface of revolution about the axis (0, 0, 0) along (0, 0, 1)"));

  const Reply cone = api_->post("/api/models/" + load_cone() + "/mode", {{"faces", {1, 2}}});
  ASSERT_EQ(cone.status, 200) << cone.text;
  EXPECT_EQ(cone.body["mode"], "meridional");

  expect_error(api_->post(path, {{"faces", {2}}, {"mode", "sideways"}}), 400,
               "mode: expected \"auto\", \"meridional\" or \"surface\", got \"sideways\"");
  expect_error(api_->post(path, {{"faces", {9}}}), 400, "the model has 4 faces; there is no face 9");
  expect_error(api_->post(path, {{"faces", {2}}, {"samples", 10}}), 400, "unknown key \"samples\"");
  expect_error(api_->post("/api/models/m77/mode", {{"faces", {1}}}), 404, "no model 'm77'");
}

TEST_F(ServeApi, ReconstructsTheDeflectedConeWithFitStatistics) {
  const std::string model = load_cone();
  Json request = cone_curve_request(model);
  request["samples"] = 20;
  const Reply r = api_->post("/api/curves", request);
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["kind"], "reconstructed");
  const Json& summary = r.body["summary"];
  EXPECT_EQ(summary["nodes"], 21);
  EXPECT_EQ(summary["used_nodes"], 21);
  EXPECT_EQ(summary["degree"], 1);
  EXPECT_EQ(summary["frame"], "rz");
  EXPECT_EQ(summary["cad"], "parts/cone.igs");
  EXPECT_LT(summary["max_node_distance_to_cad"].get<double>(), 1e-6);
  EXPECT_LT(summary["max_node_residual"].get<double>(), 1e-12);
  EXPECT_EQ(r.body["amplification"], 20.0);
  // The deformed curve is the profile moved by the deflection: exact at the nodes (s = t here).
  const Json& deformed = r.body["deformed"];
  EXPECT_EQ(deformed["degree"], 1);
  EXPECT_EQ(deformed["poles"].size() + 2, deformed["knots"].size());
  EXPECT_NEAR(deformed["samples"].front()[1].get<double>(), 60.5, 1e-6);
  EXPECT_NEAR(deformed["samples"].front()[2].get<double>(), -150.2, 1e-6);
  // Per node: parameter on the CAD curve, distance to it, residual; table order (out of order).
  ASSERT_EQ(r.body["nodes"].size(), 21u);
  const Json& node = r.body["nodes"][1];  // the second row: node 102 (s = 0.1, t = 0.9)
  EXPECT_EQ(node["id"], 102);
  EXPECT_EQ(node["line"], 3);
  EXPECT_EQ(node["label"], "node 102 (line 3)");
  EXPECT_NEAR(node["parameter"].get<double>(), 0.9, 1e-8);
  EXPECT_NEAR(node["point"][0].get<double>(), 6.0, 1e-9);
  EXPECT_NEAR(node["deflection"][1].get<double>(), -0.02, 1e-12);
  EXPECT_LT(node["distance"].get<double>(), 1e-6);
  EXPECT_LT(node["residual"].get<double>(), 1e-12);
  EXPECT_FALSE(node["rejected"].get<bool>());
  // The curve is kept: GET gives the same answer.
  const Reply again = api_->get("/api/curves/" + r.body["curve"].get<std::string>());
  EXPECT_EQ(again.status, 200);
  EXPECT_EQ(again.body, r.body);
}

TEST_F(ServeApi, DroppedFarNodesAreMarked) {
  const std::string model = load_cone();
  Json request = cone_curve_request(model);
  request["csv"] = test::cone_nodes(11, 2.0);
  expect_error(api_->post("/api/curves", request), 422, "node 103 (line 9) at distance 1.85");
  request["drop_far_nodes"] = true;
  request["degree"] = 3;
  request["form"] = "displacement";
  const Reply r = api_->post("/api/curves", request);
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["summary"]["used_nodes"], 10);
  EXPECT_EQ(r.body["summary"]["rejected_nodes"][0]["id"], 103);
  const Json& far = r.body["nodes"][7];  // row 8 of the table, line 9
  EXPECT_EQ(far["id"], 103);
  EXPECT_TRUE(far["rejected"].get<bool>());
  EXPECT_TRUE(far["residual"].is_null());
  EXPECT_NEAR(far["distance"].get<double>(), 1.85, 0.01);
}

TEST_F(ServeApi, ReconstructsA2DTableWithoutCad) {
  const Json request = {{"csv", test::read_text(std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples/ramp2d/ramp.csv")},
                        {"csv_name", "ramp.csv"}};
  const Reply r = api_->post("/api/curves", request);
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["frame"], "xy");
  EXPECT_TRUE(r.body["axis"].is_null());
  EXPECT_TRUE(r.body["summary"]["cad"].is_null());
  EXPECT_GT(r.body["summary"]["nodes"].get<int>(), 100);
  EXPECT_EQ(r.body["summary"]["max_node_distance_to_cad"], 0.0);
}

// Issue 45, item 2: a 2D drawing (gmsh's channel with a forward-facing step) loads with its
// edges, and a wall on some of them is the curve of those edges: a planar table deflects it, and
// in displacement form the fillet stays a circle (moved by the table's rigid shift).
TEST_F(ServeApi, ReconstructsA2DWallOnCadEdges) {
  const test::ChannelStep channel;
  const Reply loaded = api_->upload("channel.step", test::read_text(channel.path("channel.step")));
  ASSERT_EQ(loaded.status, 201) << loaded.text;
  EXPECT_EQ(loaded.body["face_count"], 1);
  EXPECT_EQ(loaded.body["edge_count"], 7);
  ASSERT_EQ(loaded.body["edges"].size(), 7u);
  const std::string model = loaded.body["model"];
  channel.write_table("bottom.csv", {0.0, 0.03});
  Json request = {{"model", model},
                  {"edges", channel.wall_edges()},
                  {"csv", test::read_text(channel.path("bottom.csv"))},
                  {"form", "displacement"},
                  {"samples", 400}};
  const Reply r = api_->post("/api/curves", request);
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["frame"], "xy");
  EXPECT_EQ(r.body["edges"], Json(channel.wall_edges()));
  const Json& breaks = r.body["edge_breaks"];
  ASSERT_EQ(breaks.size(), 5u);
  int on_fillet = 0;
  for (const Json& sample : r.body["deformed"]["samples"]) {
    const double t = sample[0].get<double>();
    if (t <= breaks[2].get<double>() || t >= breaks[3].get<double>()) continue;
    ++on_fillet;
    EXPECT_LT(test::StepWall::off_fillet({sample[1].get<double>(), sample[2].get<double>()}, {0.0, 0.03}), 1e-9) << t;
  }
  EXPECT_GT(on_fillet, 10);

  request["faces"] = {1};
  expect_error(api_->post("/api/curves", request), 400, "edges: give either \"faces\"");
  request.erase("faces");
  request["edges"] = {1, 9};
  expect_error(api_->post("/api/curves", request), 400, "edges: the model has 7 edges; there is no edge 9");
  request["edges"] = {1, 2, 4};
  expect_error(api_->post("/api/curves", request), 422, "do not form one chain");
}

// A body the fuzz target of the service made from the ramp's table (docs/fuzzing.md): one node
// moved 2e10 away bunches the others within 4e-9 of the curve's length, and the degree-3
// interpolation was singular: a 500 ("critical internal error") before it was a user error.
TEST_F(ServeApi, NodesTooBunchedToInterpolateAreAUserError) {
  const Reply r = api_->post("/api/curves", Json::parse(test::read_text(test::data_path("fuzz/serve-json-bunched-nodes.json"))));
  expect_error(r, 422, "ramp.csv: the FEM nodes cannot be interpolated by a curve of degree 3");
  EXPECT_THAT(r.text, HasSubstr("of the curve's length apart; look for a node far from the others"));
}

TEST_F(ServeApi, KeepsTheCurvesUsedMostRecently) {
  const Json table = {{"csv", "x,y,dx,dy\n0,0,0,0\n1,0,0,0.1\n"}, {"samples", 2}};
  std::vector<std::string> ids;
  for (int i = 0; i < 70; ++i) {
    const Reply r = api_->post("/api/curves", table);
    ASSERT_EQ(r.status, 201) << r.text;
    ids.push_back(r.body["curve"]);
    if (i >= 1) {
      EXPECT_EQ(api_->get("/api/curves/" + ids.front()).status, 200);  // keeps the first one in use
    }
  }
  // 64 are kept: the first (used all along) and the 63 newest; the 2nd to the 7th were dropped.
  EXPECT_EQ(api_->get("/api/curves/" + ids[0]).status, 200);
  for (std::size_t i = 1; i <= 6; ++i) {
    expect_error(api_->get("/api/curves/" + ids[i]), 404, "dropped as the least recently used of 64");
  }
  for (std::size_t i = 7; i < ids.size(); ++i) EXPECT_EQ(api_->get("/api/curves/" + ids[i]).status, 200) << ids[i];
}

TEST_F(ServeApi, CurveRequestErrorsSayWhatIsWrong) {
  const std::string model = load_cone();
  const Json good = cone_curve_request(model);
  auto with = [&](const std::string& key, const Json& value) {
    Json r = good;
    r[key] = value;
    return r;
  };
  auto without = [&](const std::string& key) {
    Json r = good;
    r.erase(key);
    return r;
  };
  expect_error(api_->post("/api/curves", without("csv")), 400, "csv: required");
  expect_error(api_->post("/api/curves", with("csv", "id,x,y,z,dx,dy,dz\n1,2,3\n")), 400, "cone.csv:2");
  expect_error(api_->post("/api/curves", with("csv", "a,b\n1,2\n")), 400, "csv:");
  expect_error(api_->post("/api/curves", with("csv", "x,y,z,dx,dy,dz\n")), 400, "csv:");
  expect_error(api_->post("/api/curves", with("degree", 7)), 400, "degree: expected an integer from 1 to 5, got 7");
  expect_error(api_->post("/api/curves", with("degree", 1.5)), 400, "degree");
  expect_error(api_->post("/api/curves", with("form", "spline")), 400, "form: expected \"curve\" or \"displacement\"");
  expect_error(api_->post("/api/curves", with("tolerance", -1)), 400, "tolerance");
  expect_error(api_->post("/api/curves", with("drop_far_nodes", "yes")), 400, "drop_far_nodes: expected true or false");
  expect_error(api_->post("/api/curves", with("model", "m404")), 404, "no model 'm404'");
  expect_error(api_->post("/api/curves", with("unit", "mm")), 400, "a CAD model's unit applies");
  expect_error(api_->post("/api/curves", with("samples", 10'000'000)), 400, "samples");
  expect_error(api_->post("/api/curves", without("faces")), 400, "faces: required");
  expect_error(api_->post("/api/curves", with("csv", "r,z,dr,dz\n1,2,0,0\n3,4,0,0\n")), 400,
               "meridional (r, z) nodes need the axis");
  expect_error(api_->post("/api/curves", with("csv", "x,y,dx,dy\n1,2,0,0\n3,4,0,0\n")), 422, "planar (x,y) tables");
  Json no_model = without("model");
  expect_error(api_->post("/api/curves", no_model), 400, "faces: needs \"model\"");
  no_model.erase("faces");
  expect_error(api_->post("/api/curves", no_model), 422, "nodes without CAD need \"axis\"");
  expect_error(api_->post("/api/curves", with("faces", {3})), 422, "axis");
}

TEST_F(ServeApi, ProjectsPointsOntoAStageOfTheCurve) {
  const std::string model = load_cone();
  const Reply curve = api_->post("/api/curves", cone_curve_request(model));
  ASSERT_EQ(curve.status, 201);
  const std::string path = "/api/curves/" + curve.body["curve"].get<std::string>() + "/project";
  // (r, z) = (30.125, -75.1) is on the deflected curve (s = 0.5); at stage 0 it is off the cone.
  const Reply on = api_->post(path, {{"points", {{30.125, -75.1}}}});
  ASSERT_EQ(on.status, 200) << on.text;
  EXPECT_EQ(on.body["lambda"], 1.0);
  EXPECT_LT(on.body["projections"][0]["distance"].get<double>(), 1e-9);
  EXPECT_NEAR(on.body["projections"][0]["parameter"].get<double>(), 0.5, 1e-9);
  const Reply cold = api_->post(path, {{"points", {{30.125, -75.1}}}, {"lambda", 0}});
  EXPECT_GT(cold.body["projections"][0]["distance"].get<double>(), 0.05);
  // A point in space keeps its angle about the axis: at 90 degrees (on +y), 1 mm outside.
  const Reply space = api_->post(path, {{"points", {{0.0, 31.125, -75.1 + 80.0}}}});
  ASSERT_EQ(space.status, 200) << space.text;
  const Json& p = space.body["projections"][0];
  EXPECT_NEAR(p["point"][0].get<double>(), 0.0, 1e-9);
  EXPECT_GT(p["point"][1].get<double>(), 30.0);
  EXPECT_NEAR(p["distance"].get<double>(), std::cos(std::atan(60.0 / 150.0)), 0.01);

  expect_error(api_->post(path, Json::object()), 400, "points: expected an array of points");
  expect_error(api_->post(path, {{"points", {{1, 2}, {1, 2, 3}}}}), 400, "points[1]: expected 2 numbers");
  expect_error(api_->post(path, {{"points", {{1, "a"}}}}), 400, "points[0]");
  expect_error(api_->post(path, {{"points", {{1, 2, 3, 4}}}}), 400, "points: expected");
  expect_error(api_->post(path, {{"points", {{1, 2}}}, {"lambda", 2}}), 400, "lambda: expected a number from 0 to 1");
  Json many = Json::array();
  for (int i = 0; i <= 100'000; ++i) many.push_back({0, 0});
  expect_error(api_->post(path, {{"points", many}}), 400, "more than the limit of 100000");
  expect_error(api_->post("/api/curves/c999/project", {{"points", {{1, 2}}}}), 404, "no curve 'c999'");
}

TEST_F(ServeApi, DownloadsTheCurvesAsStepIgesAndCsv) {
  const std::string model = load_cone();
  const Reply curve = api_->post("/api/curves", cone_curve_request(model));
  const std::string base = "/api/curves/" + curve.body["curve"].get<std::string>();
  const auto step = api_->client().Get((base + "/download?format=step").c_str());
  ASSERT_TRUE(step);
  EXPECT_EQ(step->status, 200);
  EXPECT_EQ(step->get_header_value("Content-Type"), "model/step");
  EXPECT_THAT(step->get_header_value("Content-Disposition"), HasSubstr("attachment; filename=\"c"));
  EXPECT_THAT(step->body, HasSubstr("GEOMETRIC_CURVE_SET('deformed'"));
  EXPECT_THAT(step->body, HasSubstr("SI_UNIT(.MILLI.,.METRE.)"));
  const auto iges = api_->client().Get((base + "/download?format=iges").c_str());
  ASSERT_TRUE(iges);
  EXPECT_THAT(iges->body, HasSubstr("undeform"));
  const auto csv = api_->client().Get((base + "/download?format=csv").c_str());
  ASSERT_TRUE(csv);
  EXPECT_THAT(csv->body, ::testing::StartsWith("t,r,z\n0,60.5,-150.2\n"));
  EXPECT_THAT(csv->get_header_value("Content-Disposition"), HasSubstr("-deformed.csv"));
  expect_error(api_->get(base + "/download"), 400, "format: required");
  expect_error(api_->get(base + "/download?format=dwg"), 400, "expected step, iges or csv, got 'dwg'");
  expect_error(api_->get("/api/curves/c999/download?format=csv"), 404, "no curve");
  EXPECT_EQ(api_->del(base).status, 200);
  expect_error(api_->get(base), 404, "no curve");
  expect_error(api_->del(base), 404, "no curve");
}

TEST_F(ServeApi, BadRequestsGetJsonErrors) {
  expect_error(api_->get("/api/nothing"), 404, "no route GET /api/nothing");
  const Reply put = api_->post_text("/api/health", "{}", "application/json");
  expect_error(put, 405, "use GET");
  const auto really_put = api_->client().Put("/api/models", "{}", "application/json");
  ASSERT_TRUE(really_put);
  EXPECT_EQ(really_put->status, 405);
  EXPECT_EQ(really_put->get_header_value("Allow"), "GET, POST");
  expect_error(api_->post_text("/api/curves", "{\"csv\": ", "application/json"), 400, "the body is not valid JSON");
  expect_error(api_->post_text("/api/curves", "[1, 2]", "application/json"), 400, "must be a JSON object");
  expect_error(api_->post_text("/api/curves", "", "application/json"), 400, "not valid JSON");
  expect_error(api_->post_text("/api/curves", "csv=1", "application/x-www-form-urlencoded"), 415,
               "send JSON (Content-Type: application/json)");
}

TEST_F(ServeApi, ServesThePageFromTheBinary) {
  const auto page = api_->client().Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_THAT(page->get_header_value("Content-Security-Policy"), HasSubstr("default-src 'self'"));
  EXPECT_THAT(page->body, HasSubstr("<script src=\"app.js\""));
  EXPECT_EQ(page->body, test::read_text(std::filesystem::path(HOTMESH_SOURCE_DIR) / "app/serve/web/index.html"));
  for (const std::string name : {"app.js", "style.css", "favicon.svg"}) {
    const auto file = api_->client().Get(("/" + name).c_str());
    ASSERT_TRUE(file);
    EXPECT_EQ(file->status, 200) << name;
    EXPECT_EQ(file->body, test::read_text(std::filesystem::path(HOTMESH_SOURCE_DIR) / "app/serve/web" / name)) << name;
  }
}

TEST(ServeLimits, BodiesAboveTheLimitGet413AndTablesAboveTheNodeLimit400) {
  test::ServeProcess server({"--max-body", "1", "--max-nodes", "10"});
  Api api(server.port());
  const std::string big(3u << 20, ' ');
  expect_error(api.post_text("/api/curves", "{\"csv\": \"" + big + "\"}", "application/json"), 413,
               "larger than the limit of 1048576 bytes");
  expect_error(api.upload("big.step", big), 413, "larger than the limit");
  expect_error(api.post("/api/curves", {{"csv", test::cone_nodes(11)}, {"axis", {{"origin", {0, 0, 0}}, {"direction", {0, 0, 1}}}}}),
               400, "11 nodes, more than the limit of 10 nodes");
  EXPECT_EQ(api.post("/api/curves", {{"csv", test::cone_nodes(10)}, {"axis", {{"origin", {0, 0, 0}}, {"direction", {0, 0, 1}}}}})
                .status,
            201);
  EXPECT_EQ(api.get("/api/health").status, 200);  // still serving
  EXPECT_EQ(server.stop(SIGTERM), 0) << server.log();
}

TEST(ServeSecurity, WithoutRootNothingIsReadByPath) {
  test::ServeProcess server;
  Api api(server.port());
  expect_error(api.post("/api/models", {{"path", test::data_path("cad/OCC8842_cone_CATIA.igs").string()}}), 403,
               "loading by path is off");
  const Reply files = api.get("/api/files");
  EXPECT_EQ(files.body["root"], false);
  EXPECT_TRUE(files.body["files"].empty());
  EXPECT_EQ(server.stop(SIGINT), 0) << server.log();
}

TEST(ServeShutdown, SigintAndSigtermStopCleanlyAndRemoveTheUploads) {
  for (const int signal : {SIGINT, SIGTERM}) {
    test::TempDir tmp;
    test::ServeProcess server({}, {{"TMPDIR", tmp.path().string()}});
    Api api(server.port());
    ASSERT_EQ(api.upload("cone.igs", cone_file()).status, 201);
    std::vector<std::filesystem::path> folders;
    for (const auto& e : std::filesystem::directory_iterator(tmp.path())) folders.push_back(e.path());
    ASSERT_EQ(folders.size(), 1u);
    EXPECT_THAT(folders[0].filename().string(), ::testing::StartsWith("hotmesh-serve-"));
    EXPECT_EQ(std::filesystem::status(folders[0]).permissions() & std::filesystem::perms::all,
              std::filesystem::perms::owner_all);  // private
    EXPECT_EQ(server.stop(signal), 0) << server.log();
    EXPECT_FALSE(std::filesystem::exists(folders[0]));
    EXPECT_THAT(server.log(), HasSubstr(signal == SIGINT ? "SIGINT received" : "SIGTERM received"));
  }
}

TEST(ServeShutdown, APortInUseIsAnError) {
  test::ServeProcess first;
  const auto r = test::run_command("timeout 30 " + std::string(HOTMESH_EXE) + " serve --port " + std::to_string(first.port()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("cannot listen on 127.0.0.1 port"));
  EXPECT_EQ(first.stop(SIGTERM), 0);
}

}  // namespace
}  // namespace hotmesh::app
