// Tests of the duct3d sample (samples/duct3d): the committed mesh is a valid hex mesh whose
// patches lie on their CAD faces read back from duct.step (the floor a B-spline face, face 1),
// the FEM tables' nodes lie on the floor face and carry the loads, the exact deflected floor's
// derivatives and closest points are right, and the wall-distance measure is the faceting for
// the undeformed mesh and a known value for meshes moved by known motions. The case files name
// the floor face and the tables. The three cases run by hotmesh deform on a coarse duct
// (make_duct3d --cells 24,8,6): valid meshes, floors on the exact deflected floor, sliding no
// worse than prescribed, and the restart ending where a straight run of its load ends.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <regex>
#include <set>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "duct_floor.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/surface_distance.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "floor_distance.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::samples::duct3d {
namespace {

namespace fs = std::filesystem;
const fs::path kSample = fs::path(HOTMESH_SOURCE_DIR) / "samples" / "duct3d";

/// The committed mesh and CAD model, read once.
struct Committed {
  mesh::Mesh mesh = io::read_gmsh(kSample / kMeshFile);
  geometry::CadModel cad = geometry::CadModel::read(kSample / kCadFile, {.unit = geometry::LengthUnit::millimetre});
};
const Committed& committed() {
  static const Committed c;
  return c;
}

const Vec3& point(const mesh::Mesh& m, mesh::NodeId n) { return m.points[static_cast<std::size_t>(n)]; }

TEST(Duct3dMesh, IsAValidHexMeshOfGoodCells) {
  mesh::Mesh copy = committed().mesh;
  const auto report = mesh::validate_mesh(copy);
  EXPECT_EQ(report.reoriented_cells, 0u);
  EXPECT_EQ(report.interior_patch_faces, 0u);
  EXPECT_EQ(copy.cell_count(), 48u * 16u * 12u);
  EXPECT_EQ(copy.node_count(), 49u * 17u * 13u);
  const auto quality = mesh::summarize_quality(mesh::scaled_jacobians(copy.cells, copy.points));
  EXPECT_EQ(quality.inverted_cells, 0u);
  EXPECT_GT(quality.min_scaled_jacobian, 0.95);  // the floor slopes by 10 degrees at most
}

TEST(Duct3dMesh, PatchesAreNamedAndTaggedAsTheirCadFacesAndCoverTheBoundary) {
  const auto& m = committed().mesh;
  ASSERT_EQ(m.patches.size(), kPatchNames.size());
  std::size_t faces = 0;
  for (std::size_t i = 0; i < m.patches.size(); ++i) {
    EXPECT_EQ(m.patches[i].name, kPatchNames[i]);
    EXPECT_EQ(m.patches[i].tag, static_cast<int>(i) + 1);
    faces += m.patches[i].faces.size();
  }
  EXPECT_EQ(m.find_patch("floor")->faces.size(), 48u * 16u);
  EXPECT_EQ(m.find_patch("floor")->nodes.size(), 49u * 17u);
  mesh::Mesh copy = m;
  EXPECT_EQ(mesh::validate_mesh(copy).boundary_faces, faces);  // every boundary face in one patch
}

TEST(Duct3dCad, HasSixNamedFacesTheFloorAFreeFormFaceWithoutAxis) {
  const auto& cad = committed().cad;
  ASSERT_EQ(cad.faces().size(), 6u);
  for (std::size_t i = 0; i < kPatchNames.size(); ++i) EXPECT_EQ(cad.face(static_cast<int>(i) + 1).name, kPatchNames[i]);
  const auto& floor = cad.face(kFloorFace);
  EXPECT_EQ(floor.kind, geometry::SurfaceKind::bspline);
  EXPECT_EQ(floor.axis_source, geometry::AxisSource::none);  // not a surface of revolution
  // Bounding boxes are OpenCASCADE's, enlarged by its tolerance (1e-7).
  EXPECT_NEAR(floor.bounds.min.x, 0.0, 1e-6);
  EXPECT_NEAR(floor.bounds.max.x, kLength, 1e-6);
  EXPECT_NEAR(floor.bounds.min.y, 0.0, 1e-6);
  EXPECT_NEAR(floor.bounds.max.y, kWidth, 1e-6);
  EXPECT_GT(floor.bounds.max.z - floor.bounds.min.z, 0.05 * kH);  // not a plane
  EXPECT_LT(floor.bounds.max.z - floor.bounds.min.z, 0.2 * kH);
}

TEST(Duct3dCad, TheFloorFaceReadBackIsTheGeneratorsSurface) {
  const auto read = committed().cad.face_bspline(kFloorFace);
  const auto floor = floor_surface();
  ASSERT_EQ(read.u_degree(), 3);
  ASSERT_EQ(read.v_degree(), 3);
  ASSERT_EQ(read.poles().size(), floor.poles().size());
  double worst = 0.0;
  for (std::size_t i = 0; i < floor.poles().size(); ++i) worst = std::max(worst, distance(read.poles()[i], floor.poles()[i]));
  EXPECT_LT(worst, 1e-12 * kH);
  for (const double t : {0.0, 7.3, 21.1, kLength}) {
    for (const double s : {0.0, 4.4, 13.9, kWidth}) EXPECT_LT(distance(read.point(t, s), floor.point(t, s)), 1e-12 * kH);
  }
}

TEST(Duct3dCad, EveryPatchsNodesLieOnItsFace) {
  const auto& [m, cad] = committed();
  for (std::size_t i = 0; i < kPatchNames.size(); ++i) {
    const int face = static_cast<int>(i) + 1;
    geometry::SurfaceDistance surface({cad.face_bspline(face)});
    double worst = 0.0;
    for (const auto n : m.find_patch(kPatchNames[i])->nodes) worst = std::max(worst, surface.nearest(point(m, n)).distance);
    EXPECT_LT(worst, 1e-12 * kH) << kPatchNames[i];
  }
}

TEST(Duct3dCad, FloorNodesAreTheSurfaceAtTheirParameters) {
  const auto& m = committed().mesh;
  const auto floor = floor_surface();
  double worst = 0.0;
  for (const auto n : m.find_patch("floor")->nodes) {
    const Vec3& p = point(m, n);
    worst = std::max(worst, distance(floor.point(p.x, p.y), p));  // S(t, s) = (t, s, f(t, s))
  }
  EXPECT_LT(worst, 1e-12 * kH);
}

struct TableCase {
  const char* file;
  const Load* load;
  FemLayout layout;
};

// Named by the file in test listings (and so in ctest's names), not by the struct's bytes.
void PrintTo(const TableCase& c, std::ostream* os) { *os << c.file; }

class Duct3dTables : public ::testing::TestWithParam<TableCase> {};

TEST_P(Duct3dTables, NodesLieOnTheFloorFaceAndCarryTheLoad) {
  const auto& [file, load, layout] = GetParam();
  const auto table = io::read_deflection_csv(kSample / file);
  ASSERT_EQ(table.frame, geometry::SampleFrame::cartesian);
  ASSERT_EQ(table.size(), static_cast<std::size_t>(kFemNodesX * kFemNodesY));
  geometry::SurfaceDistance face({committed().cad.face_bspline(kFloorFace)});
  const DeflectedFloor floor(floor_surface(), *load);
  const auto parameters = fem_parameters(layout);
  double worst_cad = 0.0, worst_node = 0.0, worst_deflection = 0.0;
  for (std::size_t j = 0; j < table.size(); ++j) {
    EXPECT_EQ(table.ids[j], static_cast<std::int64_t>(j) + 1);
    worst_cad = std::max(worst_cad, face.nearest(table.points[j]).distance);
    const auto [t, s] = parameters[j];
    worst_node = std::max(worst_node, distance(table.points[j], floor.floor().point(t, s)));
    worst_deflection = std::max(worst_deflection, distance(table.deflections[j], floor.deflection(t, s)));
  }
  EXPECT_LT(worst_cad, 1e-12 * kH);
  EXPECT_EQ(worst_node, 0.0);  // the CSV's numbers read back exactly
  EXPECT_LT(worst_deflection, 1e-14 * kH);
}

INSTANTIATE_TEST_SUITE_P(Files, Duct3dTables,
                         ::testing::Values(TableCase{"floor.csv", &kHot1, FemLayout::scattered},
                                           TableCase{"floor_grid.csv", &kHot1, FemLayout::grid},
                                           TableCase{"floor_hot2.csv", &kHot2, FemLayout::scattered}));

TEST(Duct3dTableLayouts, TheGridIsATensorGridAndTheScatteredNodesAreNot) {
  const auto distinct = [](FemLayout layout) {
    std::set<double> ts, ss;
    for (const auto& [t, s] : fem_parameters(layout)) {
      ts.insert(t);
      ss.insert(s);
    }
    return std::pair{ts.size(), ss.size()};
  };
  EXPECT_EQ(distinct(FemLayout::grid), (std::pair<std::size_t, std::size_t>{kFemNodesX, kFemNodesY}));
  const auto [ts, ss] = distinct(FemLayout::scattered);
  EXPECT_GT(ts, static_cast<std::size_t>(5 * kFemNodesX));
  EXPECT_GT(ss, static_cast<std::size_t>(5 * kFemNodesY));
  // Jittered within the floor, edge nodes along their edges.
  const double dt = kLength / (kFemNodesX - 1), ds = kWidth / (kFemNodesY - 1);
  const auto grid = fem_parameters(FemLayout::grid), scattered = fem_parameters(FemLayout::scattered);
  for (std::size_t j = 0; j < grid.size(); ++j) {
    EXPECT_LE(std::abs(scattered[j].first - grid[j].first), 0.3 * dt);
    EXPECT_LE(std::abs(scattered[j].second - grid[j].second), 0.3 * ds);
    if (grid[j].first == 0.0 || grid[j].first == kLength) {
      EXPECT_EQ(scattered[j].first, grid[j].first);
    }
    if (grid[j].second == 0.0 || grid[j].second == kWidth) {
      EXPECT_EQ(scattered[j].second, grid[j].second);
    }
  }
}

TEST(Duct3dLoads, BulgeAlongTheNormalShearAlongTheDuctAndKeepTheOutline) {
  for (const Load* load : {&kHot1, &kHot2}) {
    const DeflectedFloor floor(floor_surface(), *load);
    double normal = 0.0, tangential = 0.0;
    for (int i = 0; i <= 200; ++i) {
      for (int j = 0; j <= 100; ++j) {
        const double t = kLength * i / 200, s = kWidth * j / 100;
        const auto d = floor.floor().derivatives(t, s);
        const Vec3 n = cross(d.du, d.dv) / norm(cross(d.du, d.dv));
        const Vec3 delta = floor.deflection(t, s);
        normal = std::max(normal, dot(delta, n));
        tangential = std::max(tangential, std::abs(dot(delta, d.du / norm(d.du))));
        if (i == 0 || i == 200) {
          EXPECT_LT(norm(delta), 1e-12 * kH) << load->name;  // inlet, outlet
        }
        if (j == 0 || j == 100) {
          EXPECT_LT(std::abs(delta.y), 1e-12 * kH) << load->name;  // in the side planes
        }
      }
    }
    EXPECT_NEAR(normal, load->bulge, 1e-3 * load->bulge) << load->name;
    EXPECT_NEAR(tangential, std::abs(load->shear), 1e-3 * std::abs(load->shear)) << load->name;
  }
}

TEST(Duct3dFloor, DerivativesOfTheDeflectedFloorMatchFiniteDifferences) {
  const DeflectedFloor floor(floor_surface(), kHot1);
  const double h = 1e-5;
  for (const double t : {3.1, 12.7, 18.0, 25.3, 33.3}) {
    for (const double s : {2.2, 7.9, 10.0, 15.1}) {
      const auto x = floor.evaluate(t, s);
      const Vec3 xt = (floor.evaluate(t + h, s).x - floor.evaluate(t - h, s).x) / (2 * h);
      const Vec3 xs = (floor.evaluate(t, s + h).x - floor.evaluate(t, s - h).x) / (2 * h);
      EXPECT_LT(distance(x.xt, xt), 1e-7) << t << ", " << s;
      EXPECT_LT(distance(x.xs, xs), 1e-7) << t << ", " << s;
    }
  }
}

TEST(Duct3dFloor, ClosestPointFindsTheParametersOfPointsOffTheDeflectedFloor) {
  const DeflectedFloor floor(floor_surface(), kHot1);
  for (const double t : {1.0, 14.0, 18.0, 26.5, 39.0}) {
    for (const double s : {0.0, 6.0, 10.0, 17.5}) {
      const auto x = floor.evaluate(t, s);
      const Vec3 n = cross(x.xt, x.xs) / norm(cross(x.xt, x.xs));
      const Closest c = floor.closest(x.x + 0.02 * kH * n);  // from (x, y) of the point
      EXPECT_NEAR(c.t, t, 1e-9 * kH);
      EXPECT_NEAR(c.s, s, 1e-9 * kH);
      EXPECT_NEAR(c.distance, 0.02 * kH, 1e-12 * kH);
    }
  }
}

mesh::Mesh moved_floor(const mesh::Mesh& m, const DeflectedFloor& floor, double slide = 0.0) {
  mesh::Mesh moved = m;
  for (const auto n : m.find_patch("floor")->nodes) {
    const Vec3& p = point(m, n);
    const double t = p.x > 0.0 && p.x + slide < kLength ? p.x + slide : p.x;
    moved.points[static_cast<std::size_t>(n)] = floor.evaluate(t, p.y).x;
  }
  return moved;
}

TEST(Duct3dWallDistance, TheUndeformedMeshIsOnTheUndeformedFloorToItsFaceting) {
  const DeflectedFloor cold(floor_surface(), kCold);
  const auto d = floor_distance(committed().mesh, cold);
  EXPECT_EQ(d.nodes, 49u * 17u);
  EXPECT_LT(d.node.distance, 1e-12 * kH);
  // The faces are chords of the curved floor: their distance is the faceting, which falls as
  // the square of the cell size.
  EXPECT_GT(d.hausdorff(), 1e-5 * kH);
  EXPECT_LT(d.hausdorff(), 2e-3 * kH);
  const auto fine = floor_distance(duct_mesh(floor_surface(), {.cells_x = 96, .cells_y = 32, .cells_z = 2}), cold);
  EXPECT_LT(fine.node.distance, 1e-12 * kH);
  EXPECT_NEAR(d.hausdorff() / fine.hausdorff(), 4.0, 1.0);
}

TEST(Duct3dWallDistance, AMeshRaisedByAKnownOffsetIsThatFarFromTheFloor) {
  const DeflectedFloor cold(floor_surface(), kCold);
  const auto& m = committed().mesh;
  const double offset = 0.02 * kH;
  mesh::Mesh raised = m;
  for (Vec3& p : raised.points) p.z += offset;
  const auto before = floor_distance(m, cold);
  const auto after = floor_distance(raised, cold);
  // Straight up is the normal where the floor is level (near its crests and troughs).
  EXPECT_LE(after.node.distance, offset * (1 + 1e-12));
  EXPECT_NEAR(after.node.distance, offset, 1e-3 * offset);
  EXPECT_NEAR(after.hausdorff(), offset, before.hausdorff() + 1e-3 * offset);
  EXPECT_GT(after.hausdorff(), 0.9 * offset);
}

TEST(Duct3dWallDistance, AFloorMovedByTheFieldLiesOnTheDeflectedFloorAtItsMaterialPoints) {
  const auto& m = committed().mesh;
  const DeflectedFloor hot(floor_surface(), kHot1), cold(floor_surface(), kCold);
  const auto moved = moved_floor(m, hot);
  const auto d = floor_distance(moved, hot, {}, &m);
  EXPECT_LT(d.node.distance, 1e-12 * kH);
  ASSERT_TRUE(d.material_point);
  EXPECT_LT(d.material_point->distance, 1e-12 * kH);
  EXPECT_LT(d.hausdorff(), 3e-3 * kH);  // the faceting of the bulged floor
  // Against the undeformed floor, the moved nodes are off by about the bulge.
  const auto off = floor_distance(moved, cold);
  EXPECT_NEAR(off.node.distance, kHot1.bulge, 0.02 * kHot1.bulge);
}

TEST(Duct3dWallDistance, NodesSlidOverTheDeflectedFloorStayOnItButLeaveTheirMaterialPoints) {
  const auto& m = committed().mesh;
  const DeflectedFloor hot(floor_surface(), kHot1);
  const double slide = 0.03 * kH;  // along t, every floor node but those at the inlet and outlet
  const auto slid = moved_floor(m, hot, slide);
  const auto d = floor_distance(slid, hot, {}, &m);
  EXPECT_LT(d.node.distance, 1e-12 * kH);
  ASSERT_TRUE(d.material_point);
  EXPECT_GT(d.material_point->distance, slide);  // |X(t + slide) - X(t)|: the floor's slope
  EXPECT_LT(d.material_point->distance, 1.3 * slide);
}

TEST(Duct3dWallDistance, RefusesAMissingPatchAndMismatchedMeshes) {
  const DeflectedFloor cold(floor_surface(), kCold);
  EXPECT_THROW(floor_distance(committed().mesh, cold, {.patch = "roof"}), std::invalid_argument);
  const auto small = duct_mesh(floor_surface(), {.cells_x = 4, .cells_y = 2, .cells_z = 2});
  EXPECT_THROW(floor_distance(committed().mesh, cold, {}, &small), std::invalid_argument);
}

TEST(Duct3dFloorSection, PointsLieOnThePlaneAndOnTheDeflectedFloorAcrossItsRange) {
  const DeflectedFloor hot(floor_surface(), kHot1);
  for (const auto& [axis, value] : {std::pair{0, 18.95}, std::pair{1, 10.625}, std::pair{1, 0.0}}) {
    const auto points = floor_section(hot, axis, value, 40);
    ASSERT_EQ(points.size(), 41u);
    for (const Vec3& p : points) {
      EXPECT_NEAR(axis == 0 ? p.x : p.y, value, 1e-12 * kH) << axis << " " << value;
      EXPECT_LT(hot.closest(p).distance, 1e-12 * kH) << axis << " " << value;
    }
    // From one wall to the other: the side planes (x = V) or the inlet and outlet (y = V).
    EXPECT_NEAR(axis == 0 ? points.front().y : points.front().x, 0.0, 1e-12 * kH);
    EXPECT_NEAR(axis == 0 ? points.back().y : points.back().x, axis == 0 ? kWidth : kLength, 1e-12 * kH);
  }
  EXPECT_THROW(floor_section(hot, 2, 1.0, 10), std::invalid_argument);
  EXPECT_THROW(floor_section(hot, 0, 1.0, 0), std::invalid_argument);
}

TEST(Duct3dNodesApart, IsTheLargestDistanceBetweenTheSameNodesOverAllAndOverTheFloor) {
  const auto& m = committed().mesh;
  const mesh::NodeId inside = 5000, on_floor = m.find_patch("floor")->nodes[40];
  mesh::Mesh moved = m;
  moved.points[static_cast<std::size_t>(inside)] += Vec3{0.0, 0.0, 0.3};
  moved.points[static_cast<std::size_t>(on_floor)] += Vec3{0.1, 0.0, 0.0};
  const auto apart = nodes_apart(moved, m);
  EXPECT_NEAR(apart.all.distance, 0.3, 1e-12);
  EXPECT_EQ(apart.all.node, m.node_id(inside));
  EXPECT_NEAR(apart.patch.distance, 0.1, 1e-12);
  EXPECT_EQ(apart.patch.node, m.node_id(on_floor));
  EXPECT_EQ(nodes_apart(m, m).all.distance, 0.0);
  EXPECT_THROW(nodes_apart(m, duct_mesh(floor_surface(), {.cells_x = 4, .cells_y = 2, .cells_z = 2})), std::invalid_argument);
}

TEST(Duct3dCases, NameTheFloorFaceTheTablesAndTheRoles) {
  for (const auto& [file, role] : {std::pair{"duct-prescribed.yaml", io::PatchRole::prescribed},
                                   std::pair{"duct-sliding.yaml", io::PatchRole::sliding}}) {
    const io::Case c = io::read_case(kSample / file);
    EXPECT_EQ(c.mesh, kSample / kMeshFile) << file;
    ASSERT_TRUE(c.cad) << file;
    EXPECT_EQ(*c.cad, kSample / kCadFile) << file;
    EXPECT_EQ(c.length_unit, geometry::LengthUnit::millimetre) << file;
    EXPECT_FALSE(c.axis) << file;  // the walls are not axisymmetric
    const auto* floor = c.find_patch("floor");
    ASSERT_TRUE(floor && floor->deflection) << file;
    EXPECT_EQ(floor->role, role) << file;
    EXPECT_EQ(floor->deflection->file, kSample / "floor.csv") << file;
    EXPECT_EQ(floor->deflection->faces, std::vector<int>{kFloorFace}) << file;
    EXPECT_EQ(floor->deflection->degree, 3) << file;
    EXPECT_EQ(c.find_patch("ceiling")->role, io::PatchRole::fixed) << file;
    for (const char* plane : {"side_right", "side_left", "inlet", "outlet"}) {
      EXPECT_EQ(c.find_patch(plane)->role, io::PatchRole::slip) << file << " " << plane;
    }
  }
  // The restart case reads the sliding run's restart.hmr, which exists only after that run.
  const std::string restart = test::read_text(kSample / "duct-restart.yaml");
  EXPECT_NE(restart.find("restart: duct-sliding-out/restart.hmr"), std::string::npos);
  EXPECT_NE(restart.find("{file: floor_hot2.csv, faces: [1], degree: 3}"), std::string::npos);
}

// Runs of the cases on a coarse duct: make_duct3d --cells 24,8,6 (1 152 cells, half the committed
// mesh's cells along each way; the same duct, CAD and tables) into a temporary folder, the committed case files copied beside it (they name duct.msh, here the
// coarse mesh). One test, so that the runs are made once: 10 s in the Release build on 2 cores
// shared with other jobs at a load average of 4, 31 s at a load of 7 (2026-11-27), most of it
// the three sliding runs.

/// hotmesh deform on `yaml` in `folder` (its outputs in <case>-out/ beside it).
test::CommandResult deform(const fs::path& folder, const std::string& yaml) {
  return test::run_command(std::string(HOTMESH_EXE) + " -q deform " + test::shell_quote((folder / yaml).string()));
}

nlohmann::json report_of(const fs::path& folder, const std::string& run) {
  return nlohmann::json::parse(test::read_text(folder / (run + "-out") / "report.json"));
}

mesh::Mesh deformed_of(const fs::path& folder, const std::string& run) {
  return io::read_gmsh(folder / (run + "-out") / "deformed.msh");
}

TEST(Duct3dRuns, PrescribedSlidingAndARestartOnACoarseDuctFollowTheExactFloor) {
  if (test::under_sanitizers()) GTEST_SKIP() << "four 3D runs: seconds in the Release build, minutes here; run there";
  const auto start = std::chrono::steady_clock::now();
  const test::TempDir dir;
  const fs::path folder = dir.path();
  const auto made = test::run_command(std::string(HOTMESH_MAKE_DUCT3D) + " --cells 24,8,6 " + test::shell_quote(folder.string()));
  ASSERT_EQ(made.exit_code, 0) << made.output;
  for (const char* yaml : {"duct-prescribed.yaml", "duct-sliding.yaml", "duct-restart.yaml"}) {
    fs::copy_file(kSample / yaml, folder / yaml);
  }
  // The restart's load straight from the cold mesh: the restart case without its restart line.
  const std::string restart = test::read_text(folder / "duct-restart.yaml");
  const std::string straight = std::regex_replace(restart, std::regex("\nrestart: [^\n]*"), "");
  ASSERT_NE(straight, restart);
  test::write_text(folder / "duct-hot2-straight.yaml", straight);

  // The restart reads duct-sliding-out/restart.hmr: sliding before it.
  for (const std::string run : {"duct-prescribed", "duct-sliding", "duct-restart", "duct-hot2-straight"}) {
    const auto r = deform(folder, run + ".yaml");
    ASSERT_EQ(r.exit_code, 0) << run << "\n" << r.output;
  }
  const mesh::Mesh cold = io::read_gmsh(folder / kMeshFile);
  ASSERT_EQ(cold.cell_count(), 24u * 8u * 6u);
  const DeflectedFloor hot1(floor_surface(), kHot1), hot2(floor_surface(), kHot2);
  // The coarse floor's faceting, the least a moved floor can be off its exact shape.
  const double faceting = floor_distance(cold, DeflectedFloor(floor_surface(), kCold)).hausdorff();

  // Each run's floor against its load's exact floor, with bounds about 1.5 times what was
  // measured (2026-11-27; over h: nodes, then the larger of mesh-to-floor and floor-to-mesh):
  // hot1 prescribed 1.18e-3, 9.5e-3; sliding 1.20e-3, 8.3e-3; hot2 restarted 3.94e-3, 1.64e-2;
  // straight 3.95e-3, 1.64e-2 (the cold floor's faceting: 4.9e-3). The nodes are off by what the
  // fitted field misses of the exact deflection (a least-squares cubic through the table's 230
  // scattered nodes; hot2's narrower hump is fitted less well); the faces by that and the
  // faceting of the bulged floor by the coarse quads.
  struct Run {
    std::string name;
    const DeflectedFloor* floor;
    double node_bound;       ///< over h
    double hausdorff_bound;  ///< over h
    nlohmann::json report;
    mesh::Mesh mesh;
    FloorDistance distance;
  };
  std::vector<Run> runs;
  for (auto [name, floor, node_bound, hausdorff_bound] :
       {std::tuple{"duct-prescribed", &hot1, 2e-3, 1.5e-2}, std::tuple{"duct-sliding", &hot1, 2e-3, 1.5e-2},
        std::tuple{"duct-restart", &hot2, 6e-3, 2.5e-2}, std::tuple{"duct-hot2-straight", &hot2, 6e-3, 2.5e-2}}) {
    Run run{name, floor, node_bound, hausdorff_bound, report_of(folder, name), deformed_of(folder, name), {}};
    run.distance = floor_distance(run.mesh, *floor, {}, &cold);
    runs.push_back(std::move(run));
  }
  for (const Run& run : runs) {
    SCOPED_TRACE(run.name);
    EXPECT_EQ(run.report["status"], "success");
    EXPECT_EQ(run.report["inverted_cells"], 0);
    // The mesh written, checked here rather than trusted from the report.
    const auto quality = mesh::summarize_quality(mesh::scaled_jacobians(run.mesh.cells, run.mesh.points));
    EXPECT_EQ(quality.inverted_cells, 0u);
    EXPECT_NEAR(quality.min_scaled_jacobian, run.report["quality"]["min_scaled_jacobian"].get<double>(), 1e-9);
    EXPECT_GT(quality.min_scaled_jacobian, 0.9);  // measured 0.93 to 0.98
    const auto& d = run.distance;
    std::printf("%s: min scaled Jacobian %.4f, floor nodes %.3g h, mesh to floor %.3g h, floor to mesh %.3g h, "
                "material points %.3g h (faceting of the cold floor %.3g h)\n",
                run.name.c_str(), quality.min_scaled_jacobian, d.node.distance / kH, d.mesh_to_floor.distance / kH,
                d.floor_to_mesh.distance / kH, d.material_point->distance / kH, faceting / kH);
    EXPECT_EQ(d.nodes, 25u * 9u);
    EXPECT_LT(d.node.distance, run.node_bound * kH);
    EXPECT_LT(d.mesh_to_floor.distance, run.hausdorff_bound * kH);
    EXPECT_LT(d.floor_to_mesh.distance, run.hausdorff_bound * kH);
    EXPECT_GT(d.hausdorff(), 0.5 * faceting);  // a curved floor: faceted, however good the nodes
  }
  const Run &prescribed = runs[0], &sliding = runs[1], &restarted = runs[2], &direct = runs[3];
  // A prescribed floor's nodes sit at their material points, up to the fit; sliding ones leave
  // them (by design: they go where the mesh needs them).
  EXPECT_LT(prescribed.distance.material_point->distance, prescribed.node_bound * kH);
  EXPECT_GT(sliding.distance.material_point->distance, 10 * prescribed.distance.material_point->distance);
  EXPECT_GT(sliding.report["sliding_nodes"].get<int>(), 100);
  EXPECT_EQ(prescribed.report["sliding_nodes"], 0);
  // Sliding is not worse than prescribed.
  EXPECT_GE(sliding.report["min_scaled_jacobian"].get<double>(), prescribed.report["min_scaled_jacobian"].get<double>() - 0.01);

  // Restart continuity: hot1 then hot2 ends near hot2 run straight from the cold mesh. Both
  // floors are on the hot2 floor; the meshes differ by where the sliding nodes ended (the
  // restarted run's kept the slides of the first run, and its stiffness is the hot1 mesh's)
  // and so the interior: the motion follows the path. Measured 0.015 h apart (0.0145 h at the
  // floor nodes, the nodes above them about as much), the second load moving the mesh by
  // 0.135 h; the bound is 3 times the measured value.
  EXPECT_THAT(restarted.report["restarted_from"].get<std::string>(), ::testing::HasSubstr("duct-sliding-out/restart.hmr"));
  const auto apart = nodes_apart(restarted.mesh, direct.mesh);
  const double moved = nodes_apart(restarted.mesh, sliding.mesh).all.distance;
  std::printf("restart: %.3g h from the straight run of hot2 (floor nodes %.3g h), moved %.3g h from the sliding run of hot1\n",
              apart.all.distance / kH, apart.patch.distance / kH, moved / kH);
  EXPECT_GT(moved, 0.1 * kH);  // the second load moved the mesh on
  EXPECT_LT(apart.all.distance, 0.045 * kH);
  std::printf("coarse duct runs: %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace
}  // namespace hotmesh::samples::duct3d
