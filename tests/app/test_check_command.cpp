// Tests of `hotmesh check`: a consistent mesh passes and a perturbed one fails naming the node
// that was moved, for the real ramp2d sample (a mesh deformed by hotmesh deform, checked against
// the deflection table), for a revolved 3D mesh built here on a cylinder and a plane written
// to STEP (undeformed against the CAD faces, deformed against the deflected cylinder) and for
// the stator-well sample's casing, whose two faces lie on either side of the blade row; checks
// driven by a case file are in test_check_case_files.cpp; the faces' two-sided distance, which sees the corner of the prescribed ramp that an
// edge cuts (--wall-tol); how CAD faces are taken (issue 45: a forward-facing step written with
// OpenCASCADE, planes and one cylinder fillet, is measured on its faces, undeformed and
// deflected; faces all about one axis through their meridional curve; --mode); the JSON and
// JUnit reports, also of a check that cannot be made; user errors; 2D meshes against CAD edges (a
// channel with a forward-facing step drawn and meshed by gmsh) and, axisymmetric, against revolved
// faces about an axis.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "channel_step.hpp"
#include "check_command_support.hpp"
#include "occt_fixtures.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using namespace check_test;  // NOLINT: the helpers of these tests
using ::testing::HasSubstr;

TEST(CheckCommand, RampSampleDeformedMeshLiesOnTheDeflectedWallAndAMovedNodeIsFound) {
  test::TempDir dir;
  const std::filesystem::path sample = std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples/ramp2d";
  const auto deformed = hotmesh("-q deform " + q(sample / "ramp2d.yaml") + " -o " + q(dir / "out"));
  ASSERT_EQ(deformed.exit_code, 0) << deformed.output;
  const std::string table = " --deflection bottom=" + q(sample / "ramp.csv");

  const auto [pass_code, pass] = check_json("--mesh " + q(dir / "out/deformed.msh") + table);
  EXPECT_EQ(pass_code, 0) << pass.dump(2);
  EXPECT_EQ(pass["passed"], true);
  ASSERT_EQ(pass["patches"].size(), 1u);
  EXPECT_EQ(pass["patches"][0]["patch"], "bottom");
  EXPECT_EQ(pass["patches"][0]["nodes"], 58);
  EXPECT_LT(pass["patches"][0]["max_distance"].get<double>(), 1e-12);
  EXPECT_NEAR(pass["tolerance"].get<double>(), 1e-6 * std::sqrt(5.0), 1e-12);  // 1e-6 of the 2 x 1 channel
  // The checked mesh's cells as a flow solver sees them, as deform's report.json gave them.
  const auto report = nlohmann::json::parse(test::read_text(dir / "out/report.json"));
  for (const char* measure : {"non_orthogonality", "skewness", "volume_ratio", "aspect_ratio"}) {
    const double reported = report["quality"][measure]["max"].get<double>();
    EXPECT_NEAR(pass["quality"][measure]["max"].get<double>(), reported, 1e-9 * reported) << measure;
    EXPECT_EQ(pass["quality"][measure]["worst_cell"], report["quality"][measure]["worst_cell"]) << measure;
  }
  EXPECT_GT(report["quality"]["non_orthogonality"]["max"].get<double>(), 1.0);
  EXPECT_THAT(hotmesh("check --mesh " + q(dir / "out/deformed.msh") + table).output, HasSubstr("non-orthogonality max"));

  // Move one node of the flat part of the wall 1 mm up: the check fails and names it.
  mesh::Mesh mesh = io::read_gmsh(dir / "out/deformed.msh");
  const mesh::NodeId moved = nearest_node(mesh, "bottom", {0.3, 0.0, 0.0});
  mesh.points[static_cast<std::size_t>(moved)].y += 1e-3;
  io::write_gmsh(dir / "perturbed.msh", mesh);
  const auto [fail_code, fail] = check_json("--mesh " + q(dir / "perturbed.msh") + table);
  EXPECT_EQ(fail_code, 1);
  EXPECT_EQ(fail["passed"], false);
  EXPECT_EQ(fail["patches"][0]["worst_node"]["id"], mesh.node_id(moved));
  EXPECT_NEAR(fail["patches"][0]["max_distance"].get<double>(), 1e-3, 1e-9);

  // A looser tolerance lets it pass; JUnit names the node in a <failure> otherwise.
  EXPECT_EQ(hotmesh("-q check --tol 2e-3 --mesh " + q(dir / "perturbed.msh") + table).exit_code, 0);
  const auto junit = hotmesh("-q check --format junit --mesh " + q(dir / "perturbed.msh") + table);
  EXPECT_EQ(junit.exit_code, 1);
  EXPECT_THAT(junit.output, HasSubstr("<testcase classname=\"hotmesh.check.perturbed\" name=\"bottom\""));
  EXPECT_THAT(junit.output, HasSubstr("<failure type=\"tolerance\" message=\"node " + std::to_string(mesh.node_id(moved))));
}

/// The node of `mesh` whose number in the mesh file is `id`.
const geometry::Vec3& node_point(const mesh::Mesh& mesh, std::int64_t id) {
  for (std::size_t n = 0; n < mesh.points.size(); ++n) {
    if (mesh.node_id(static_cast<mesh::NodeId>(n)) == id) return mesh.points[n];
  }
  throw std::runtime_error("no node " + std::to_string(id));
}

// Issue 20: the prescribed ramp's nodes lie on the deflected ramp (node distances at round-off)
// but no node lands on its corner A (0.975, 0), so the edge between the nodes on either side
// cuts it by about 0.025 h. The faces' two-sided distance sees it and names the corner and the
// edge; it is reported only, unless --wall-tol is given, which then fails the patch.
TEST(CheckCommand, CornerCutByAnEdgeOfTheRampIsSeenByTheFacesNotByTheNodes) {
  test::TempDir dir;
  const std::filesystem::path case_file = kSamples / "ramp2d/ramp2d.yaml";
  const auto deformed = hotmesh("-q deform " + q(case_file) + " -o " + q(dir / "out"));
  ASSERT_EQ(deformed.exit_code, 0) << deformed.output;
  const std::string check = q(dir / "out/deformed.msh") + " --case " + q(case_file);

  const auto [code, report] = check_json(check);
  ASSERT_EQ(code, 0) << report.dump(2);
  EXPECT_TRUE(report["wall_tolerance"].is_null());
  ASSERT_EQ(report["patches"].size(), 1u);
  const Json& patch = report["patches"][0];
  EXPECT_LT(patch["max_distance"].get<double>(), 1e-12);
  const Json& wall = patch["wall"];
  EXPECT_EQ(wall["edges"], 57);
  EXPECT_NEAR(wall["hausdorff"].get<double>(), 0.025, 5e-4);
  EXPECT_EQ(wall["worst"], "shape_to_mesh");
  EXPECT_NEAR(wall["worst_point"][0].get<double>(), 0.975, 1e-9);
  EXPECT_NEAR(wall["worst_point"][1].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(wall["passed"], true);
  const mesh::Mesh mesh = io::read_gmsh(dir / "out/deformed.msh");
  const geometry::Vec3& a = node_point(mesh, wall["shape_to_mesh"]["edge_nodes"][0].get<std::int64_t>());
  const geometry::Vec3& b = node_point(mesh, wall["shape_to_mesh"]["edge_nodes"][1].get<std::int64_t>());
  EXPECT_LT(std::min(a.x, b.x), 0.975);  // the edge across the corner
  EXPECT_GT(std::max(a.x, b.x), 0.975);
  EXPECT_LT(wall["mesh_to_shape"]["distance"].get<double>(), wall["hausdorff"].get<double>());
  EXPECT_THAT(hotmesh("-q check " + check).output, HasSubstr("faces: two-sided distance 2.50"));

  const auto [tight_code, tight] = check_json(check + " --wall-tol 1e-3");
  EXPECT_EQ(tight_code, 1) << tight.dump(2);
  EXPECT_EQ(tight["wall_tolerance"], 1e-3);
  EXPECT_EQ(tight["patches"][0]["passed"], false);
  EXPECT_EQ(tight["patches"][0]["wall"]["passed"], false);
  EXPECT_EQ(hotmesh("-q check " + check + " --wall-tol 0.03").exit_code, 0);
  const auto junit = hotmesh("-q check " + check + " --wall-tol 1e-3 --format junit -o " + q(dir / "check.xml"));
  EXPECT_EQ(junit.exit_code, 1);
  const auto parsed = parse_junit(dir / "check.xml");
  ASSERT_EQ(parsed.exit_code, 0) << parsed.output;
  EXPECT_THAT(parsed.output, HasSubstr("1 1 0 [('bottom', 'failure')]"));
  EXPECT_THAT(parsed.output, HasSubstr("from the reference shape at (0.975, 0, 0) (shape_to_mesh, face edge of nodes"));
  EXPECT_THAT(parsed.output, HasSubstr("above the wall tolerance 1.000e-03"));
}

/// A 30-degree sector of the annulus 0.5 < r < 0.7, 0 < z < 1 about the z axis, as hexes:
/// patch "inner" on the cylinder r = 0.5, "bottom" on the plane z = 0.
mesh::Mesh annulus_sector() {
  const auto xs = mesh::uniform_line(0.0, 1.0, 3), ys = mesh::uniform_line(0.0, 1.0, 6),
             zs = mesh::uniform_line(0.0, 1.0, 5);
  mesh::Mesh mesh = mesh::structured_hexes(xs, ys, zs, {"inner", "outer", "side0", "side1", "bottom", "top"});
  for (auto& p : mesh.points) {
    const double r = 0.5 + 0.2 * p.x, theta = std::numbers::pi / 6 * p.y;
    p = {r * std::cos(theta), r * std::sin(theta), p.z};
  }
  return mesh;
}

/// The segment from (r, z) = a to b turned a quarter about the z axis, from the x axis to the y
/// axis: a B-spline surface, rational quadratic arcs by linear.
geometry::BSplineSurface quarter_turn(geometry::Vec2 a, geometry::Vec2 b) {
  const double w = std::sqrt(0.5);
  std::vector<geometry::Vec3> poles;
  std::vector<double> weights;
  for (const auto& [cx, cy, weight] : {std::tuple{1.0, 0.0, 1.0}, std::tuple{1.0, 1.0, w}, std::tuple{0.0, 1.0, 1.0}}) {
    for (const geometry::Vec2& end : {a, b}) {
      poles.push_back({cx * end.x, cy * end.x, end.y});
      weights.push_back(weight);
    }
  }
  return geometry::BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, poles, weights);
}

/// Face 1: the quarter cylinder r = 0.5, 0 < z < 1 about the z axis; face 2: the plane z = 0
/// over [0, 1]^2.
void write_cylinder_and_plane(const std::filesystem::path& path) {
  geometry::CadExport content;
  content.surfaces.push_back({"cylinder", quarter_turn({0.5, 0.0}, {0.5, 1.0})});
  content.surfaces.push_back(
      {"plane", geometry::BSplineSurface(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}})});
  io::write_file_atomically(path, geometry::to_step(content));
}

/// Face 1: the quarter cylinder r = 0.5, 0 < z < 1 about the z axis; face 2: the quarter ring
/// 0.5 < r < 0.7 of the plane z = 0 at its foot. Both turn about the z axis.
void write_cylinder_and_ring(const std::filesystem::path& path) {
  geometry::CadExport content;
  content.surfaces.push_back({"cylinder", quarter_turn({0.5, 0.0}, {0.5, 1.0})});
  content.surfaces.push_back({"ring", quarter_turn({0.5, 0.0}, {0.7, 0.0})});
  io::write_file_atomically(path, geometry::to_step(content));
}

/// Radial deflection of the cylinder: d(z) = 0.01 + 0.02 z.
double deflection(double z) { return 0.01 + 0.02 * z; }

TEST(CheckCommand, RevolvedMeshAgainstCadFacesAndTheDeflectedCylinder) {
  test::TempDir dir;
  write_cylinder_and_plane(dir / "sector.step");
  const auto faces = hotmesh("cad --json " + q(dir / "sector.step"));
  ASSERT_EQ(faces.exit_code, 0) << faces.output;
  const Json cad = Json::parse(faces.output);
  ASSERT_EQ(cad["faces"].size(), 2u);
  ASSERT_FALSE(cad["faces"][0]["axis"].is_null());  // a cylinder: a fitted axis
  ASSERT_TRUE(cad["faces"][1]["axis"].is_null());   // a plane: none

  mesh::Mesh mesh = annulus_sector();
  io::write_gmsh(dir / "sector.msh", mesh);
  const std::string common = "--cad " + q(dir / "sector.step") + " --map inner=1 --map bottom=2 --mesh ";
  const auto [pass_code, pass] = check_json(common + q(dir / "sector.msh"));
  EXPECT_EQ(pass_code, 0) << pass.dump(2);
  ASSERT_EQ(pass["patches"].size(), 2u);
  EXPECT_LT(pass["patches"][0]["max_distance"].get<double>(), 1e-9);
  EXPECT_THAT(pass["patches"][0]["reference"].get<std::string>(), HasSubstr("meridional curve"));
  EXPECT_LT(pass["patches"][1]["max_distance"].get<double>(), 1e-12);
  EXPECT_THAT(pass["patches"][1]["reference"].get<std::string>(), HasSubstr("their surfaces"));
  // The faces in the meridional plane: the quads' chords across theta are not counted.
  EXPECT_LT(pass["patches"][0]["wall"]["hausdorff"].get<double>(), 1e-9);
  // The plane's faces in space, against the CAD face as hotmesh deform sees it.
  EXPECT_EQ(pass["patches"][1]["wall"]["shape"], "faces");
  EXPECT_LT(pass["patches"][1]["wall"]["hausdorff"].get<double>(), 1e-12);

  // One node of the inner wall 0.2 mm outwards, one of the bottom 0.3 mm down.
  mesh::Mesh perturbed = mesh;
  const mesh::NodeId inner = middle_node(mesh, "inner"), bottom = middle_node(mesh, "bottom");
  auto& p = perturbed.points[static_cast<std::size_t>(inner)];
  p = p * ((0.5 + 2e-4) / std::hypot(p.x, p.y));
  p.z = mesh.points[static_cast<std::size_t>(inner)].z;
  perturbed.points[static_cast<std::size_t>(bottom)].z -= 3e-4;
  io::write_gmsh(dir / "perturbed.msh", perturbed);
  const auto [fail_code, fail] = check_json(common + q(dir / "perturbed.msh"));
  EXPECT_EQ(fail_code, 1);
  EXPECT_EQ(fail["patches"][0]["worst_node"]["id"], mesh.node_id(inner));
  EXPECT_NEAR(fail["patches"][0]["max_distance"].get<double>(), 2e-4, 1e-9);
  EXPECT_EQ(fail["patches"][1]["worst_node"]["id"], mesh.node_id(bottom));
  EXPECT_NEAR(fail["patches"][1]["max_distance"].get<double>(), 3e-4, 1e-9);
  // The bottom's faces bulge 0.3 mm off the plane at that node.
  EXPECT_EQ(fail["patches"][1]["wall"]["worst"], "mesh_to_shape");
  EXPECT_NEAR(fail["patches"][1]["wall"]["hausdorff"].get<double>(), 3e-4, 1e-9);
  const std::vector<std::int64_t> around = fail["patches"][1]["wall"]["mesh_to_shape"]["face_nodes"];
  EXPECT_NE(std::find(around.begin(), around.end(), mesh.node_id(bottom)), around.end());

  // Deformed: the inner wall moved out by d(z); the table samples the cylinder at 0.3 rad.
  std::ostringstream table;
  table.precision(17);
  table << "x,y,z,dx,dy,dz\n";
  for (const double z : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    table << 0.5 * std::cos(0.3) << "," << 0.5 * std::sin(0.3) << "," << z << "," << deflection(z) * std::cos(0.3) << ","
          << deflection(z) * std::sin(0.3) << ",0\n";
  }
  test::write_text(dir / "inner.csv", table.str());
  mesh::Mesh deformed = mesh;
  for (const mesh::NodeId n : mesh.find_patch("inner")->nodes) {
    auto& d = deformed.points[static_cast<std::size_t>(n)];
    d = d * ((0.5 + deflection(d.z)) / 0.5);
    d.z = mesh.points[static_cast<std::size_t>(n)].z;
  }
  io::write_gmsh(dir / "deformed.msh", deformed);
  const std::string deflected = "--cad " + q(dir / "sector.step") + " --map inner=1 --deflection inner=" +
                                q(dir / "inner.csv") + " --mesh ";
  const auto [moved_code, moved] = check_json(deflected + q(dir / "deformed.msh"));
  EXPECT_EQ(moved_code, 0) << moved.dump(2);
  EXPECT_LT(moved["patches"][0]["max_distance"].get<double>(), 1e-9);
  EXPECT_LT(moved["patches"][0]["wall"]["hausdorff"].get<double>(), 1e-9);
  EXPECT_THAT(moved["patches"][0]["reference"].get<std::string>(), HasSubstr("deflected by"));
  const auto [still_code, still] = check_json(deflected + q(dir / "sector.msh"));  // the undeformed mesh
  EXPECT_EQ(still_code, 1);
  // At z = 1, normal to the deflected wall r = 0.51 + 0.02 z.
  EXPECT_NEAR(still["patches"][0]["max_distance"].get<double>(), deflection(1.0) / std::hypot(1.0, 0.02), 1e-9);
}

/// A user's hexahedral mesh over the forward-facing step of occt_fixtures.hpp (mm): the wall
/// "step" has its nodes on the floor (1 mm apart), the fillet (8 chords of pi/16), the riser
/// (0.5 mm apart) and the top (1 mm apart), each column of nodes rising from the wall to the
/// channel's top y = 8 (over the fillet and the riser leaning upstream, so that no cell folds);
/// "inlet", "outlet", "upper", "side0", "side1" bound the rest.
mesh::Mesh forward_facing_step_mesh() {
  std::vector<geometry::Vec2> feet;  // (x, y) of each column's foot, along the wall
  std::vector<double> heads;         // x of its head, at y = 8
  for (int i = 0; i <= 10; ++i) {
    feet.push_back({i * 1.0, 0.0});
    heads.push_back(i * 1.0);
  }
  for (int k = 1; k <= 8; ++k) {
    const double angle = std::numbers::pi / 2 * (k / 8.0 - 1.0);
    feet.push_back({10.0 + std::cos(angle), 1.0 + std::sin(angle)});
    heads.push_back(10.0 + 0.0375 * k);
  }
  for (int m = 1; m <= 4; ++m) {
    feet.push_back({11.0, 1.0 + 0.5 * m});
    heads.push_back(10.3 + 0.1 * m);  // leaning back over the riser, up to its top
  }
  for (int j = 1; j <= 9; ++j) {
    feet.push_back({11.0 + j, 3.0});
    heads.push_back(11.0 + j);
  }
  const int columns = static_cast<int>(feet.size());
  mesh::Mesh mesh = mesh::structured_hexes(mesh::uniform_line(0.0, 1.0, columns - 1), mesh::uniform_line(0.0, 1.0, 4),
                                           mesh::uniform_line(0.0, 4.0, 2),
                                           {"inlet", "outlet", "step", "upper", "side0", "side1"});
  for (auto& p : mesh.points) {
    const auto column = static_cast<std::size_t>(std::lround(p.x * (columns - 1)));
    const geometry::Vec2 foot = feet[column];
    p = {foot.x + (heads[column] - foot.x) * p.y, foot.y + (8.0 - foot.y) * p.y, p.z};
  }
  return mesh;
}

// Issue 45: on a part without an axis, one fillet (a cylinder) among the planes of a patch made
// check take the fillet's axis and refuse the planes. Now it chooses as hotmesh deform does:
// meridional only when every face turns about one axis, else the faces themselves.
TEST(CheckCommand, APartWithoutAnAxisIsMeasuredOnItsFacesThoughOneIsACylinder) {
  test::TempDir dir;
  geometry::test::write_forward_facing_step(dir / "step.step");
  const auto faces = hotmesh("cad --json --unit mm " + q(dir / "step.step"));
  ASSERT_EQ(faces.exit_code, 0) << faces.output;
  const Json listed = Json::parse(faces.output);
  std::vector<std::string> kinds;
  for (const Json& face : listed["faces"]) kinds.push_back(face["kind"]);
  ASSERT_THAT(kinds, ::testing::ElementsAre("plane", "cylinder", "plane", "plane"));

  const mesh::Mesh mesh = forward_facing_step_mesh();
  io::write_gmsh(dir / "step.msh", mesh);
  const std::string check = "--unit mm --cad " + q(dir / "step.step") + " --map step=1,2,3,4 --mesh ";
  const auto [code, report] = check_json(check + q(dir / "step.msh"));
  ASSERT_EQ(code, 0) << report.dump(2);
  const Json& patch = report["patches"][0];
  EXPECT_EQ(patch["nodes"], 32 * 3);
  EXPECT_LT(patch["max_distance"].get<double>(), 1e-9);
  EXPECT_THAT(patch["reference"].get<std::string>(),
              HasSubstr("CAD faces 1, 2, 3, 4: their surfaces (not one surface of revolution: face 1 (plane) is not a "
                        "surface of revolution about the axis (10, 1, 0) along (0, 0, 1): its point "));
  // The faces in space: the fillet's quads are chords of pi/16 across it, the planes' lie on them.
  EXPECT_EQ(patch["wall"]["shape"], "faces");
  EXPECT_NEAR(patch["wall"]["hausdorff"].get<double>(), 1.0 - std::cos(std::numbers::pi / 32), 1e-4);

  // A node of the fillet 0.1 mm into the part is found.
  mesh::Mesh perturbed = mesh;
  const mesh::NodeId moved = nearest_node(mesh, "step", {10.0 + std::sqrt(0.5), 1.0 - std::sqrt(0.5), 2.0});
  auto& p = perturbed.points[static_cast<std::size_t>(moved)];
  p = p + 0.1 * geometry::Vec3{std::sqrt(0.5), -std::sqrt(0.5), 0.0};
  io::write_gmsh(dir / "perturbed.msh", perturbed);
  const auto [fail_code, fail] = check_json(check + q(dir / "perturbed.msh"));
  EXPECT_EQ(fail_code, 1);
  EXPECT_EQ(fail["patches"][0]["worst_node"]["id"], mesh.node_id(moved));
  EXPECT_NEAR(fail["patches"][0]["max_distance"].get<double>(), 0.1, 1e-9);

  // --mode surface says so itself; --mode meridional is refused, naming the plane.
  const auto [surface_code, surface] = check_json(check + q(dir / "step.msh") + " --mode surface");
  EXPECT_EQ(surface_code, 0) << surface.dump(2);
  EXPECT_EQ(surface["patches"][0]["reference"], "CAD faces 1, 2, 3, 4: their surfaces");
  EXPECT_LT(surface["patches"][0]["max_distance"].get<double>(), 1e-9);
  const auto meridional = hotmesh("check " + check + q(dir / "step.msh") + " --mode meridional");
  EXPECT_EQ(meridional.exit_code, 2) << meridional.output;
  EXPECT_THAT(meridional.output, HasSubstr("patch 'step': --mode meridional: "));
  EXPECT_THAT(meridional.output,
              HasSubstr("face 1 (plane) is not a surface of revolution about the axis (10, 1, 0) along (0, 0, 1)"));
  // The fillet alone does turn about its axis.
  const auto [fillet_code, fillet] =
      check_json("--unit mm --cad " + q(dir / "step.step") + " --map step=2 --mode meridional --mesh " + q(dir / "step.msh"));
  EXPECT_EQ(fillet_code, 1);  // the other faces' nodes are off the fillet
  EXPECT_THAT(fillet["patches"][0]["reference"].get<std::string>(),
              HasSubstr("CAD face 2: its meridional curve about the axis (10, 1, 0) along (0, 0, 1)"));
  EXPECT_EQ(hotmesh("check " + check + q(dir / "step.msh") + " --mode sideways").exit_code, 2);
}

// The deformed step against its deflected faces: a table of FEM nodes on the four faces, all
// moved 0.01 mm up, makes a field d(t, s) on each face (as hotmesh deform's surface walls), not
// a meridional curve about the fillet's axis.
TEST(CheckCommand, DeflectedPartWithoutAnAxisIsMeasuredOnItsDeflectedFaces) {
  test::TempDir dir;
  geometry::test::write_forward_facing_step(dir / "step.step");
  constexpr double lift = 0.01;
  std::ostringstream table;
  table.precision(17);
  table << "id,x,y,z,dx,dy,dz\n";
  int id = 0;
  for (const double f : {0.05, 0.35, 0.65, 0.95}) {  // along each face
    const double angle = std::numbers::pi / 2 * (f - 1.0);
    for (const geometry::Vec2 q :
         {geometry::Vec2{10.0 * f, 0.0}, geometry::Vec2{10.0 + std::cos(angle), 1.0 + std::sin(angle)},
          geometry::Vec2{11.0, 1.0 + 2.0 * f}, geometry::Vec2{11.0 + 9.0 * f, 3.0}}) {
      for (const double z : {0.2, 2.0, 3.8}) table << ++id << "," << q.x << "," << q.y << "," << z << ",0," << lift << ",0\n";
    }
  }
  test::write_text(dir / "step.csv", table.str());
  const mesh::Mesh mesh = forward_facing_step_mesh();
  io::write_gmsh(dir / "step.msh", mesh);
  mesh::Mesh lifted = mesh;
  for (const mesh::NodeId n : mesh.find_patch("step")->nodes) lifted.points[static_cast<std::size_t>(n)].y += lift;
  io::write_gmsh(dir / "lifted.msh", lifted);

  const std::string check = "--unit mm --cad " + q(dir / "step.step") + " --map step=1,2,3,4 --deflection step=" +
                            q(dir / "step.csv") + " --mesh ";
  const auto [code, report] = check_json(check + q(dir / "lifted.msh"));
  ASSERT_EQ(code, 0) << report.dump(2);
  EXPECT_LT(report["patches"][0]["max_distance"].get<double>(), 1e-9);
  EXPECT_THAT(report["patches"][0]["reference"].get<std::string>(),
              HasSubstr("(a field d(t, s) on each face, degree 1, displacement form) (not one surface of revolution: "
                        "face 1 (plane)"));
  // The undeformed mesh: the floor and the top are 0.01 mm below the deflected wall.
  const auto [still_code, still] = check_json(check + q(dir / "step.msh"));
  EXPECT_EQ(still_code, 1);
  EXPECT_NEAR(still["patches"][0]["max_distance"].get<double>(), lift, 1e-9);
  EXPECT_EQ(hotmesh("check " + check + q(dir / "lifted.msh") + " --mode meridional").exit_code, 2);
}

// Faces that all turn about one axis are still measured through their meridional curve under
// auto: a cylinder and the ring of the plane across its foot (fitted axes: B-spline faces).
TEST(CheckCommand, FacesAllTurningAboutOneAxisAreMeasuredThroughTheirMeridionalCurve) {
  test::TempDir dir;
  write_cylinder_and_ring(dir / "corner.step");
  io::write_gmsh(dir / "sector.msh", annulus_sector());
  const std::string check = "--cad " + q(dir / "corner.step") + " --map inner=1,2 --map bottom=1,2 --mesh " +
                            q(dir / "sector.msh");
  const auto [code, report] = check_json(check);
  ASSERT_EQ(code, 0) << report.dump(2);
  for (const Json& patch : report["patches"]) {
    EXPECT_LT(patch["max_distance"].get<double>(), 1e-9) << patch["patch"];
    EXPECT_THAT(patch["reference"].get<std::string>(), HasSubstr("CAD faces 1, 2: their meridional curve about the axis"));
  }
  const auto [surface_code, surface] = check_json(check + " --mode surface");
  ASSERT_EQ(surface_code, 0) << surface.dump(2);
  EXPECT_EQ(surface["patches"][0]["reference"], "CAD faces 1, 2: their surfaces");
  EXPECT_LT(surface["patches"][0]["max_distance"].get<double>(), 1e-9);
}

TEST(CheckCommand, JunitReportFileIsWellFormedXmlWithATestCasePerPatch) {
  test::TempDir dir;
  write_cylinder_and_plane(dir / "sector.step");
  mesh::Mesh mesh = annulus_sector();
  const mesh::NodeId moved = middle_node(mesh, "bottom");
  mesh.points[static_cast<std::size_t>(moved)].z += 1e-3;
  io::write_gmsh(dir / "sector.msh", mesh);
  const auto r = hotmesh("-q check --cad " + q(dir / "sector.step") + " --map inner=1 --map bottom=2 --mesh " +
                         q(dir / "sector.msh") + " --format junit -o " + q(dir / "report.xml"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("FAIL bottom"));  // stdout: the text form
  EXPECT_THAT(r.output, HasSubstr("pass inner"));
  const auto parsed = parse_junit(dir / "report.xml");
  ASSERT_EQ(parsed.exit_code, 0) << parsed.output;
  EXPECT_THAT(parsed.output, HasSubstr("2 1 0 [('inner', 'pass'), ('bottom', 'failure')]"));
  EXPECT_THAT(parsed.output, HasSubstr("node " + std::to_string(mesh.node_id(moved)) + " is 1.000e-03 from"));
  // The report never replaces an input.
  EXPECT_EQ(hotmesh("-q check --cad " + q(dir / "sector.step") + " --map inner=1 --mesh " + q(dir / "sector.msh") +
                    " -o " + q(dir / "sector.msh"))
                .exit_code,
            2);
}

TEST(CheckCommand, UserErrorsNameWhatIsWrong) {
  test::TempDir dir;
  io::write_gmsh(dir / "sector.msh", annulus_sector());
  write_cylinder_and_plane(dir / "sector.step");
  const std::string mesh = " --mesh " + q(dir / "sector.msh");
  const std::string cad = " --cad " + q(dir / "sector.step");
  auto expect = [](const test::CommandResult& r, const std::string& text) {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr(text));
  };
  expect(hotmesh("check" + mesh), "nothing to check");
  expect(hotmesh("check" + cad + " --map inner=1"), "give the mesh to check");
  expect(hotmesh("check" + mesh + cad + " --map wall=1"), "the mesh has no patch 'wall' (its patches: inner, outer");
  expect(hotmesh("check" + mesh + " --map inner=1"), "--map inner: needs --cad");
  expect(hotmesh("check" + mesh + cad + " --map inner"), "expected PATCH=FACE_IDS");
  expect(hotmesh("check" + mesh + cad + " --map inner=1,x"), "face ids are integers from 1");
  expect(hotmesh("check" + mesh + cad + " --map inner=9"), "no face 9");
  expect(hotmesh("check" + mesh + cad + " --map bottom=2,2"), "--map bottom=2,2: face 2 is listed twice");
  expect(hotmesh("check" + mesh + cad + " --map inner=1 --map inner=2"), "mapped twice");
  expect(hotmesh("check" + mesh + cad + " --map inner=1 --axis 0,0,1"), "--axis needs six numbers");
  expect(hotmesh("check" + mesh + " --deflection inner=" + q(dir / "missing.csv")), "missing.csv");
  EXPECT_EQ(hotmesh("check" + mesh + cad + " --map inner=1 --format yaml").exit_code, 2);
}

// docs/cli.md's example on the stator-well sample: the casing is two cylinders r = 0.45, face 3
// in front of the blade row (z 0 to 0.034) and face 4 behind it (z 0.066 to 0.1), whose
// meridional curves do not meet. It once stopped with "do not form one connected profile".
TEST(CheckCommand, StatorWellCasingOnEitherSideOfTheBladeIsCheckedPerProfile) {
  test::TempDir dir;
  const std::filesystem::path sample = kSamples / "stator_well";
  const std::string readme = "check --cad " + q(sample / "stator_well.step") + " " + q(sample / "stator_well.msh") +
                             " --map casing=3,4 --map disc_base=39 --format junit -o " + q(dir / "check.xml");
  const auto r = hotmesh("-q " + readme);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("2 of 2 patches within the tolerance"));
  const auto parsed = parse_junit(dir / "check.xml");
  ASSERT_EQ(parsed.exit_code, 0) << parsed.output;
  EXPECT_THAT(parsed.output, HasSubstr("2 0 0 [('casing', 'pass'), ('disc_base', 'pass')]"));

  const std::string casing = "--cad " + q(sample / "stator_well.step") + " --map casing=3,4 --mesh ";
  const auto [pass_code, pass] = check_json(casing + q(sample / "stator_well.msh"));
  ASSERT_EQ(pass_code, 0) << pass.dump(2);
  const Json& patch = pass["patches"][0];
  EXPECT_EQ(patch["nodes"], 264);
  EXPECT_LT(patch["max_distance"].get<double>(), 1e-12);
  EXPECT_THAT(patch["reference"].get<std::string>(), HasSubstr("CAD faces 3, 4: 2 separate meridional profiles"));
  ASSERT_EQ(patch["parts"].size(), 2u);
  EXPECT_THAT(patch["parts"][0]["reference"].get<std::string>(), HasSubstr("CAD face 3: its meridional curve"));
  EXPECT_THAT(patch["parts"][1]["reference"].get<std::string>(), HasSubstr("CAD face 4: its meridional curve"));
  EXPECT_EQ(patch["parts"][0]["nodes"].get<int>() + patch["parts"][1]["nodes"].get<int>(), 264);
  EXPECT_GT(patch["parts"][0]["nodes"].get<int>(), 100);
  EXPECT_GT(patch["parts"][1]["nodes"].get<int>(), 100);

  // A node of the rear casing 0.1 mm outwards: that part fails and names it, the other passes.
  mesh::Mesh mesh = io::read_gmsh(sample / "stator_well.msh");
  const mesh::NodeId moved = nearest_node(mesh, "casing", {0.45, 0.0, 0.08});
  auto& p = mesh.points[static_cast<std::size_t>(moved)];
  p = p * ((0.45 + 1e-4) / std::hypot(p.x, p.y));
  p.z = 0.08 + (p.z - 0.08);  // unchanged: only r moves
  io::write_gmsh(dir / "perturbed.msh", mesh);
  const auto [fail_code, fail] = check_json(casing + q(dir / "perturbed.msh"));
  EXPECT_EQ(fail_code, 1);
  const Json& failed = fail["patches"][0];
  EXPECT_EQ(failed["passed"], false);
  EXPECT_EQ(failed["worst_node"]["id"], mesh.node_id(moved));
  EXPECT_NEAR(failed["max_distance"].get<double>(), 1e-4, 1e-9);
  EXPECT_EQ(failed["parts"][0]["passed"], true);
  EXPECT_EQ(failed["parts"][1]["passed"], false);
  EXPECT_EQ(failed["parts"][1]["worst_node"]["id"], mesh.node_id(moved));
}

// `--format junit -o FILE` once wrote nothing when the check could not be made, leaving CI an
// earlier (passing) report. Now the report holds one test case in error with the message.
TEST(CheckCommand, JunitReportOfACheckThatCannotBeMadeIsATestCaseInError) {
  test::TempDir dir;
  const std::filesystem::path sample = kSamples / "stator_well";
  const std::string check = "-q check --cad " + q(sample / "stator_well.step") + " --mesh " +
                            q(sample / "stator_well.msh") + " --format junit ";
  ASSERT_EQ(hotmesh(check + "--map casing=3,4 -o " + q(dir / "check.xml")).exit_code, 0);
  const auto r = hotmesh(check + "--map casing=3,99 -o " + q(dir / "check.xml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("patch 'casing': "));
  EXPECT_THAT(r.output, HasSubstr("no face 99"));
  const auto parsed = parse_junit(dir / "check.xml");
  ASSERT_EQ(parsed.exit_code, 0) << parsed.output;
  EXPECT_THAT(parsed.output, HasSubstr("1 0 1 [('input', 'error')]"));
  EXPECT_THAT(parsed.output, HasSubstr("no face 99: the faces are 1 to 44"));
  EXPECT_THAT(test::read_text(dir / "check.xml"), HasSubstr("<error type=\"input error\""));

  // Never over an input, even to report an error.
  const std::filesystem::path table = dir / "disc_base.csv";
  std::filesystem::copy_file(sample / "disc_base.csv", table);
  const std::string before = test::read_text(table);
  EXPECT_EQ(hotmesh(check + "--map casing=99 --deflection disc_base=" + q(table) + " -o " + q(table)).exit_code, 2);
  EXPECT_EQ(test::read_text(table), before);

  // A case file that cannot be read: its inputs are unknown, so the report replaces only an
  // earlier XML report or nothing.
  test::write_text(dir / "broken.yaml", "mesh: " + (sample / "stator_well.msh").string() + "\npatches: {casing: {rol: fixed}}\n");
  const auto broken = hotmesh("-q check --case " + q(dir / "broken.yaml") + " --format junit -o " + q(dir / "check.xml"));
  EXPECT_EQ(broken.exit_code, 2);
  EXPECT_THAT(test::read_text(dir / "check.xml"), HasSubstr("patches.casing.rol: unknown key"));
  test::write_text(dir / "notes.txt", "not a report\n");
  EXPECT_EQ(hotmesh("-q check --case " + q(dir / "broken.yaml") + " --format junit -o " + q(dir / "notes.txt")).exit_code, 2);
  EXPECT_EQ(test::read_text(dir / "notes.txt"), "not a report\n");
}

// Issue 45, item 2: a 2D mesh against its CAD. --map names the wall's CAD edges; the nodes on
// them (gmsh put them on the CAD's lines and arc) are at round-off, and a node moved off the wall
// by a known amount, on the floor or radially off the fillet, is reported with that distance:
// the wall is the CAD's circle, not a polygon.
TEST(CheckCommand, TwoDMeshIsMeasuredAgainstItsCadEdgesAndAMovedNodeIsFound) {
  const test::ChannelStep channel;
  ASSERT_EQ(channel.wall_edges().size(), 4u);
  const std::string map = fmt::format(" --cad {} --unit mm --map bottom={}", q(channel.path("channel.step")),
                                      fmt::join(channel.wall_edges(), ","));
  const auto [code, report] = check_json(q(channel.path("channel.msh")) + map);
  ASSERT_EQ(code, 0) << report.dump(2);
  const Json& patch = report["patches"][0];
  EXPECT_LT(patch["max_distance"].get<double>(), 1e-9);
  EXPECT_THAT(patch["reference"].get<std::string>(), HasSubstr("curve in the x-y plane"));

  const mesh::Mesh mesh = io::read_gmsh(channel.path("channel.msh"));
  const auto check_moved = [&](const geometry::Vec3& near, const auto& move, double expected) {
    mesh::Mesh moved = mesh;
    const mesh::NodeId n = nearest_node(moved, "bottom", near);
    geometry::Vec3& p = moved.points[static_cast<std::size_t>(n)];
    p = move(p);
    io::write_gmsh(channel.path("moved.msh"), moved);
    const auto [fail_code, fail] = check_json(q(channel.path("moved.msh")) + map);
    EXPECT_EQ(fail_code, 1);
    EXPECT_EQ(fail["patches"][0]["worst_node"]["id"], moved.node_id(n));
    EXPECT_NEAR(fail["patches"][0]["max_distance"].get<double>(), expected, 1e-9);
  };
  // A node of the floor, 0.01 up.
  check_moved({5, 0, 0}, [](const geometry::Vec3& p) { return p + geometry::Vec3{0, 0.01, 0}; }, 0.01);
  // The node of the fillet nearest to its middle, 0.004 out along its radius.
  const geometry::Vec3 centre{12, 3, 0};
  check_moved({12 - std::sqrt(2.0), 3 + std::sqrt(2.0), 0},
              [&](const geometry::Vec3& p) {
                EXPECT_NEAR(distance(p, centre), 2.0, 1e-9) << "not a node of the fillet";
                return centre + (1.0 + 0.004 / 2.0) * (p - centre);
              },
              0.004);
}

// An axisymmetric 2D mesh, x along the axis and y the radius, against the revolved CAD: --map
// names faces, read about --axis as (z, r).
TEST(CheckCommand, AxisymmetricTwoDMeshIsMeasuredAgainstTheFacesAboutTheAxis) {
  test::TempDir dir;
  const std::string geo = q(test::data_path("gmsh/hub_axisymmetric.geo"));
  ASSERT_EQ(run_command("gmsh -2 -nt 1 " + geo + " -format msh41 -o " + q(dir / "hub.msh")).exit_code, 0);
  ASSERT_EQ(run_command("gmsh -0 -setnumber part 3 " + geo + " -o " + q(dir / "hub.step")).exit_code, 0);
  const auto listing = hotmesh("-q cad --json " + q(dir / "hub.step"));
  ASSERT_EQ(listing.exit_code, 0) << listing.output;
  const Json model = Json::parse(listing.output);
  std::vector<int> faces;
  for (const auto& face : model["faces"]) {
    if (face["kind"] == "cylinder" || face["kind"] == "cone") faces.push_back(face["id"].get<int>());
  }
  const auto [code, report] = check_json(fmt::format("{} --cad {} --unit mm --axis 0,0,0,1,0,0 --map hub={}", q(dir / "hub.msh"),
                                                     q(dir / "hub.step"), fmt::join(faces, ",")));
  ASSERT_EQ(code, 0) << report.dump(2);
  EXPECT_LT(report["patches"][0]["max_distance"].get<double>(), 1e-9);
  EXPECT_THAT(report["patches"][0]["reference"].get<std::string>(), HasSubstr("as (z, r) in the mesh's plane"));
}

}  // namespace
}  // namespace hotmesh::app
