// The corners of sliding walls held by mesh nodes (wall_features.hpp and the corner pass of
// move_mesh): a wall that an FEM table folds into a trapezoidal bump, whose four corners lie
// between mesh nodes, in 2D and on a surface of revolution (a 10-degree sector about z).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"

namespace hotmesh::deform {
namespace {

using geometry::BSplineCurve2d;
using geometry::DeflectedCurve;
using geometry::DeflectionForm;
using geometry::Vec2;

constexpr double kBump = 0.2;  ///< height of the bump
/// The corners' parameters (t = r - 1, or x - 1): feet at 0.3 and 0.7, shoulders at 0.35 and 0.65.
const std::vector<double> kCorners{0.3, 0.35, 0.65, 0.7};

/// The wall from (1, 0) to (2, 0) in its plane, deflected by a trapezoidal bump of kBump.
DeflectedCurve bump_wall() {
  const std::vector<double> ends{0.0, 1.0};
  const std::vector<Vec2> wall{{1.0, 0.0}, {2.0, 0.0}};
  const std::vector<double> t{0.0, 0.3, 0.35, 0.65, 0.7, 1.0};
  const std::vector<Vec2> d{{0, 0}, {0, 0}, {0, kBump}, {0, kBump}, {0, 0}, {0, 0}};
  return {BSplineCurve2d::polyline(ends, wall), BSplineCurve2d::polyline(t, d), DeflectionForm::displacement};
}

/// Where the deflected wall is at parameter t, in its plane.
Vec2 exact(double t) { return bump_wall().point(t, 1.0); }

/// 12 cells along the wall (none of the corners on a node; feet and shoulders in neighbouring
/// cells), 10 across, growing from 0.03 at the wall.
std::vector<double> along() { return mesh::uniform_line(1.0, 2.0, 12); }
std::vector<double> across() { return mesh::stretched_line(0.0, 1.0, 10, 0.03); }

std::vector<PatchMotion> motions(std::shared_ptr<const geometry::BoundaryShape> wall, bool features,
                                 std::vector<std::string> slips) {
  std::vector<PatchMotion> m{{"left", BoundaryRole::fixed, nullptr},
                             {"right", BoundaryRole::fixed, nullptr},
                             {"top", BoundaryRole::fixed, nullptr},
                             {"bottom", BoundaryRole::sliding, std::move(wall)}};
  m.back().features.enabled = features;
  for (auto& s : slips) m.push_back({s, BoundaryRole::slip, nullptr});
  return m;
}

/// Largest distance of a corner from the wall's nodes in (its plane's) coordinates `plane`.
template <class Plane>
double largest_corner_gap(const mesh::Mesh& mesh, const MotionResult& r, Plane plane) {
  double largest = 0.0;
  for (const double t : kCorners) {
    const Vec2 c = exact(t);
    double nearest = 1e300;
    for (mesh::NodeId n : mesh.find_patch("bottom")->nodes) {
      nearest = std::min(nearest, norm(plane(r.points[static_cast<std::size_t>(n)]) - c));
    }
    largest = std::max(largest, nearest);
  }
  return largest;
}

TEST(WallCorners, EveryCornerOfAPlanarWallGetsANodeOnIt) {
  const mesh::Mesh mesh = mesh::structured_quads(along(), across(), {"left", "right", "bottom", "top"});
  const auto wall = std::make_shared<geometry::PlanarCurveShape>(bump_wall());
  const auto xy = [](const Vec3& p) { return Vec2{p.x, p.y}; };

  const MotionResult free = move_mesh(mesh, motions(wall, false, {}), {}, {});
  ASSERT_TRUE(free.success) << free.message;
  EXPECT_TRUE(free.features.empty());
  EXPECT_GT(largest_corner_gap(mesh, free, xy), 0.01);  // the paper's sliding cuts corners

  const MotionResult held = move_mesh(mesh, motions(wall, true, {}), {}, {});
  ASSERT_TRUE(held.success) << held.message;
  EXPECT_EQ(held.summary.inverted_cells, 0u);
  ASSERT_EQ(held.features.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const WallFeature& f = held.features[k];
    EXPECT_DOUBLE_EQ(f.parameter, kCorners[k]);
    EXPECT_EQ(f.given_nodes, 1u);
    EXPECT_EQ(f.unheld_edges, 0u);
    EXPECT_LT(f.distance, 1e-12);
    EXPECT_NEAR(f.point.x, exact(f.parameter).x, 1e-12);
    EXPECT_NEAR(f.point.y, exact(f.parameter).y, 1e-12);
  }
  EXPECT_LT(largest_corner_gap(mesh, held, xy), 1e-12);
  // Four nodes, four corners: no node holds two.
  std::vector<mesh::NodeId> holders;
  for (const WallFeature& f : held.features) holders.push_back(f.nodes.front());
  std::sort(holders.begin(), holders.end());
  EXPECT_EQ(std::unique(holders.begin(), holders.end()), holders.end());
  // The corner pass follows the motion's increments, and a restart would continue from the
  // mesh before it: the motion's own.
  EXPECT_TRUE(held.increments.back().corner_pass);
  EXPECT_FALSE(held.increments.front().corner_pass);
  ASSERT_EQ(held.restart_points.size(), mesh.node_count());
  double same = 0.0;
  for (std::size_t n = 0; n < mesh.node_count(); ++n) same = std::max(same, distance(held.restart_points[n], free.points[n]));
  EXPECT_EQ(same, 0.0);
  // Every wall node lies on the deflected wall, none beyond a corner it may not cross: the
  // wall's nodes stay in order along it.
  const auto& bottom = mesh.find_patch("bottom")->nodes;
  std::vector<double> xs;
  for (mesh::NodeId n : bottom) xs.push_back(held.points[static_cast<std::size_t>(n)].x);
  std::vector<double> sorted = xs;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
}

TEST(WallCorners, TwoCornersWithinOneCellAreReportedNotSquashed) {
  // 4 cells along the wall: the feet and shoulders of the bump pair up inside single cells.
  const mesh::Mesh mesh =
      mesh::structured_quads(mesh::uniform_line(1.0, 2.0, 4), across(), {"left", "right", "bottom", "top"});
  const auto wall = std::make_shared<geometry::PlanarCurveShape>(bump_wall());
  const MotionResult r = move_mesh(mesh, motions(wall, true, {}), {}, {});
  ASSERT_TRUE(r.success) << r.message;
  ASSERT_EQ(r.features.size(), 4u);
  std::size_t unheld = 0;
  for (const WallFeature& f : r.features) unheld += f.unheld_edges;
  EXPECT_GT(unheld, 0u);
  bool noted = false;
  for (const std::string& note : r.notes) noted = noted || note.find("two corners within one cell") != std::string::npos;
  EXPECT_TRUE(noted);
}

/// The wall's 10-degree sector about z, 3 cells in theta, sides side0/side1 (slip planes in
/// the tests); the wall's inner rows of nodes turned by `turn` of a cell in theta.
constexpr double kSector = 10.0 * std::numbers::pi / 180.0;
mesh::Mesh sector_mesh(double turn) {
  mesh::Mesh mesh = mesh::structured_hexes(along(), mesh::uniform_line(0.0, kSector, 3), across(),
                                           {"left", "right", "side0", "side1", "bottom", "top"});
  for (Vec3& p : mesh.points) {
    const bool inner_wall_row = p.z == 0.0 && p.y > 0.1 * kSector && p.y < 0.9 * kSector;
    const double theta = p.y + (inner_wall_row ? turn * kSector / 3.0 : 0.0);
    p = {p.x * std::cos(theta), p.x * std::sin(theta), p.z};
  }
  return mesh;
}

TEST(WallCorners, OnASurfaceOfRevolutionEveryMeridionalRowHoldsEachCornerCircle) {
  // The same wall as the meridional curve (r, z) of a 10-degree sector about z, 3 cells in
  // theta; its sides are slip planes, whose wall nodes hold the corners too (the corner circle
  // crosses them in their own meridional planes).
  const mesh::Mesh mesh = sector_mesh(0.0);
  const geometry::Axis axis({0, 0, 0}, {0, 0, 1});
  const auto wall = std::make_shared<geometry::RevolvedShape>(bump_wall(), axis);
  const auto rz = [&](const Vec3& p) {
    const auto c = axis.to_cylindrical(p);
    return Vec2{c.r, c.z};
  };
  const MotionResult r = move_mesh(mesh, motions(wall, true, {"side0", "side1"}), {}, {});
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.summary.inverted_cells, 0u);
  ASSERT_EQ(r.features.size(), 4u);
  for (const WallFeature& f : r.features) {
    EXPECT_EQ(f.given_nodes, 4u) << f.parameter;  // one per row of nodes in theta
    EXPECT_EQ(f.unheld_edges, 0u);
    EXPECT_LT(f.distance, 1e-12);
    std::vector<double> thetas;
    for (mesh::NodeId n : f.nodes) thetas.push_back(axis.to_cylindrical(r.points[static_cast<std::size_t>(n)]).theta);
    std::sort(thetas.begin(), thetas.end());
    EXPECT_NEAR(thetas.front(), 0.0, 1e-12);
    EXPECT_NEAR(thetas.back(), kSector, 1e-12);
  }
  EXPECT_LT(largest_corner_gap(mesh, r, rz), 1e-12);
}

TEST(WallCorners, OnATriangulatedSurfaceOfRevolutionEveryCornerCircleIsHeld) {
  // The sector above as prisms (the wall's faces triangles, the slip sides quads) and as
  // tetrahedra (every face a triangle): the wall's edges now run along diagonals too.
  const geometry::Axis axis({0, 0, 0}, {0, 0, 1});
  const auto wall = std::make_shared<geometry::RevolvedShape>(bump_wall(), axis);
  const auto rz = [&](const Vec3& p) {
    const auto c = axis.to_cylindrical(p);
    return Vec2{c.r, c.z};
  };
  const mesh::Mesh hexes = sector_mesh(0.0);
  for (const mesh::CellSplit how : {mesh::CellSplit::prisms, mesh::CellSplit::tetrahedra}) {
    SCOPED_TRACE(how == mesh::CellSplit::prisms ? "prisms" : "tetrahedra");
    const mesh::Mesh mesh = mesh::split_cells(hexes, std::vector<mesh::CellSplit>(hexes.cell_count(), how));
    const MotionResult r = move_mesh(mesh, motions(wall, true, {"side0", "side1"}), {}, {});
    ASSERT_TRUE(r.success) << r.message;
    EXPECT_EQ(r.summary.inverted_cells, 0u);
    ASSERT_EQ(r.features.size(), 4u);
    for (const WallFeature& f : r.features) {
      EXPECT_GE(f.given_nodes, 4u) << f.parameter;  // at least one per row of nodes in theta
      EXPECT_EQ(f.unheld_edges, 0u);
      EXPECT_LT(f.distance, 1e-12);
    }
    EXPECT_LT(largest_corner_gap(mesh, r, rz), 1e-12);
  }
}

TEST(WallCorners, OnASurfaceOfRevolutionTheHoldingNodesSlideAlongTheCornerCircle) {
  // The sector above with the wall's inner rows of nodes turned by a quarter cell in theta, so
  // that the mesh pulls wall nodes round the axis. Nodes given a corner circle end on it, and
  // are free along it: in the corner pass they move in theta too (a node prescribed onto the
  // corner would keep the theta it had).
  const mesh::Mesh mesh = sector_mesh(0.25);
  const geometry::Axis axis({0, 0, 0}, {0, 0, 1});
  const auto wall = std::make_shared<geometry::RevolvedShape>(bump_wall(), axis);
  const MotionResult r = move_mesh(mesh, motions(wall, true, {"side0", "side1"}), {}, {});
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.summary.inverted_cells, 0u);
  ASSERT_EQ(r.restart_points.size(), r.points.size()) << "the corner pass ran";
  double turned = 0.0;
  for (const WallFeature& f : r.features) {
    EXPECT_LT(f.distance, 1e-12);
    for (mesh::NodeId n : f.nodes) {
      const auto i = static_cast<std::size_t>(n);
      const double before = axis.to_cylindrical(r.restart_points[i]).theta;
      const double after = axis.to_cylindrical(r.points[i]).theta;
      turned = std::max(turned, std::abs(after - before));
      const auto c = axis.to_cylindrical(r.points[i]);
      EXPECT_LT(norm(Vec2{c.r, c.z} - exact(f.parameter)), 1e-12);
    }
  }
  EXPECT_GT(turned, 1e-7) << "the nodes holding the corner circles did not move along them";
}

/// A wall drawn with a step of height kStep whose four corners lie on rows of nodes, as a mesh
/// made from CAD has them: (r, z) through (1, 0), (1 + 4/12, 0), (1 + 5/12, kStep),
/// (1 + 7/12, kStep), (1 + 8/12, 0), (2, 0), the mesh's nodes at r = 1 + i/12. The deflection
/// moves it out and up, more at larger r, so every corner circle moves and turns.
constexpr double kStep = 0.1;
const std::vector<Vec2> kStepWall{{1.0, 0.0}, {1.0 + 4.0 / 12, 0.0}, {1.0 + 5.0 / 12, kStep},
                                  {1.0 + 7.0 / 12, kStep}, {1.0 + 8.0 / 12, 0.0}, {2.0, 0.0}};

DeflectedCurve step_wall() {
  std::vector<double> t{0.0};
  for (std::size_t k = 1; k < kStepWall.size(); ++k) t.push_back(t.back() + norm(kStepWall[k] - kStepWall[k - 1]));
  for (double& v : t) v /= t.back();
  const std::vector<double> ends{0.0, 1.0};
  const std::vector<Vec2> d{{0.0, 0.0}, {0.05, 0.08}};
  return {BSplineCurve2d::polyline(t, kStepWall), BSplineCurve2d::polyline(ends, d), DeflectionForm::displacement};
}

/// The 10-degree sector with its wall on step_wall(): each node's z lifted by the step's height
/// at its r, fading to nothing at the top.
mesh::Mesh stepped_sector_mesh() {
  mesh::Mesh mesh = sector_mesh(0.0);
  const geometry::Axis axis({0, 0, 0}, {0, 0, 1});
  for (Vec3& p : mesh.points) {
    const double r = std::hypot(p.x, p.y);
    double lift = 0.0;
    for (std::size_t k = 0; k + 1 < kStepWall.size(); ++k) {
      const Vec2 a = kStepWall[k], b = kStepWall[k + 1];
      if (r >= a.x - 1e-12 && r <= b.x + 1e-12) lift = a.y + (b.y - a.y) * (r - a.x) / (b.x - a.x);
    }
    p.z += (1.0 - p.z) * lift;
  }
  return mesh;
}

TEST(WallCorners, OnASurfaceOfRevolutionTheRowsOfNodesOnCornerCirclesHoldThemFromTheStart) {
  // A wall whose meridional curve has corners on rows of nodes before the motion: those nodes
  // cannot slide (the wall has no tangent there, Newton would alternate between the sides); they
  // follow their corner circle through the motion, free round the axis, with or without features.
  const mesh::Mesh mesh = stepped_sector_mesh();
  const geometry::Axis axis({0, 0, 0}, {0, 0, 1});
  const auto wall = std::make_shared<geometry::RevolvedShape>(step_wall(), axis);
  for (const bool features : {true, false}) {
    SCOPED_TRACE(features ? "features" : "features off");
    const MotionResult r = move_mesh(mesh, motions(wall, features, {"side0", "side1"}), {}, {});
    ASSERT_TRUE(r.success) << r.message;
    EXPECT_EQ(r.summary.inverted_cells, 0u);
    ASSERT_EQ(r.features.size(), 4u);
    for (const WallFeature& f : r.features) {
      EXPECT_TRUE(f.from_start);
      EXPECT_EQ(f.given_nodes, 4u) << f.parameter;  // the row of nodes on it, one per meridional plane
      EXPECT_LT(f.distance, 1e-12);
      EXPECT_LT(f.largest_offset, 1e-12);
    }
    // The wall's nodes end on it (but those of the fixed ends) and none slid across a corner.
    for (mesh::NodeId n : mesh.find_patch("bottom")->nodes) {
      const auto i = static_cast<std::size_t>(n);
      if (r.node_roles[i] == 1 + static_cast<int>(BoundaryRole::fixed)) continue;
      const auto before = axis.to_cylindrical(mesh.points[i]), after = axis.to_cylindrical(r.points[i]);
      const double t = wall->project(mesh.points[i], 0.0).parameter.t;
      const double moved = wall->project(r.points[i], 1.0).parameter.t;
      EXPECT_LT(wall->project(r.points[i], 1.0).distance, 1e-9);
      for (const WallFeature& f : r.features) {
        EXPECT_EQ(t < f.parameter - 1e-9, moved < f.parameter - 1e-9) << "node " << n << " at r " << before.r << " -> " << after.r;
      }
    }
  }
}

TEST(WallCorners, OnAPeriodicSectorTheCornerCirclesAreHeldAcrossItsBorderWithoutANote) {
  // The sector with periodic sides instead of slip planes: the slave side's wall nodes follow
  // their masters, which hold the corner circles where they cross the side, so no wall edge is
  // left cutting a corner and no note says one is.
  const mesh::Mesh mesh = sector_mesh(0.0);
  const geometry::Axis axis({0, 0, 0}, {0, 0, 1});
  const auto wall = std::make_shared<geometry::RevolvedShape>(bump_wall(), axis);
  std::vector<PatchMotion> m = motions(wall, true, {});
  m.push_back({"side0", BoundaryRole::periodic, nullptr, "side1", kSector, axis});
  m.push_back({"side1", BoundaryRole::periodic, nullptr});
  const MotionResult r = move_mesh(mesh, m, {}, {});
  ASSERT_TRUE(r.success) << r.message;
  ASSERT_EQ(r.features.size(), 4u);
  for (const WallFeature& f : r.features) {
    EXPECT_EQ(f.unheld_edges, 0u) << f.parameter;
    EXPECT_LT(f.distance, 1e-12);
  }
  for (const std::string& note : r.notes) EXPECT_EQ(note.find("has no node on"), std::string::npos) << note;
  const auto rz = [&](const Vec3& p) {
    const auto c = axis.to_cylindrical(p);
    return Vec2{c.r, c.z};
  };
  EXPECT_LT(largest_corner_gap(mesh, r, rz), 1e-12);
  EXPECT_LT(r.max_periodic_mismatch, 1e-12);
}

TEST(WallCorners, TheCornerPassRunsWithTheAmgSolverToo) {
  // The sector's corner circles with the assembled solver (nodal frames for the nodes that
  // slide along a circle): the same corners held as with jacobi-pcg.
  const mesh::Mesh mesh = sector_mesh(0.0);
  const geometry::Axis axis({0, 0, 0}, {0, 0, 1});
  const auto wall = std::make_shared<geometry::RevolvedShape>(bump_wall(), axis);
  SolverOptions amg;
  amg.linear = LinearSolverKind::amg;
  const MotionResult r = move_mesh(mesh, motions(wall, true, {"side0", "side1"}), {}, amg);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.summary.inverted_cells, 0u);
  ASSERT_EQ(r.features.size(), 4u);
  for (const WallFeature& f : r.features) {
    EXPECT_EQ(f.given_nodes, 4u);
    EXPECT_LT(f.distance, 1e-12);
  }
}

}  // namespace
}  // namespace hotmesh::deform
