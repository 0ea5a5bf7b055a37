// Tests of `hotmesh check`: a consistent mesh passes and a perturbed one fails naming the node
// that was moved, for the real ramp2d sample (a mesh deformed by hotmesh deform, checked against
// the deflection table) and for a revolved 3D mesh built here on a cylinder and a plane written
// to STEP (undeformed against the CAD faces, deformed against the deflected cylinder); the
// JSON and JUnit reports; user errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <nlohmann/json.hpp>
#include <sstream>

#include "hotmesh/deform/structured_mesh.hpp"
#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using test::run_command;
using test::shell_quote;
using Json = nlohmann::json;

test::CommandResult hotmesh(const std::string& arguments) {
  return run_command(std::string(HOTMESH_EXE) + " " + arguments);
}

std::string q(const std::filesystem::path& path) { return shell_quote(path.string()); }

/// The node in the middle of a patch's node list (sorted by index).
deform::NodeId middle_node(const deform::Mesh& mesh, const std::string& patch) {
  const auto& nodes = mesh.find_patch(patch)->nodes;
  return nodes[nodes.size() / 2];
}

/// The node of `patch` nearest to `point`.
deform::NodeId nearest_node(const deform::Mesh& mesh, const std::string& patch, const geometry::Vec3& point) {
  const auto& nodes = mesh.find_patch(patch)->nodes;
  return *std::min_element(nodes.begin(), nodes.end(), [&](deform::NodeId a, deform::NodeId b) {
    return distance(mesh.points[static_cast<std::size_t>(a)], point) < distance(mesh.points[static_cast<std::size_t>(b)], point);
  });
}

/// The JSON report of a check, with its exit code.
std::pair<int, Json> check_json(const std::string& arguments) {
  const auto r = hotmesh("-q check --format json " + arguments);
  const auto start = r.output.find('{');
  if (start == std::string::npos) return {r.exit_code, Json{{"output", r.output}}};
  return {r.exit_code, Json::parse(r.output.substr(start))};
}

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

  // Move one node of the flat part of the wall 1 mm up: the check fails and names it.
  deform::Mesh mesh = io::read_gmsh(dir / "out/deformed.msh");
  const deform::NodeId moved = nearest_node(mesh, "bottom", {0.3, 0.0, 0.0});
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

/// A 30-degree sector of the annulus 0.5 < r < 0.7, 0 < z < 1 about the z axis, as hexes:
/// patch "inner" on the cylinder r = 0.5, "bottom" on the plane z = 0.
deform::Mesh annulus_sector() {
  const auto xs = deform::uniform_line(0.0, 1.0, 3), ys = deform::uniform_line(0.0, 1.0, 6),
             zs = deform::uniform_line(0.0, 1.0, 5);
  deform::Mesh mesh = deform::structured_hexes(xs, ys, zs, {"inner", "outer", "side0", "side1", "bottom", "top"});
  for (auto& p : mesh.points) {
    const double r = 0.5 + 0.2 * p.x, theta = std::numbers::pi / 6 * p.y;
    p = {r * std::cos(theta), r * std::sin(theta), p.z};
  }
  return mesh;
}

/// Face 1: the quarter cylinder r = 0.5, 0 < z < 1 about the z axis (rational quadratic arcs);
/// face 2: the plane z = 0 over [0, 1]^2.
void write_cylinder_and_plane(const std::filesystem::path& path) {
  const double r = 0.5, w = std::sqrt(0.5);
  const std::vector<geometry::Vec3> arc{{r, 0, 0}, {r, r, 0}, {0, r, 0}};
  std::vector<geometry::Vec3> poles;
  std::vector<double> weights;
  for (std::size_t i = 0; i < 3; ++i) {
    for (const double z : {0.0, 1.0}) {
      poles.push_back({arc[i].x, arc[i].y, z});
      weights.push_back(i == 1 ? w : 1.0);
    }
  }
  geometry::CadExport content;
  content.surfaces.push_back({"cylinder", geometry::BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, poles, weights)});
  content.surfaces.push_back(
      {"plane", geometry::BSplineSurface(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}})});
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

  deform::Mesh mesh = annulus_sector();
  io::write_gmsh(dir / "sector.msh", mesh);
  const std::string common = "--cad " + q(dir / "sector.step") + " --map inner=1 --map bottom=2 --mesh ";
  const auto [pass_code, pass] = check_json(common + q(dir / "sector.msh"));
  EXPECT_EQ(pass_code, 0) << pass.dump(2);
  ASSERT_EQ(pass["patches"].size(), 2u);
  EXPECT_LT(pass["patches"][0]["max_distance"].get<double>(), 1e-9);
  EXPECT_THAT(pass["patches"][0]["reference"].get<std::string>(), HasSubstr("meridional curve"));
  EXPECT_LT(pass["patches"][1]["max_distance"].get<double>(), 1e-12);
  EXPECT_THAT(pass["patches"][1]["reference"].get<std::string>(), HasSubstr("their surfaces"));

  // One node of the inner wall 0.2 mm outwards, one of the bottom 0.3 mm down.
  deform::Mesh perturbed = mesh;
  const deform::NodeId inner = middle_node(mesh, "inner"), bottom = middle_node(mesh, "bottom");
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

  // Deformed: the inner wall moved out by d(z); the table samples the cylinder at 0.3 rad.
  std::ostringstream table;
  table.precision(17);
  table << "x,y,z,dx,dy,dz\n";
  for (const double z : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    table << 0.5 * std::cos(0.3) << "," << 0.5 * std::sin(0.3) << "," << z << "," << deflection(z) * std::cos(0.3) << ","
          << deflection(z) * std::sin(0.3) << ",0\n";
  }
  test::write_text(dir / "inner.csv", table.str());
  deform::Mesh deformed = mesh;
  for (const deform::NodeId n : mesh.find_patch("inner")->nodes) {
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
  EXPECT_THAT(moved["patches"][0]["reference"].get<std::string>(), HasSubstr("deflected by"));
  const auto [still_code, still] = check_json(deflected + q(dir / "sector.msh"));  // the undeformed mesh
  EXPECT_EQ(still_code, 1);
  // At z = 1, normal to the deflected wall r = 0.51 + 0.02 z.
  EXPECT_NEAR(still["patches"][0]["max_distance"].get<double>(), deflection(1.0) / std::hypot(1.0, 0.02), 1e-9);
}

TEST(CheckCommand, JunitReportFileIsWellFormedXmlWithATestCasePerPatch) {
  test::TempDir dir;
  write_cylinder_and_plane(dir / "sector.step");
  deform::Mesh mesh = annulus_sector();
  const deform::NodeId moved = middle_node(mesh, "bottom");
  mesh.points[static_cast<std::size_t>(moved)].z += 1e-3;
  io::write_gmsh(dir / "sector.msh", mesh);
  const auto r = hotmesh("-q check --cad " + q(dir / "sector.step") + " --map inner=1 --map bottom=2 --mesh " +
                         q(dir / "sector.msh") + " --format junit -o " + q(dir / "report.xml"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("FAIL bottom"));  // stdout: the text form
  EXPECT_THAT(r.output, HasSubstr("pass inner"));
  // Parsed by a real XML parser, as CI systems do.
  const auto parsed = run_command(
      "python3 -c \"import sys, xml.etree.ElementTree as E; s = E.parse(sys.argv[1]).getroot(); "
      "print(s.get('tests'), s.get('failures'), [(c.get('name'), c.find('failure') is not None) for c in s.iter('testcase')], "
      "[f.get('message') for f in s.iter('failure')])\" " +
      q(dir / "report.xml"));
  ASSERT_EQ(parsed.exit_code, 0) << parsed.output;
  EXPECT_THAT(parsed.output, HasSubstr("2 1 [('inner', False), ('bottom', True)]"));
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
  expect(hotmesh("check" + mesh + cad + " --map wall=1"), "the mesh has no patch 'wall' (its patches: inner, outer");
  expect(hotmesh("check" + mesh + " --map inner=1"), "--map inner: needs --cad");
  expect(hotmesh("check" + mesh + cad + " --map inner"), "expected PATCH=FACE_IDS");
  expect(hotmesh("check" + mesh + cad + " --map inner=1,x"), "face ids are integers from 1");
  expect(hotmesh("check" + mesh + cad + " --map inner=9"), "no face 9");
  expect(hotmesh("check" + mesh + cad + " --map inner=1 --map inner=2"), "mapped twice");
  expect(hotmesh("check" + mesh + cad + " --map inner=1 --axis 0,0,1"), "--axis needs six numbers");
  expect(hotmesh("check" + mesh + " --deflection inner=" + q(dir / "missing.csv")), "missing.csv");
  EXPECT_EQ(hotmesh("check" + mesh + cad + " --map inner=1 --format yaml").exit_code, 2);
}

}  // namespace
}  // namespace hotmesh::app
