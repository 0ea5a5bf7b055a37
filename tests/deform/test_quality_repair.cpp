// Tests of the repair after the corner pass (deform/src/motion/quality_repair.hpp): cells below a
// floor are raised by moving their interior nodes, boundary nodes never move, and no move
// lowers the worst cell; in 2D and 3D.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "motion/quality_repair.hpp"

namespace hotmesh::deform::detail {
namespace {

/// 1 for nodes on no patch (interior), 0 for the others.
std::vector<char> interior_nodes(const Mesh& mesh) {
  std::vector<char> interior(mesh.node_count(), 1);
  for (const mesh::Patch& p : mesh.patches) {
    for (const NodeId n : p.nodes) interior[static_cast<std::size_t>(n)] = 0;
  }
  return interior;
}

double worst(const Mesh& mesh, std::span<const Vec3> points) {
  const auto q = mesh::scaled_jacobians(mesh.cells, points);
  return *std::min_element(q.begin(), q.end());
}

/// The node nearest p.
std::size_t node_at(const Mesh& mesh, const Vec3& p) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < mesh.node_count(); ++i) {
    if (distance(mesh.points[i], p) < distance(mesh.points[best], p)) best = i;
  }
  return best;
}

TEST(QualityRepair, AnInteriorNodePulledAsideGoesBackAndTheBoundaryStays) {
  Mesh mesh = mesh::structured_quads(mesh::uniform_line(0.0, 1.0, 4), mesh::uniform_line(0.0, 1.0, 4),
                                     {"left", "right", "bottom", "top"});
  std::vector<Vec3> points = mesh.points;
  points[node_at(mesh, {0.5, 0.5, 0.0})] += Vec3{0.17, 0.11, 0.0};
  const double before = worst(mesh, points);
  ASSERT_LT(before, 0.7);
  const std::vector<char> interior = interior_nodes(mesh);
  const QualityRepair r = repair_cells_below(mesh, points, interior, 0.95, 50);
  EXPECT_EQ(r.cells_below, 4u);
  EXPECT_GE(r.nodes_moved, 1u);
  EXPECT_DOUBLE_EQ(r.min_before, before);
  EXPECT_GE(r.min_after, 0.95);
  EXPECT_DOUBLE_EQ(r.min_after, worst(mesh, points));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!interior[i]) {
      EXPECT_EQ(points[i], mesh.points[i]) << "boundary node " << i << " moved";
    }
  }
}

TEST(QualityRepair, ABoundaryNodeOutOfPlaceStaysAndNoCellEndsBelowTheWorst) {
  // A wall node pushed into the mesh: the angle the wall makes there is split between its two
  // cells as evenly as it already is, so nothing can raise the worst cell without moving the
  // wall node; it stays, and nothing ends below the worst cell.
  Mesh mesh = mesh::structured_quads(mesh::uniform_line(0.0, 1.0, 6), mesh::uniform_line(0.0, 1.0, 6),
                                     {"left", "right", "bottom", "top"});
  std::vector<Vec3> points = mesh.points;
  const std::size_t wall = node_at(mesh, {0.5, 0.0, 0.0});
  points[wall] += Vec3{0.0, 0.15, 0.0};
  const Vec3 pushed = points[wall];
  const double before = worst(mesh, points);
  const QualityRepair r = repair_cells_below(mesh, points, interior_nodes(mesh), 0.99, 50);
  EXPECT_EQ(points[wall], pushed);
  EXPECT_GE(r.min_after, before);
  EXPECT_LT(r.min_after, 0.99);
}

TEST(QualityRepair, InThreeDimensionsATwistedInteriorNodeIsRepaired) {
  Mesh mesh = mesh::structured_hexes(mesh::uniform_line(0.0, 1.0, 3), mesh::uniform_line(0.0, 1.0, 3),
                                     mesh::uniform_line(0.0, 1.0, 3),
                                     {"x0", "x1", "y0", "y1", "z0", "z1"});
  std::vector<Vec3> points = mesh.points;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = mesh.points[i];
    const bool inside = p.x > 0.1 && p.x < 0.9 && p.y > 0.1 && p.y < 0.9 && p.z > 0.1 && p.z < 0.9;
    if (inside) points[i] += Vec3{0.1, -0.08, 0.12};
  }
  const double before = worst(mesh, points);
  ASSERT_LT(before, 0.8);
  const QualityRepair r = repair_cells_below(mesh, points, interior_nodes(mesh), 0.9, 50);
  EXPECT_GE(r.min_after, 0.9);
  EXPECT_GT(r.nodes_moved, 0u);
}

TEST(QualityRepair, NothingBelowTheFloorMovesNothing) {
  Mesh mesh = mesh::structured_quads(mesh::uniform_line(0.0, 1.0, 3), mesh::uniform_line(0.0, 1.0, 3),
                                     {"left", "right", "bottom", "top"});
  std::vector<Vec3> points = mesh.points;
  const QualityRepair r = repair_cells_below(mesh, points, interior_nodes(mesh), 0.5, 50);
  EXPECT_EQ(r.cells_below, 0u);
  EXPECT_EQ(r.nodes_moved, 0u);
  EXPECT_EQ(points, mesh.points);
}

}  // namespace
}  // namespace hotmesh::deform::detail
