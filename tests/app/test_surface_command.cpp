// Tests of `hotmesh surface` (issue 23, item 3): deflection fields on CAD faces of any shape from
// FEM nodes, the deformed faces written to STEP/IGES and read back, the nodes and faces as VTK
// PolyData read by VTK itself, the residual picture, summary.json, and user errors.
//
// The CAD is built here: face 1 a wavy bicubic B-spline over (t, s) in [0, 1]^2 with x = t and
// y = s, its edge t = 1 the line (1, s, 0); face 2 a quarter cylinder (rational quadratic in t,
// linear in s, radius 0.5 about the line x = 1, z = -0.5 along y) that starts at that edge.
// The deflections are polynomials of degree 2 in each face's (t, s) that agree on the shared edge,
// so degree-2 fields reproduce them and the deformed faces are S + delta exactly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "run_command.hpp"
#include "test_support.hpp"
#include "vtk_reader.hpp"

namespace hotmesh::app {
namespace {

using geometry::BSplineSurface;
using geometry::Vec3;
using ::testing::HasSubstr;
using test::shell_quote;

test::CommandResult hotmesh(const std::string& arguments) {
  return test::run_command(std::string(HOTMESH_EXE) + " " + arguments);
}

/// Face 1: bicubic, uniform knots, poles at the Greville abscissae in x and y (so x = t, y = s)
/// and wavy heights, zero along the last row of poles (the edge t = 1).
BSplineSurface wavy_face() {
  const std::vector<double> knots{0, 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1, 1};
  const double greville[] = {0.0, 1.0 / 9, 1.0 / 3, 2.0 / 3, 8.0 / 9, 1.0};
  std::vector<Vec3> poles;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const double z = i == 5 ? 0.0 : 0.08 * std::sin(2.1 * i + 0.4) * std::cos(1.7 * j);
      poles.push_back({greville[i], greville[j], z});
    }
  }
  return BSplineSurface(3, 3, knots, knots, std::move(poles));
}

/// Face 2: the quarter cylinder from (1, s, 0) (t = 0) to (1.5, s, -0.5) (t = 1), exact circle
/// arcs (weights 1, 1/sqrt 2, 1).
BSplineSurface cylinder_face() {
  const double w = std::sqrt(0.5);
  const Vec3 arc[] = {{1.0, 0.0, 0.0}, {1.5, 0.0, 0.0}, {1.5, 0.0, -0.5}};
  std::vector<Vec3> poles;
  std::vector<double> weights;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      poles.push_back(arc[i] + Vec3{0.0, static_cast<double>(j), 0.0});
      weights.push_back(i == 1 ? w : 1.0);
    }
  }
  return BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, std::move(poles), std::move(weights));
}

/// The deflection on the shared edge, then on each face (both reduce to it there).
Vec3 on_edge(double s) { return {0.01 * s * s, -0.005 * s + 0.002, 0.02 * s * (1 - s)}; }
Vec3 delta_1(double t, double s) {
  return on_edge(s) + (t - 1) * Vec3{0.01 * t * s, 0.02 * s * s, 0.03 * (1 - s)};
}
Vec3 delta_2(double t, double s) { return on_edge(s) + t * Vec3{0.02 * (1 - t), 0.01 * s, -0.015 * s * s}; }

/// A folder with the two faces in faces.step (coordinates in `unit`) and a node table.
struct Case {
  test::TempDir dir;
  BSplineSurface face1 = wavy_face();
  BSplineSurface face2 = cylinder_face();
  geometry::DeflectionSamples nodes;

  explicit Case(geometry::LengthUnit unit = geometry::LengthUnit::metre) {
    geometry::CadExport content;
    content.unit = unit;
    content.surfaces = {{"wavy", face1}, {"cylinder", face2}};
    test::write_text(dir / "faces.step", geometry::to_step(content));
    nodes.frame = geometry::SampleFrame::cartesian;
  }
  std::string step() const { return shell_quote((dir / "faces.step").string()); }
  std::string table() const { return shell_quote((dir / "nodes.csv").string()); }
  std::string out(const std::string& name = "out") const { return shell_quote((dir / name).string()); }

  void add(const Vec3& point, const Vec3& deflection) {
    nodes.points.push_back(point);
    nodes.deflections.push_back(deflection);
    nodes.ids.push_back(static_cast<std::int64_t>(100 + nodes.ids.size()));
  }
  /// Face 1 on a 5 x 5 grid of (t, s) (its column t = 1 lies on face 2 too), face 2 on 4 x 5
  /// (t > 0): each face has a 5 x 5 grid of nodes.
  void add_grids(bool face_1 = true, bool face_2 = true) {
    for (int i = 0; i <= 4; ++i) {
      for (int j = 0; j <= 4; ++j) {
        const double t = i / 4.0, s = j / 4.0;
        if (face_1) add(face1.point(t, s), delta_1(t, s));
        if (face_2 && i > 0) add(face2.point(t, s), delta_2(t, s));
      }
    }
  }
  void write_table() const { test::write_text(dir / "nodes.csv", io::format_deflection_csv(nodes)); }
};

nlohmann::json summary_of(const std::filesystem::path& folder) {
  return nlohmann::json::parse(test::read_text(folder / "summary.json"));
}

TEST(SurfaceCli, HasHelpAndIsListed) {
  const auto help = hotmesh("surface --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.output, HasSubstr("--drop-far-nodes"));
  EXPECT_THAT(help.output, HasSubstr("--faces"));
  EXPECT_THAT(hotmesh("--help").output, HasSubstr("surface"));
}

// Deflections of degree <= q in (t, s) give the deformed faces S + delta: exactly (to round-off)
// for the polynomial face, within the reported deviation for the rational one; both read back
// from deformed.step by OpenCASCADE and compared at random parameters.
TEST(SurfaceCli, DeformedFacesReproducePolynomialDeflections) {
  Case c;
  c.add_grids();
  c.write_table();
  const auto r = hotmesh("surface --cad " + c.step() + " --faces 1,2 --fem " + c.table() + " --degree 2 -o " + c.out());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("face 2: 25 nodes, interpolation"));

  const nlohmann::json summary = summary_of(c.dir / "out");
  EXPECT_EQ(summary["degree"], 2);
  EXPECT_EQ(summary["nodes"], 45);
  EXPECT_EQ(summary["used_nodes"], 45);
  EXPECT_EQ(summary["rejected_nodes"].size(), 0u);
  EXPECT_EQ(summary["inputs"]["faces"], nlohmann::json({1, 2}));
  EXPECT_EQ(summary["inputs"]["unit"], "m");
  EXPECT_LT(summary["max_node_residual"].get<double>(), 1e-12);
  EXPECT_LT(summary["max_node_distance_to_cad"].get<double>(), 1e-10);
  EXPECT_LT(summary["max_edge_gap"].get<double>(), 1e-12);  // both fields carry on_edge(s)
  EXPECT_EQ(summary["shared_edges"], 1);
  EXPECT_EQ(summary["joined_edges"], 1);
  EXPECT_GT(summary["tolerance"].get<double>(), 0.0);
  ASSERT_EQ(summary["faces"].size(), 2u);
  const nlohmann::json& f1 = summary["faces"][0];
  const nlohmann::json& f2 = summary["faces"][1];
  EXPECT_EQ(f1["id"], 1);
  EXPECT_EQ(f1["name"], "wavy");
  EXPECT_EQ(f1["nodes"], 25);
  EXPECT_EQ(f1["method"], "interpolation");
  EXPECT_EQ(f1["poles"], nlohmann::json({5, 5}));
  EXPECT_EQ(f1["exact"], true);
  EXPECT_LT(f1["max_deviation"].get<double>(), 1e-14);
  EXPECT_EQ(f1["export_degree"], nlohmann::json({3, 3}));
  EXPECT_EQ(f2["id"], 2);
  EXPECT_EQ(f2["rational"], true);
  EXPECT_EQ(f2["nodes"], 25);  // 20 of its own and the 5 on the shared edge
  EXPECT_EQ(f2["exact"], false);
  const double deviation = f2["max_deviation"].get<double>();
  EXPECT_GT(deviation, 0.0);     // a rational face is interpolated, not summed
  EXPECT_LT(deviation, 1.3e-9);  // within 1e-9 of the face's size (its poles' diagonal, 1.22)
  EXPECT_GT(f2["deviation_checks"].get<int>(), 100);

  const geometry::CadModel deformed = geometry::CadModel::read(c.dir / "out" / "deformed.step");
  ASSERT_EQ(deformed.faces().size(), 2u);
  EXPECT_EQ(deformed.faces()[0].name, "face 1");
  const BSplineSurface s1 = deformed.face_bspline(1);
  const BSplineSurface s2 = deformed.face_bspline(2);
  EXPECT_FALSE(s1.is_rational());
  std::mt19937 random(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst1 = 0.0, worst2 = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double t = unit(random), s = unit(random);
    worst1 = std::max(worst1, distance(s1.point(t, s), c.face1.point(t, s) + delta_1(t, s)));
    worst2 = std::max(worst2, distance(s2.point(t, s), c.face2.point(t, s) + delta_2(t, s)));
  }
  EXPECT_LT(worst1, 1e-12);
  EXPECT_LT(worst2, 2.0 * deviation + 1e-12);
  EXPECT_GT(distance(s1.point(0.5, 0.5), c.face1.point(0.5, 0.5)), 0.003);  // it did move
  // The IGES file holds the same faces.
  const geometry::CadModel iges = geometry::CadModel::read(c.dir / "out" / "deformed.iges");
  ASSERT_EQ(iges.faces().size(), 2u);
  EXPECT_LT(distance(iges.face_bspline(1).point(0.3, 0.7), c.face1.point(0.3, 0.7) + delta_1(0.3, 0.7)), 1e-9);
}

// nodes.vtp and faces.vtp as VTK's own reader sees them: every placement of a node with its
// face, (t, s), distance and residual; each face a triangulated grid of S + d with d and |d|.
TEST(SurfaceCli, NodesAndFacesOpenInVtk) {
  Case c;
  c.add_grids();
  c.write_table();
  const auto r = hotmesh("-q surface --cad " + c.step() + " --faces 2,1 --fem " + c.table() +
                         " --degree 2 --samples 8 -o " + c.out());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const nlohmann::json nodes = test::read_with_vtk(c.dir / "out" / "nodes.vtp");
  ASSERT_FALSE(nodes.contains("error")) << nodes;
  const std::size_t count = 50;  // 45 nodes, the 5 on the shared edge twice
  ASSERT_EQ(nodes["points"].size(), 3 * count);
  EXPECT_EQ(nodes["cell_types"], nlohmann::json(std::vector<int>(count, 1)));  // VTK_VERTEX
  const auto& data = nodes["point_data"];
  for (const char* name : {"deflection", "face", "t", "s", "distance", "residual", "rejected", "line", "id"}) {
    ASSERT_TRUE(data.contains(name)) << name;
  }
  EXPECT_EQ(data["deflection"]["components"], 3);
  int on_face[3] = {0, 0, 0};
  for (std::size_t k = 0; k < count; ++k) {
    const int face = data["face"]["values"][k].get<int>();
    ASSERT_TRUE(face == 1 || face == 2) << face;
    ++on_face[face];
    const double t = data["t"]["values"][k].get<double>(), s = data["s"]["values"][k].get<double>();
    const Vec3 q{nodes["points"][3 * k].get<double>(), nodes["points"][3 * k + 1].get<double>(),
                 nodes["points"][3 * k + 2].get<double>()};
    const Vec3 expected = face == 1 ? delta_1(t, s) : delta_2(t, s);
    const Vec3 given{data["deflection"]["values"][3 * k].get<double>(), data["deflection"]["values"][3 * k + 1].get<double>(),
                     data["deflection"]["values"][3 * k + 2].get<double>()};
    EXPECT_LT(distance(given, expected), 1e-10) << k;  // (t, s) is where the node lies on its face
    EXPECT_LT(distance(q, (face == 1 ? c.face1 : c.face2).point(t, s)), 1e-10) << k;
    EXPECT_LT(data["residual"]["values"][k].get<double>(), 1e-12);
    EXPECT_LT(data["distance"]["values"][k].get<double>(), 1e-10);
    EXPECT_EQ(data["rejected"]["values"][k], 0);
    EXPECT_GE(data["id"]["values"][k].get<int>(), 100);
  }
  EXPECT_EQ(on_face[1], 25);
  EXPECT_EQ(on_face[2], 25);

  const nlohmann::json faces = test::read_with_vtk(c.dir / "out" / "faces.vtp");
  ASSERT_FALSE(faces.contains("error")) << faces;
  ASSERT_EQ(faces["points"].size(), 3u * 2 * 81);                                  // 9 x 9 per face
  EXPECT_EQ(faces["cell_types"], nlohmann::json(std::vector<int>(2 * 128, 5)));  // VTK_TRIANGLE
  const auto& fd = faces["point_data"];
  for (std::size_t k = 0; k < 2 * 81; k += 7) {
    const int face = fd["face"]["values"][k].get<int>();
    const double t = fd["t"]["values"][k].get<double>(), s = fd["s"]["values"][k].get<double>();
    const Vec3 d = face == 1 ? delta_1(t, s) : delta_2(t, s);
    const Vec3 p{faces["points"][3 * k].get<double>(), faces["points"][3 * k + 1].get<double>(),
                 faces["points"][3 * k + 2].get<double>()};
    EXPECT_LT(distance(p, (face == 1 ? c.face1 : c.face2).point(t, s) + d), 1e-12) << k;
    EXPECT_NEAR(fd["deflection_magnitude"]["values"][k].get<double>(), norm(d), 1e-12) << k;
    EXPECT_NEAR(fd["deflection"]["values"][3 * k + 2].get<double>(), d.z, 1e-12) << k;
  }
  EXPECT_EQ(fd["face"]["values"][0], 2);  // in the order of --faces

  // residuals.png: a PNG of one row of two panels (IHDR width and height, big-endian).
  const std::string png = test::read_text(c.dir / "out" / "residuals.png");
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned char>(png[at]) << 24) | (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  EXPECT_EQ(be32(16), 950);
  EXPECT_EQ(be32(20), 570);
}

// Scattered nodes (least squares) in millimetres: still reproduced, the unit declared in the
// STEP file and the summary.
TEST(SurfaceCli, ScatteredNodesInMillimetres) {
  Case c(geometry::LengthUnit::millimetre);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 60; ++k) {
    const double t = unit(random), s = unit(random);
    c.add(c.face1.point(t, s), delta_1(t, s));
  }
  c.write_table();
  const auto r = hotmesh("surface --unit mm --cad " + c.step() + " --faces 1 --fem " + c.table() +
                         " --degree 2 -o " + c.out());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json summary = summary_of(c.dir / "out");
  EXPECT_EQ(summary["inputs"]["unit"], "mm");
  EXPECT_EQ(summary["faces"][0]["method"], "least_squares");
  EXPECT_EQ(summary["faces"][0]["exact"], true);
  EXPECT_LT(summary["max_node_residual"].get<double>(), 1e-9);
  EXPECT_THAT(test::read_text(c.dir / "out" / "deformed.step"), HasSubstr("SI_UNIT(.MILLI.,.METRE.)"));
  geometry::CadReadOptions mm;
  mm.unit = geometry::LengthUnit::millimetre;
  const BSplineSurface s1 = geometry::CadModel::read(c.dir / "out" / "deformed.step", mm).face_bspline(1);
  for (const double t : {0.1, 0.45, 0.9}) {
    for (const double s : {0.2, 0.6, 0.95}) {
      EXPECT_LT(distance(s1.point(t, s), c.face1.point(t, s) + delta_1(t, s)), 1e-8) << t << " " << s;
    }
  }
}

// A node far from the faces is named with its line, or left out with --drop-far-nodes (listed
// in summary.json and as a rejected vertex in nodes.vtp).
TEST(SurfaceCli, FarNodesAreListedOrDropped) {
  Case c;
  c.add_grids();
  c.add({0.5, 0.5, 0.4}, {0.0, 0.0, 0.0});  // id 145 on line 47, 0.4 above face 1
  c.write_table();
  const std::string common = "surface --cad " + c.step() + " --faces 1,2 --fem " + c.table() + " --degree 2";
  const auto fail = hotmesh(common + " -o " + c.out("a"));
  EXPECT_EQ(fail.exit_code, 2) << fail.output;
  EXPECT_THAT(fail.output, HasSubstr("nodes.csv"));
  EXPECT_THAT(fail.output, HasSubstr("1 of 46 FEM nodes are farther than"));
  EXPECT_THAT(fail.output, HasSubstr("node 145 (line 47)"));
  EXPECT_FALSE(std::filesystem::exists(c.dir / "a"));

  const auto drop = hotmesh(common + " --drop-far-nodes -o " + c.out("b"));
  ASSERT_EQ(drop.exit_code, 0) << drop.output;
  EXPECT_THAT(drop.output, HasSubstr("node 145 (line 47) is"));
  const nlohmann::json summary = summary_of(c.dir / "b");
  EXPECT_EQ(summary["used_nodes"], 45);
  ASSERT_EQ(summary["rejected_nodes"].size(), 1u);
  EXPECT_EQ(summary["rejected_nodes"][0]["id"], 145);
  EXPECT_EQ(summary["rejected_nodes"][0]["line"], 47);
  EXPECT_GT(summary["rejected_nodes"][0]["distance"].get<double>(), 0.3);
  const nlohmann::json nodes = test::read_with_vtk(c.dir / "b" / "nodes.vtp");
  ASSERT_EQ(nodes["points"].size(), 3u * 51);
  EXPECT_EQ(nodes["point_data"]["rejected"]["values"][50], 1);
  EXPECT_EQ(nodes["point_data"]["face"]["values"][50], 0);
  EXPECT_EQ(nodes["point_data"]["line"]["values"][50], 47);
  EXPECT_TRUE(nodes["point_data"]["t"]["values"][50].is_null());  // NaN: on no face
  EXPECT_TRUE(nodes["point_data"]["residual"]["values"][50].is_null());
}

TEST(SurfaceCli, BadInputIsExitCodeTwoNamingTheProblem) {
  Case c;
  c.add_grids();
  c.write_table();
  const std::string fem = " --fem " + c.table();
  const auto expect_refused = [&](const std::string& arguments, const std::string& message) {
    const auto r = hotmesh("surface --cad " + c.step() + arguments + " -o " + c.out("x"));
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(message)) << arguments;
    EXPECT_FALSE(std::filesystem::exists(c.dir / "x")) << arguments;
  };
  expect_refused(" --faces 1,3" + fem, "faces.step: no face 3: the faces are 1 to 2");
  expect_refused(" --faces 1,1" + fem, "faces.step: face 1 is given twice");
  expect_refused(" --faces 1,2" + fem + " --degree 5",
                 "CAD face 1: 25 FEM nodes on this face cannot determine a deflection surface of degree 5");
  expect_refused(" --faces 1,2" + fem + " --unit furlong", "unknown length unit 'furlong'");
  expect_refused(fem, "--faces is required");

  test::write_text(c.dir / "planar.csv", "x,y,dx,dy\n0,0,0,0.1\n1,0,0,0.1\n");
  expect_refused(" --faces 1 --fem " + shell_quote((c.dir / "planar.csv").string()),
                 "planar.csv: a wall reconstructed on CAD faces needs a cartesian (x, y, z) table, got a planar (x, y) one");
  test::write_text(c.dir / "bad.csv", "x,y,z,dx,dy,dz\n0,0,0,0,0\n");
  expect_refused(" --faces 1 --fem " + shell_quote((c.dir / "bad.csv").string()), "bad.csv:2");

  // Face 1 without nodes: only face 2's own (t > 0) are given.
  Case only2;
  only2.add_grids(false, true);
  only2.write_table();
  const auto none = hotmesh("surface --cad " + only2.step() + " --faces 1,2 --fem " + only2.table() + " -o " +
                            only2.out());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_THAT(none.output, HasSubstr("no FEM node lies on CAD face 1"));
  // Face 2 with only the 5 nodes of the shared edge: too few for degree 1, named.
  Case only1;
  only1.add_grids(true, false);
  only1.write_table();
  const auto few = hotmesh("surface --cad " + only1.step() + " --faces 1,2 --fem " + only1.table() + " -o " +
                           only1.out());
  EXPECT_EQ(few.exit_code, 2);
  EXPECT_THAT(few.output, HasSubstr("CAD face 2: 5 FEM nodes on this face cannot determine"));

  // An output folder holding the inputs is refused; nothing is written next to them.
  const auto in_place = hotmesh("surface --cad " + c.step() + " --faces 1,2" + fem + " --degree 2 -o " +
                                shell_quote(c.dir.path().string()));
  EXPECT_EQ(in_place.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(c.dir / "summary.json"));
}

// A real CAD file end to end: I-DEAS's cylinder (rational B-spline faces whose knot vectors
// float, caps trimmed by the circles) with a cap given first. hotmesh surface reads every face,
// keeps the three as one wall (the circles are edges of the file shared by the lateral face and
// the caps) and joins the lateral face to the caps along them.
TEST(SurfaceCli, ARealCylinderWithTrimmedCapsIsOneWallWhoseFacesMeet) {
  Case c;
  c.nodes = {};
  c.nodes.frame = geometry::SampleFrame::cartesian;
  const auto deflection = [](const Vec3& p) { return Vec3{0.002 * p.x + 1e-4, 1e-4 * std::cos(30.0 * p.x), 0.003 * p.z}; };
  for (int i = 0; i < 24; ++i) {
    for (int j = 0; j <= 6; ++j) {
      const double angle = 2.0 * M_PI * i / 24.0;
      const Vec3 p{0.025 * std::cos(angle), -0.075 + 0.025 * j, 0.025 * std::sin(angle)};
      c.add(p, deflection(p));
    }
  }
  for (const double y : {-0.075, 0.075}) {
    for (int i = 0; i < 8; ++i) {
      const Vec3 p{0.015 * std::cos(M_PI * i / 4.0), y, 0.015 * std::sin(M_PI * i / 4.0)};
      c.add(p, deflection(p));
    }
    c.add({0.0, y, 0.0}, deflection({0.0, y, 0.0}));
  }
  c.write_table();
  const std::string cylinder = shell_quote(test::data_path("cad/OCC8842_cylinder_Ideas.igs").string());
  const auto r = hotmesh("surface --cad " + cylinder + " --faces 2,1,3 --fem " + c.table() + " --degree 3 -o " + c.out());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json summary = summary_of(c.dir / "out");
  EXPECT_EQ(summary["shared_edges"], 2) << summary.dump(2);
  EXPECT_LT(summary["max_edge_gap"].get<double>(), 1e-8);
}

}  // namespace
}  // namespace hotmesh::app
