// Tests of `hotmesh deform` on 3D walls that are not surfaces of revolution (issue 23): a box
// channel whose floor takes an x, y, z table without CAD and without an axis (prescribed, the
// table interpolated over the floor), and on a CAD face in B-spline form (prescribed and
// sliding, the deflection field fitted on the face); a sliding floor without faces is refused.
// The floor on a CAD face is measured both ways against its deflected face, in report.json and
// by `hotmesh check --case` (which describes the wall as deform builds it); the floor without CAD
// is said not to be measured, and why.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "deform_cases.hpp"
#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using test::hotmesh;
using test::read_json;
using test::shell_quote;
using geometry::distance;

/// The floor's deflection: a bulge and a shear along the channel, with a linear part.
geometry::Vec3 bulge(const geometry::Vec3& x) {
  return {0.02 * x.y, 0.0, 0.05 + 0.02 * x.x - 0.01 * x.y + 0.08 * std::sin(M_PI * x.x / 4.0) * std::sin(M_PI * x.y)};
}
/// The same without its sine: linear in x, y.
geometry::Vec3 tilt(const geometry::Vec3& x) { return {0.02 * x.y, 0.0, 0.05 + 0.02 * x.x - 0.01 * x.y}; }

/// A box channel [0, 4] x [0, 1] x [0, 1] of 16 x 4 x 8 hexes (patches inlet, outlet, sides,
/// floor, ceiling) in `dir`, a table of the floor's FEM nodes on a 9 x 5 grid, and the floor
/// as a bilinear B-spline face in floor.step (face 1).
template <class F>
void write_channel(const std::filesystem::path& dir, F deflection) {
  const auto xs = mesh::uniform_line(0.0, 4.0, 16);
  const auto ys = mesh::uniform_line(0.0, 1.0, 4);
  const auto zs = mesh::uniform_line(0.0, 1.0, 8);
  io::write_gmsh(dir / "box.msh",
                 mesh::structured_hexes(xs, ys, zs, {"inlet", "outlet", "side_a", "side_b", "floor", "ceiling"}));
  std::string table = "x,y,z,dx,dy,dz\n";
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const geometry::Vec3 x{0.5 * i, 0.25 * j, 0.0};
      const geometry::Vec3 d = deflection(x);
      table += fmt::format("{},{},{},{:.17g},{:.17g},{:.17g}\n", x.x, x.y, x.z, d.x, d.y, d.z);
    }
  }
  test::write_text(dir / "floor.csv", table);
  geometry::CadExport cad;
  cad.surfaces.push_back({"floor", geometry::BSplineSurface(1, 1, {0, 0, 4, 4}, {0, 0, 1, 1},
                                                              {{0, 0, 0}, {0, 1, 0}, {4, 0, 0}, {4, 1, 0}})});
  test::write_text(dir / "floor.step", geometry::to_step(cad));
}

std::string channel_case(const std::string& floor, const std::string& extra = "",
                         const std::string& linear = "jacobi-pcg") {
  return fmt::format("mesh: box.msh\n{}solver: {{increments: 4, newton_tolerance: 1.0e-8, pcg_tolerance: 1.0e-8, "
                     "linear: {}}}\n"
                     "patches:\n  inlet: {{role: slip}}\n  outlet: {{role: slip}}\n  side_a: {{role: slip}}\n"
                     "  side_b: {{role: slip}}\n  ceiling: {{role: fixed}}\n  floor: {}\n",
                     extra, linear, floor);
}

struct DeformRun {
  test::CommandResult result;
  std::filesystem::path out;
};

DeformRun deform(const test::TempDir& dir, const std::string& yaml) {
  test::write_text(dir / "case.yaml", yaml);
  DeformRun r{{}, dir / "out"};
  r.result = hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " + shell_quote(r.out.string()));
  return r;
}

/// The floor nodes of the undeformed and the deformed mesh.
std::vector<std::pair<geometry::Vec3, geometry::Vec3>> floor_nodes(const std::filesystem::path& dir, const DeformRun& r) {
  const mesh::Mesh before = io::read_gmsh(dir / "box.msh");
  const mesh::Mesh after = io::read_gmsh(r.out / "deformed.msh");
  EXPECT_EQ(mesh::summarize_quality(mesh::scaled_jacobians(after.cells, after.points)).inverted_cells, 0u);
  std::vector<std::pair<geometry::Vec3, geometry::Vec3>> nodes;
  for (mesh::NodeId n : before.find_patch("floor")->nodes) {
    nodes.emplace_back(before.points[static_cast<std::size_t>(n)], after.points[static_cast<std::size_t>(n)]);
  }
  return nodes;
}

// Item 0 of issue 23: a plain box channel with an FEM table on its floor, no CAD and no axis.
// The table is interpolated over the floor, exactly for its linear part: with a linear
// deflection every floor node moves exactly by it.
TEST(DeformSurfaces, BoxChannelFloorTakesACartesianTableWithoutCadOrAxis) {
  test::TempDir dir;
  write_channel(dir.path(), tilt);
  const DeformRun r = deform(dir, channel_case("{role: prescribed, deflection: {file: floor.csv}}"));
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  for (const auto& [x0, x] : floor_nodes(dir.path(), r)) {
    EXPECT_LT(distance(x, x0 + tilt(x0)), 1e-10) << x0.x << " " << x0.y;
  }
  const auto report = read_json(r.out / "report.json");
  EXPECT_EQ(report["deflections"][0]["wall"], "scattered");
  EXPECT_EQ(report["deflections"][0]["used_nodes"], 45);
}

/// A bump 0.35 high, piecewise linear along the channel: up from x = 1 to its ridge at 2, down to
/// 3; every kink on a column of the table's nodes.
geometry::Vec3 tent(const geometry::Vec3& x) { return {0.0, 0.0, 0.35 * std::clamp(1.0 - std::abs(x.x - 2.0), 0.0, 1.0)}; }

// Issue 49, item 8: `degree: 1` on a wall without CAD is linear between the table's nodes, so a
// piecewise-linear deflection with a node on every kink moves every floor node exactly by it
// (the smooth interpolation of higher degrees overshoots next to the kinks).
TEST(DeformSurfaces, PiecewiseLinearTableOnAFloorWithoutCadIsFollowedExactlyAtDegreeOne) {
  test::TempDir dir;
  write_channel(dir.path(), tent);
  const DeformRun linear = deform(dir, channel_case("{role: prescribed, deflection: {file: floor.csv, degree: 1}}"));
  ASSERT_EQ(linear.result.exit_code, 0) << linear.result.output;
  for (const auto& [x0, x] : floor_nodes(dir.path(), linear)) {
    EXPECT_LT(distance(x, x0 + tent(x0)), 1e-10) << x0.x << " " << x0.y;
  }
  const auto report = read_json(linear.out / "report.json");
  EXPECT_EQ(report["deflections"][0]["wall"], "scattered");
  EXPECT_EQ(report["deflections"][0]["interpolation"]["method"], "linear over triangles");
  EXPECT_EQ(report["deflections"][0]["interpolation"]["triangles"], 2 * 8 * 4);

  std::filesystem::remove_all(linear.out);
  const DeformRun smooth = deform(dir, channel_case("{role: prescribed, deflection: {file: floor.csv, degree: 2}}"));
  ASSERT_EQ(smooth.result.exit_code, 0) << smooth.result.output;
  double largest = 0.0;
  for (const auto& [x0, x] : floor_nodes(dir.path(), smooth)) largest = std::max(largest, distance(x, x0 + tent(x0)));
  EXPECT_GT(largest, 1e-3);
  EXPECT_EQ(read_json(smooth.out / "report.json")["deflections"][0]["interpolation"]["method"], "partition-of-unity RBF");
}

// The same floor as a CAD face: the deflection field d(t, s) fitted on the face through the
// nodes. Prescribed: every floor node at S + d; sliding: every floor node on the deflected face,
// and the mesh valid.
TEST(DeformSurfaces, FloorOnACadFacePrescribedAndSliding) {
  test::TempDir dir;
  write_channel(dir.path(), bulge);
  const DeformRun prescribed = deform(dir, channel_case("{role: prescribed, deflection: {file: floor.csv, faces: [1], "
                                                  "degree: 3}}",
                                                  "cad: floor.step\n"));
  ASSERT_EQ(prescribed.result.exit_code, 0) << prescribed.result.output;
  double worst = 0.0;
  for (const auto& [x0, x] : floor_nodes(dir.path(), prescribed)) worst = std::max(worst, distance(x, x0 + bulge(x0)));
  EXPECT_LT(worst, 2e-3);  // the bicubic interpolant of a sine on a 9 x 5 grid
  const auto report = read_json(prescribed.out / "report.json");
  EXPECT_EQ(report["deflections"][0]["wall"], "faces");
  EXPECT_EQ(report["deflections"][0]["faces"][0]["method"], "interpolation");

  std::filesystem::rename(prescribed.out, dir / "prescribed-out");
  const DeformRun sliding = deform(dir, channel_case("{role: sliding, deflection: {file: floor.csv, faces: [1], degree: "
                                               "3}}",
                                               "cad: floor.step\n"));
  ASSERT_EQ(sliding.result.exit_code, 0) << sliding.result.output;
  // Every floor node on the deflected floor, whatever it slid to: its material point p on the
  // cold floor (p + bulge(p) = x, solved by fixed-point iteration) is found within the fit's
  // accuracy; the corner nodes, held by the slip planes on two sides, stay at the corners.
  for (const auto& [x0, x] : floor_nodes(dir.path(), sliding)) {
    geometry::Vec3 p{x.x, x.y, 0.0};
    for (int k = 0; k < 100; ++k) p = {x.x - bulge(p).x, x.y - bulge(p).y, 0.0};
    EXPECT_LT(distance(p + bulge(p), x), 2e-3) << x0.x << " " << x0.y;
    if ((x0.x == 0.0 || x0.x == 4.0) && (x0.y == 0.0 || x0.y == 1.0)) {
      EXPECT_NEAR(x.x, x0.x, 1e-9);
      EXPECT_NEAR(x.y, x0.y, 1e-9);
    }
  }
  const auto slid = read_json(sliding.out / "report.json");
  EXPECT_EQ(slid["status"], "success");
  EXPECT_LT(slid["final_projection_distance"].get<double>(), 1e-9);
}

// The assembled solver (nodal frames in PETSc, algebraic multigrid) takes the deflected face's
// normals as Jacobi-PCG does: both end at the same mesh, to their tolerances.
TEST(DeformSurfaces, SlidingOnACadFaceEndsAlikeWithEitherLinearSolver) {
  test::TempDir dir;
  write_channel(dir.path(), bulge);
  const std::string floor = "{role: sliding, deflection: {file: floor.csv, faces: [1], degree: 3}}";
  const DeformRun pcg = deform(dir, channel_case(floor, "cad: floor.step\n"));
  ASSERT_EQ(pcg.result.exit_code, 0) << pcg.result.output;
  std::filesystem::rename(pcg.out, dir / "pcg-out");
  const DeformRun amg = deform(dir, channel_case(floor, "cad: floor.step\n", "amg"));
  ASSERT_EQ(amg.result.exit_code, 0) << amg.result.output;
  const mesh::Mesh a = io::read_gmsh(dir / "pcg-out" / "deformed.msh");
  const mesh::Mesh b = io::read_gmsh(amg.out / "deformed.msh");
  double apart = 0.0;
  for (std::size_t n = 0; n < a.points.size(); ++n) apart = std::max(apart, distance(a.points[n], b.points[n]));
  EXPECT_LT(apart, 1e-5);
}

/// A channel [0, 4] x [0, 1] whose floor bends up by 30 degrees at x = `crease` (two planar CAD
/// faces, 1 flat and 2 rising, sharing the edge x = crease), ceiling at z = 2; 16 x 4 x 8 hexes
/// whose floor nodes lie on the bent floor (at x = 0, 0.25, ...: on the crease where it is at 2).
/// The FEM table: a 9 x 5 grid over both faces, with a deflection linear along the floor.
const double kRise = std::tan(M_PI / 6.0);
geometry::Vec3 bent_floor(double x, double y, double crease = 2.0) {
  return {x, y, x > crease ? (x - crease) * kRise : 0.0};
}
geometry::Vec3 crease_shift(const geometry::Vec3& x) { return {0.1 + 0.02 * x.y, 0.0, 0.05 + 0.02 * x.y}; }

/// The channel of hexes, or with every hex split (mesh/split_cells.hpp) as `cells` says.
void write_bent_channel(const std::filesystem::path& dir, double crease = 2.0, mesh::CellSplit cells = mesh::CellSplit::keep) {
  mesh::Mesh m = mesh::structured_hexes(mesh::uniform_line(0.0, 4.0, 16), mesh::uniform_line(0.0, 1.0, 4),
                                        mesh::uniform_line(0.0, 2.0, 8),
                                        {"inlet", "outlet", "side_a", "side_b", "floor", "ceiling"});
  for (auto& p : m.points) {
    const double floor = bent_floor(p.x, p.y, crease).z;
    p.z = floor + p.z * (2.0 - floor) / 2.0;
  }
  if (cells != mesh::CellSplit::keep) m = mesh::split_cells(m, std::vector<mesh::CellSplit>(m.cell_count(), cells));
  io::write_gmsh(dir / "box.msh", m);
  std::string table = "x,y,z,dx,dy,dz\n";
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const geometry::Vec3 x = bent_floor(0.5 * i, 0.25 * j, crease), d = crease_shift(x);
      table += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", x.x, x.y, x.z, d.x, d.y, d.z);
    }
  }
  test::write_text(dir / "floor.csv", table);
  geometry::CadExport cad;
  const auto face = [crease](double x0, double x1) {
    const geometry::Vec3 a = bent_floor(x0, 0, crease), b = bent_floor(x0, 1, crease), c = bent_floor(x1, 0, crease),
                         d = bent_floor(x1, 1, crease);
    return geometry::BSplineSurface(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {a, b, c, d});
  };
  cad.surfaces = {{"flat", face(0, crease)}, {"rising", face(crease, 4)}};
  test::write_text(dir / "floor.step", geometry::to_step(cad));
}

// A crease of the wall (issue 23 item 2, issue 20 item 2 on faces): the floor nodes on the edge
// where the two faces meet at 30 degrees slide along that edge only, so the deflected floor
// keeps its crease: each ends on the deflected edge, (2, y, 0) + d.
TEST(DeformSurfaces, NodesOnACreaseBetweenTwoFacesSlideAlongIt) {
  test::TempDir dir;
  write_bent_channel(dir.path());
  const DeformRun r = deform(dir, channel_case("{role: sliding, deflection: {file: floor.csv, faces: [1, 2]}}",
                                               "cad: floor.step\n"));
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  EXPECT_THAT(r.result.output, HasSubstr("patch floor: 0 corners and 1 creases held from the start by the nodes on them"));
  int on_crease = 0;
  for (const auto& [x0, x] : floor_nodes(dir.path(), r)) {
    if (std::abs(x0.x - 2.0) > 1e-12) continue;
    ++on_crease;
    const geometry::Vec3 edge = bent_floor(2.0, x.y) + crease_shift(bent_floor(2.0, x.y));
    EXPECT_NEAR(x.x, edge.x, 1e-6) << "node at y = " << x0.y;
    EXPECT_NEAR(x.z, edge.z, 1e-6) << "node at y = " << x0.y;
  }
  EXPECT_EQ(on_crease, 5);
  // report.json lists the crease with its CAD faces, its 5 nodes and their distance from it.
  const auto features = read_json(r.out / "report.json")["features"];
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(features[0]["kind"], "crease");
  EXPECT_EQ(features[0]["faces"], nlohmann::json::array({1, 2}));
  EXPECT_EQ(features[0]["nodes"].size(), 5u);
  // 30 degrees undeformed; the deflection, whose dz grows with y, turns the faces by 0.006 more.
  EXPECT_NEAR(features[0]["angle_deg"].get<double>(), 30.0057, 1e-4);
  EXPECT_LT(features[0]["distance"].get<double>(), 1e-9);
}

// A crease the mesh's lines miss (issue 20 item 2 on faces): the floor bends at x = 2.1, between
// the rows of floor nodes at x = 2 (on the flat face) and 2.25 (on the rising face), so the
// wall's quads cut the crease by a chord. The motion's sliding draws the nodes towards the
// crease but leaves the chord (the deflected floor 0.013 off the wall); with features (the
// default) the corner pass then gives the crease the row nearest it, one node per column of
// wall faces, each led onto the deflected edge (2.1, y, 0) + d, those on the channel's sides
// where the edge crosses them. The planar faces and the linear deflection then leave the
// floor's quads on the deflected faces to round-off, both ways.
TEST(DeformSurfaces, ACreaseTheMeshLinesMissIsGivenTheNearestRowOfNodes) {
  constexpr double kCrease = 2.1;
  test::TempDir dir;
  write_bent_channel(dir.path(), kCrease);
  const auto floor = [](const std::string& extra) {
    return "{role: sliding, deflection: {file: floor.csv, faces: [1, 2]}" + extra + "}";
  };
  const DeformRun r = deform(dir, channel_case(floor(""), "cad: floor.step\n"));
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  // The deflected edge: (2.1, y, 0) + d(2.1, y, 0) for y in [0, 1].
  const auto off_edge = [&](const geometry::Vec3& x) {
    const geometry::Vec3 a = bent_floor(kCrease, 0.0, kCrease), b = bent_floor(kCrease, 1.0, kCrease);
    const geometry::Vec3 p = a + crease_shift(a), q = b + crease_shift(b);
    const geometry::Vec3 along = (q - p) / norm(q - p);
    return norm(cross(x - p, along));
  };
  std::vector<double> columns_on_edge;
  for (const auto& [x0, x] : floor_nodes(dir.path(), r)) {
    if (off_edge(x) < 1e-6) columns_on_edge.push_back(x0.y);
  }
  EXPECT_THAT(columns_on_edge, ::testing::UnorderedElementsAre(0.0, 0.25, 0.5, 0.75, 1.0));
  const auto report = read_json(r.out / "report.json");
  const auto& features = report["features"];
  ASSERT_EQ(features.size(), 1u) << features.dump();
  EXPECT_EQ(features[0]["kind"], "crease");
  EXPECT_EQ(features[0]["faces"], nlohmann::json::array({1, 2}));
  EXPECT_EQ(features[0]["nodes"].size(), 5u);
  EXPECT_GT(features[0]["largest_offset"].get<double>(), 1e-3);
  EXPECT_LT(features[0]["largest_offset"].get<double>(), 0.125);  // the nearer end of a quarter-long edge
  EXPECT_EQ(features[0]["unheld_edges"], 0);
  EXPECT_LT(features[0]["distance"].get<double>(), 1e-9);
  ASSERT_EQ(report["wall_deviations"].size(), 1u);
  EXPECT_LT(report["wall_deviations"][0]["hausdorff"].get<double>(), 1e-6);

  const DeformRun off = deform(dir, channel_case(floor(", features: off"), "cad: floor.step\n"));
  ASSERT_EQ(off.result.exit_code, 0) << off.result.output;
  const auto cut = read_json(off.out / "report.json");
  EXPECT_TRUE(cut["features"].empty()) << cut["features"].dump();
  EXPECT_GT(cut["wall_deviations"][0]["hausdorff"].get<double>(), 0.01);
}

// The same crease on a mesh of tetrahedra (every hex split about its centre): the floor's faces
// are triangles, its edges run along diagonals too, and the crease is held as on hexes.
TEST(DeformSurfaces, ACreaseOnAFloorOfTrianglesIsHeldAsOnQuads) {
  constexpr double kCrease = 2.1;
  test::TempDir dir;
  write_bent_channel(dir.path(), kCrease, mesh::CellSplit::tetrahedra);
  const DeformRun r =
      deform(dir, channel_case("{role: sliding, deflection: {file: floor.csv, faces: [1, 2]}}", "cad: floor.step\n"));
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  const auto report = read_json(r.out / "report.json");
  EXPECT_EQ(report["quality"]["by_type"]["tet4"]["inverted_cells"], 0);
  const auto& features = report["features"];
  ASSERT_EQ(features.size(), 1u) << features.dump();
  EXPECT_EQ(features[0]["kind"], "crease");
  EXPECT_GE(features[0]["nodes"].size(), 5u);
  EXPECT_EQ(features[0]["unheld_edges"], 0);
  EXPECT_LT(features[0]["distance"].get<double>(), 1e-9);
  ASSERT_EQ(report["wall_deviations"].size(), 1u);
  EXPECT_LT(report["wall_deviations"][0]["hausdorff"].get<double>(), 1e-6);
}

/// `hotmesh check MESH --case case.yaml --format json` plus `extra`: its exit code, its report
/// and the text it prints on its own.
struct CheckRun {
  int exit_code = -1;
  nlohmann::json report;
  std::string text;
};
CheckRun check(const test::TempDir& dir, const std::filesystem::path& mesh, const std::string& extra = "") {
  const std::string arguments =
      "check " + shell_quote(mesh.string()) + " --case " + shell_quote((dir / "case.yaml").string()) + extra;
  CheckRun run;
  const test::CommandResult json = hotmesh("-q " + arguments + " --format json -o " + shell_quote((dir / "check.json").string()));
  run.exit_code = json.exit_code;
  run.report = read_json(dir / "check.json");
  run.text = hotmesh(arguments).output;
  return run;
}

// A floor on a CAD face is measured against its deflected face S + d, both ways (report.json's
// wall_deviations, hotmesh check's faces line). A linear deflection keeps the face planar and
// the fit reproduces it, so the quads are on it: round-off. The bulge curves it: the quads are
// off it by their faceting, a few 1e-3 (the sine's sagitta over a quarter-wide cell at the
// hump, 0.08 x 0.07 = 5.6e-3), which --wall-tol fails when tighter. A floor node raised by 0.05
// is found, in a face holding it.
TEST(DeformSurfaces, AFloorOnACadFaceIsMeasuredBothWaysAgainstItsDeflectedFace) {
  test::TempDir dir;
  const std::string floor = "{role: prescribed, deflection: {file: floor.csv, faces: [1], degree: 3}}";
  write_channel(dir.path(), tilt);
  const DeformRun flat = deform(dir, channel_case(floor, "cad: floor.step\n"));
  ASSERT_EQ(flat.result.exit_code, 0) << flat.result.output;
  const auto flat_report = read_json(flat.out / "report.json");
  ASSERT_EQ(flat_report["wall_deviations"].size(), 1u);
  const auto& planar = flat_report["wall_deviations"][0];
  EXPECT_EQ(planar["patch"], "floor");
  EXPECT_EQ(planar["shape"], "faces");
  EXPECT_EQ(planar["measured"], true);
  EXPECT_EQ(planar["faces"], 64);
  EXPECT_LT(planar["hausdorff"].get<double>(), 1e-9);
  EXPECT_GT(planar["shape_samples"].get<int>(), 64 * 16);

  std::filesystem::remove_all(flat.out);
  write_channel(dir.path(), bulge);
  const DeformRun hump = deform(dir, channel_case(floor, "cad: floor.step\n"));
  ASSERT_EQ(hump.result.exit_code, 0) << hump.result.output;
  const auto report = read_json(hump.out / "report.json");
  ASSERT_EQ(report["wall_deviations"].size(), 1u);
  const auto& wall = report["wall_deviations"][0];
  EXPECT_EQ(wall["shape"], "faces");
  EXPECT_EQ(wall["stage"], 1.0);
  const double hausdorff = wall["hausdorff"].get<double>();
  EXPECT_GT(hausdorff, 3e-3);
  EXPECT_LT(hausdorff, 9e-3);
  for (const char* side : {"mesh_to_shape", "shape_to_mesh"}) {
    EXPECT_EQ(wall[side]["cad_face"], 1) << side;
    EXPECT_EQ(wall[side]["face_nodes"].size(), 4u) << side;
    EXPECT_GT(wall[side]["distance"].get<double>(), 1e-3) << side;  // both ways: faceting
  }
  // Near the hump's crest (x = 2, y = 0.5), between nodes across the floor (y = 0.25 ... 0.75).
  const auto& worst = wall["worst_point"];
  EXPECT_NEAR(worst[0].get<double>(), 2.0, 0.75);
  EXPECT_GT(std::abs(4.0 * worst[1].get<double>() - std::round(4.0 * worst[1].get<double>())), 0.1);

  // hotmesh check on the deformed mesh against the case: the same measure, and the wall
  // described as deform builds it (no axis: the case has none).
  const CheckRun checked = check(dir, hump.out / "deformed.msh");
  ASSERT_EQ(checked.exit_code, 0) << checked.text;
  const auto& patch = checked.report["patches"][0];
  EXPECT_EQ(patch["patch"], "floor");
  EXPECT_LT(patch["max_distance"].get<double>(), 1e-9);  // prescribed: the nodes on the face
  EXPECT_NEAR(patch["wall"]["hausdorff"].get<double>(), hausdorff, 1e-9);
  EXPECT_EQ(patch["wall"]["passed"], true);
  EXPECT_EQ(patch["reference"], "the deflected wall of the case (prescribed): CAD face 1 of floor.step, deflected by "
                                "floor.csv (a field d(t, s) on each face, degree 3, displacement form)");
  EXPECT_THAT(checked.text, HasSubstr(fmt::format("faces: two-sided distance {:.3e} over 64 faces",
                                                  patch["wall"]["hausdorff"].get<double>())));
  EXPECT_THAT(checked.text, ::testing::Not(HasSubstr("axis")));
  EXPECT_THAT(checked.text, ::testing::Not(HasSubstr("not measured")));
  const CheckRun tight = check(dir, hump.out / "deformed.msh", fmt::format(" --wall-tol {:.3e}", 0.5 * hausdorff));
  EXPECT_EQ(tight.exit_code, 1) << tight.text;
  EXPECT_EQ(tight.report["patches"][0]["wall"]["passed"], false);
  EXPECT_THAT(tight.text, HasSubstr("FAIL floor"));
  EXPECT_EQ(check(dir, hump.out / "deformed.msh", fmt::format(" --wall-tol {:.3e}", 2.0 * hausdorff)).exit_code, 0);

  // The case's own mesh against the undeformed face (flat, the mesh's floor on it).
  const CheckRun cold = check(dir, dir / "box.msh");
  ASSERT_EQ(cold.exit_code, 0) << cold.text;
  EXPECT_EQ(cold.report["patches"][0]["reference"],
            "the undeformed wall of the case (prescribed): CAD face 1 of floor.step");
  EXPECT_LT(cold.report["patches"][0]["wall"]["hausdorff"].get<double>(), 1e-12);

  // A floor node raised by 0.05: the faces are that far from the face, at the node.
  mesh::Mesh moved = io::read_gmsh(hump.out / "deformed.msh");
  const mesh::Mesh box = io::read_gmsh(dir / "box.msh");
  const auto& on_floor = box.find_patch("floor")->nodes;
  const mesh::NodeId node = *std::min_element(on_floor.begin(), on_floor.end(), [&](mesh::NodeId a, mesh::NodeId b) {
    const geometry::Vec3 at{1.5, 0.5, 0.0};  // inside the floor, on the hump's flank
    return distance(box.points[static_cast<std::size_t>(a)], at) < distance(box.points[static_cast<std::size_t>(b)], at);
  });
  geometry::Vec3& p = moved.points[static_cast<std::size_t>(node)];
  p.z += 0.05;
  io::write_gmsh(dir / "moved.msh", moved);
  const CheckRun bumped = check(dir, dir / "moved.msh");
  const auto& bump = bumped.report["patches"][0]["wall"];
  EXPECT_NEAR(bump["mesh_to_shape"]["distance"].get<double>(), 0.05, 2e-3);  // along the face's normal
  EXPECT_EQ(bump["worst"], "mesh_to_shape");
  EXPECT_LT(std::hypot(bump["worst_point"][0].get<double>() - p.x, bump["worst_point"][1].get<double>() - p.y,
                       bump["worst_point"][2].get<double>() - p.z),
            1e-9);
  const auto& holding = bump["mesh_to_shape"]["face_nodes"];
  EXPECT_NE(std::find(holding.begin(), holding.end(), moved.node_id(node)), holding.end());
}

// A floor without CAD moves by the table interpolated over it: there is no surface to measure
// its faces against, and report.json and hotmesh check say so.
TEST(DeformSurfaces, AFloorWithoutCadIsSaidNotToBeMeasured) {
  test::TempDir dir;
  write_channel(dir.path(), bulge);
  const DeformRun r = deform(dir, channel_case("{role: prescribed, deflection: {file: floor.csv}}"));
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  const auto report = read_json(r.out / "report.json");
  ASSERT_EQ(report["wall_deviations"].size(), 1u);
  const auto& wall = report["wall_deviations"][0];
  EXPECT_EQ(wall["patch"], "floor");
  EXPECT_EQ(wall["shape"], "scattered");
  EXPECT_EQ(wall["measured"], false);
  EXPECT_TRUE(wall["hausdorff"].is_null());
  EXPECT_EQ(wall["reason"], "the wall has no surface, only the table's interpolated displacement");

  const CheckRun checked = check(dir, r.out / "deformed.msh", " --wall-tol 1e-6");
  EXPECT_EQ(checked.exit_code, 0) << checked.text;  // not measured: the wall tolerance does not apply
  EXPECT_THAT(checked.text,
              HasSubstr("faces: not measured: the wall has no surface, only the table's interpolated displacement"));
  EXPECT_EQ(checked.report["patches"][0]["reference"],
            "the deflected wall of the case (prescribed): the table floor.csv interpolated over the wall "
            "(linear over triangles)");
  EXPECT_EQ(checked.report["patches"][0]["wall"]["measured"], false);
}

TEST(DeformSurfaces, SlidingFloorWithoutFacesIsRefused) {
  test::TempDir dir;
  write_channel(dir.path(), tilt);
  const DeformRun r = deform(dir, channel_case("{role: sliding, deflection: {file: floor.csv}}"));
  EXPECT_EQ(r.result.exit_code, 2);
  EXPECT_THAT(r.result.output, HasSubstr("patches.floor: a sliding wall that is not a surface of revolution slides "
                                         "over its CAD faces"));
}

}  // namespace
}  // namespace hotmesh::app
