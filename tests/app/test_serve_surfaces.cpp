// Tests of `hotmesh serve`'s surfaces (POST /api/surfaces and the routes of a surface): the
// deflection field d(t, s) reconstructed on a CAD face of any shape from FEM nodes (section 4.2
// on B-spline surfaces, issue 23), the same run as `hotmesh surface`.
//
// The CAD is built here: a wavy bicubic B-spline face over (t, s) in [0, 1]^2 with x = t and
// y = s (as in test_surface_command.cpp), uploaded as STEP in metres. The FEM deflections are a
// polynomial of degree 2 in (t, s), so a degree-2 field reproduces them everywhere: at the nodes
// and on the answer's sample grid, to round-off.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <signal.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "serve_client.hpp"
#include "serve_process.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using geometry::BSplineSurface;
using geometry::Vec3;
using test::Api;
using test::expect_error;
using test::Json;
using test::Reply;

/// Bicubic, uniform knots, poles at the Greville abscissae in x and y (so x = t, y = s) and
/// wavy heights.
BSplineSurface wavy_face() {
  const std::vector<double> knots{0, 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1, 1};
  const double greville[] = {0.0, 1.0 / 9, 1.0 / 3, 2.0 / 3, 8.0 / 9, 1.0};
  std::vector<Vec3> poles;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) poles.push_back({greville[i], greville[j], 0.08 * std::sin(2.1 * i + 0.4) * std::cos(1.7 * j)});
  }
  return BSplineSurface(3, 3, knots, knots, std::move(poles));
}

/// A deflection of degree 2 in t and s.
Vec3 deflection(double t, double s) {
  return {0.01 * s * s + 0.002 * t, -0.005 * s + 0.02 * t * s, 0.02 * s * (1 - s) + 0.03 * t * (1 - t)};
}

/// The face and a second one apart from it (a flat square at z = 5, sharing no edge), as STEP.
std::string faces_step() {
  geometry::CadExport content;
  content.unit = geometry::LengthUnit::metre;
  const BSplineSurface flat(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {{0, 0, 5}, {0, 1, 5}, {1, 0, 5}, {1, 1, 5}});
  content.surfaces = {{"wavy", wavy_face()}, {"flat", flat}};
  return geometry::to_step(content);
}

/// FEM nodes on an n x n grid of the wavy face, ids 100, 101, ...
std::string grid_table(int n) {
  const BSplineSurface face = wavy_face();
  geometry::DeflectionSamples nodes;
  nodes.frame = geometry::SampleFrame::cartesian;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double t = i / (n - 1.0), s = j / (n - 1.0);
      nodes.points.push_back(face.point(t, s));
      nodes.deflections.push_back(deflection(t, s));
      nodes.ids.push_back(100 + static_cast<std::int64_t>(nodes.ids.size()));
    }
  }
  return io::format_deflection_csv(nodes);
}

Vec3 vec3(const Json& v) { return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}; }

class ServeSurfaces : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<test::ServeProcess>();
    api_ = std::make_unique<Api>(server_->port());
    const Reply r = api_->upload("faces.step", faces_step(), "m");
    ASSERT_EQ(r.status, 201) << r.text;
    model_ = r.body["model"];
  }

  void TearDown() override {
    api_.reset();
    EXPECT_EQ(server_->stop(SIGTERM), 0) << server_->log();
  }

  Json request(int nodes = 5) const {
    return {{"model", model_}, {"faces", {1}}, {"csv", grid_table(nodes)}, {"csv_name", "wavy.csv"}, {"degree", 2}};
  }

  std::unique_ptr<test::ServeProcess> server_;
  std::unique_ptr<Api> api_;
  std::string model_;
};

// A deflection of degree <= q is reproduced: residuals at round-off at the nodes, and the
// answer's grid of d(t, s) is the polynomial itself.
TEST_F(ServeSurfaces, ReproducesPolynomialDeflectionOnBSplineFace) {
  const Reply r = api_->post("/api/surfaces", request());
  ASSERT_EQ(r.status, 201) << r.text;
  const Json& summary = r.body["summary"];
  EXPECT_EQ(summary["degree"], 2);
  EXPECT_EQ(summary["nodes"], 25);
  EXPECT_EQ(summary["used_nodes"], 25);
  EXPECT_LT(summary["max_node_residual"].get<double>(), 1e-12);
  EXPECT_LT(summary["max_node_distance_to_cad"].get<double>(), 1e-9);
  EXPECT_EQ(summary["inputs"]["cad"], "faces.step");
  EXPECT_EQ(summary["inputs"]["fem"], "wavy.csv");
  EXPECT_EQ(summary["inputs"]["unit"], "m");
  ASSERT_EQ(summary["faces"].size(), 1u);
  EXPECT_EQ(summary["faces"][0]["method"], "interpolation");
  EXPECT_EQ(r.body["max_edge_gap"], summary["max_edge_gap"]);
  EXPECT_EQ(r.body["left_out"], Json::array());

  const BSplineSurface face = wavy_face();
  ASSERT_EQ(r.body["nodes"].size(), 25u);
  for (int k = 0; k < 25; ++k) {
    const Json& node = r.body["nodes"][static_cast<std::size_t>(k)];
    const double t = (k / 5) / 4.0, s = (k % 5) / 4.0;
    EXPECT_EQ(node["index"], k);
    EXPECT_EQ(node["id"], 100 + k);
    EXPECT_EQ(node["line"], k + 2);  // after the header
    EXPECT_EQ(node["label"], "node " + std::to_string(100 + k) + " (line " + std::to_string(k + 2) + ")");
    EXPECT_EQ(node["face"], 1);
    EXPECT_NEAR(node["t"].get<double>(), t, 1e-9);
    EXPECT_NEAR(node["s"].get<double>(), s, 1e-9);
    EXPECT_LT(node["distance"].get<double>(), 1e-9);
    EXPECT_LT(node["residual"].get<double>(), 1e-12);
    EXPECT_LT(geometry::distance(vec3(node["deflection"]), deflection(t, s)), 1e-15);
  }

  ASSERT_EQ(r.body["faces"].size(), 1u);
  const Json& f = r.body["faces"][0];
  EXPECT_EQ(f["id"], 1);
  EXPECT_EQ(f["kind"], summary["faces"][0]["kind"]);
  EXPECT_EQ(f["parameter_range"], summary["faces"][0]["parameter_range"]);
  const Json& grid = f["grid"];
  ASSERT_EQ(grid["size"], 24);
  ASSERT_EQ(grid["t"].size(), 24u);
  ASSERT_EQ(grid["points"].size(), 24u * 24u);
  ASSERT_EQ(grid["deflections"].size(), 24u * 24u);
  double worst_point = 0.0, worst_deflection = 0.0;
  for (std::size_t i = 0; i < 24; ++i) {
    for (std::size_t j = 0; j < 24; ++j) {
      const double t = grid["t"][i], s = grid["s"][j];
      worst_point = std::max(worst_point, geometry::distance(vec3(grid["points"][i * 24 + j]), face.point(t, s)));
      worst_deflection = std::max(worst_deflection, geometry::distance(vec3(grid["deflections"][i * 24 + j]), deflection(t, s)));
    }
  }
  EXPECT_LT(worst_point, 1e-12);
  EXPECT_LT(worst_deflection, 1e-12);
}

TEST_F(ServeSurfaces, IsKeptDownloadedAndDeleted) {
  Json req = request();
  req["grid"] = 3;
  const Reply made = api_->post("/api/surfaces", req);
  ASSERT_EQ(made.status, 201) << made.text;
  const std::string id = made.body["surface"];
  EXPECT_EQ(made.body["faces"][0]["grid"]["points"].size(), 9u);
  const Reply again = api_->get("/api/surfaces/" + id);
  ASSERT_EQ(again.status, 200);
  EXPECT_EQ(again.body, made.body);

  EXPECT_EQ(made.body["downloads"]["step"], "/api/surfaces/" + id + "/download?format=step");
  const Reply step = api_->get(made.body["downloads"]["step"]);
  ASSERT_EQ(step.status, 200);
  EXPECT_THAT(step.text, ::testing::StartsWith("ISO-10303-21;"));
  EXPECT_THAT(step.text, ::testing::HasSubstr("face 1"));
  EXPECT_THAT(step.headers.find("Content-Disposition")->second, ::testing::HasSubstr(id + "-deformed.step"));
  const Reply iges = api_->get(made.body["downloads"]["iges"]);
  EXPECT_EQ(iges.status, 200);
  EXPECT_GT(iges.text.size(), 1000u);
  expect_error(api_->get("/api/surfaces/" + id + "/download?format=csv"), 400, "format: expected step or iges");
  expect_error(api_->get("/api/surfaces/" + id + "/download"), 400, "format: required");

  EXPECT_EQ(api_->del("/api/surfaces/" + id).status, 200);
  expect_error(api_->get("/api/surfaces/" + id), 404, "no surface '" + id + "'");
  expect_error(api_->del("/api/surfaces/" + id), 404, "no surface");
}

TEST_F(ServeSurfaces, NodesFarFromTheFacesAreLeftOutOnRequest) {
  Json req = request();
  req["csv"] = req["csv"].get<std::string>() + "999,0.5,0.5,3,0,0,0\n";
  expect_error(api_->post("/api/surfaces", req), 422, "csv: wavy.csv: 1 of 26 FEM nodes are farther than");
  req["drop_far_nodes"] = true;
  const Reply r = api_->post("/api/surfaces", req);
  ASSERT_EQ(r.status, 201) << r.text;
  EXPECT_EQ(r.body["summary"]["used_nodes"], 25);
  ASSERT_EQ(r.body["left_out"].size(), 1u);
  EXPECT_EQ(r.body["left_out"][0]["id"], 999);
  EXPECT_EQ(r.body["left_out"][0]["line"], 27);
  EXPECT_NEAR(r.body["left_out"][0]["distance"].get<double>(), 3.0, 0.2);
  EXPECT_EQ(r.body["summary"]["rejected_nodes"].size(), 1u);
}

TEST_F(ServeSurfaces, BadRequestsNameTheField) {
  const auto post = [&](const Json& body) { return api_->post("/api/surfaces", body); };
  Json req = request();
  req.erase("model");
  expect_error(post(req), 400, "model: required");
  req = request();
  req["model"] = "m99";
  expect_error(post(req), 404, "no model 'm99'");
  req = request();
  req["faces"] = {3};
  expect_error(post(req), 400, "faces: the model has 2 faces; there is no face 3");
  req["faces"] = Json::array();
  expect_error(post(req), 400, "faces:");
  req = request();
  req["form"] = "curve";
  expect_error(post(req), 400, "unknown key \"form\"");
  req = request();
  req["grid"] = 1;
  expect_error(post(req), 400, "grid: expected an integer from 2 to 200");
  req["grid"] = 100000000;
  expect_error(post(req), 400, "grid: expected an integer from 2 to 200");
  req = request();
  req["degree"] = 9;
  expect_error(post(req), 400, "degree: expected an integer from 1 to");
  req = request();
  req["csv"] = "r,z,dr,dz\n0.1,0.2,0,0\n0.2,0.3,0,0\n";
  expect_error(post(req), 422, "csv: wavy.csv: a wall reconstructed on CAD faces needs a cartesian (x, y, z) table");
  req = request(2);  // 4 nodes, too few for degree 2
  expect_error(post(req), 422, "csv: wavy.csv: CAD face 1:");
  req = request();
  req["faces"] = {1, 2};  // the flat face lies apart from the wavy one
  expect_error(post(req), 422, "csv: wavy.csv: the CAD faces of the wall do not join");
  req = request();
  req["csv"] = "x,y,z,dx,dy,dz\n1,2\n";
  expect_error(post(req), 400, "csv: wavy.csv:2");
  expect_error(api_->post_text("/api/surfaces", "{", "application/json"), 400, "");
}

// The sample grid is bounded per direction and over all faces together, before any work.
TEST_F(ServeSurfaces, TheGridOfAllFacesIsBounded) {
  const Reply duct = api_->upload("duct.step", test::read_text(std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples/duct3d/duct.step"), "mm");
  ASSERT_EQ(duct.status, 201) << duct.text;
  const Json req = {{"model", duct.body["model"]}, {"faces", {1, 2, 3, 4, 5, 6}}, {"csv", grid_table(5)}, {"grid", 200}};
  expect_error(api_->post("/api/surfaces", req), 400,
               "grid: 200 x 200 points on each of 6 faces is more than the limit of 200000 points in one answer");
}

// /api/health says what the stores keep: how many surfaces, and their bytes as the service
// reckons them (the answer's text twice), within the budget.
TEST_F(ServeSurfaces, HealthSaysWhatTheStoresKeep) {
  Json before = api_->get("/api/health").body["kept"];
  EXPECT_EQ(before["models"], 1);
  EXPECT_EQ(before["surfaces"], 0);
  EXPECT_EQ(before["surface_bytes"], 0);
  const Reply made = api_->post("/api/surfaces", request());
  ASSERT_EQ(made.status, 201) << made.text;
  const Json kept = api_->get("/api/health").body["kept"];
  EXPECT_EQ(kept["surfaces"], 1);
  EXPECT_EQ(kept["surface_bytes"], 2 * made.body.dump().size());
  EXPECT_EQ(kept["max_surface_bytes"], 256u << 20);
  EXPECT_EQ(api_->del("/api/surfaces/" + made.body["surface"].get<std::string>()).status, 200);
  EXPECT_EQ(api_->get("/api/health").body["kept"]["surface_bytes"], 0);
}

// Clients posting surfaces on one model at once, and reading them back, all get their answers;
// the store keeps the 32 used last.
TEST_F(ServeSurfaces, ConcurrentClientsGetTheirSurfacesAndTheStoreIsBounded) {
  Json req = request();
  req["grid"] = 4;
  const Reply first = api_->post("/api/surfaces", req);
  ASSERT_EQ(first.status, 201) << first.text;
  std::atomic<int> failures{0};
  std::vector<std::thread> clients;
  for (int c = 0; c < 4; ++c) {
    clients.emplace_back([&] {
      Api api(server_->port());
      for (int i = 0; i < 10; ++i) {
        const Reply made = api.post("/api/surfaces", req);
        if (made.status != 201 || made.body["summary"]["max_node_residual"].get<double>() > 1e-12) {
          ++failures;
          continue;
        }
        const std::string id = made.body["surface"];
        if (api.get("/api/surfaces/" + id).status != 200) ++failures;
        if (api.get("/api/surfaces/" + id + "/download?format=iges").status != 200) ++failures;
      }
    });
  }
  for (auto& client : clients) client.join();
  EXPECT_EQ(failures, 0);
  expect_error(api_->get("/api/surfaces/" + first.body["surface"].get<std::string>()), 404,
               "dropped as the least recently used of 32");
  EXPECT_EQ(api_->get("/api/surfaces/s41").status, 200);
}

}  // namespace
}  // namespace hotmesh::app
