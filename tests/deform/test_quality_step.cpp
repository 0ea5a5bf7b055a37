// Tests of the quality step (deform/src/motion/quality_step.hpp): nodes around faces a flow
// solver finds non-orthogonal and skewed are moved to lower them, boundary nodes stay, a node
// of a slip line moves along it only, and no cell is moved below the scaled-Jacobian floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/solver_quality.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "motion/quality_step.hpp"

namespace hotmesh::deform::detail {
namespace {

double worst_jacobian(const Mesh& mesh, std::span<const Vec3> points) {
  const auto q = mesh::scaled_jacobians(mesh.cells, points);
  return *std::min_element(q.begin(), q.end());
}

/// A graded 12 x 10 quad block whose interior is sheared by a bump: the boundary as drawn, the
/// mesh lines inside leaning up to 35 degrees.
struct ShearedBlock {
  Mesh mesh = mesh::structured_quads(mesh::geometric_line(0.0, 3.0, 12, 1.1), mesh::geometric_line(0.0, 2.0, 10, 1.15),
                                     {"left", "right", "bottom", "top"});
  std::vector<Vec3> points = mesh.points;
  std::vector<char> on_boundary = std::vector<char>(mesh.node_count(), 0);
  ShearedBlock() {
    for (const mesh::Patch& p : mesh.patches) {
      for (const NodeId n : p.nodes) on_boundary[static_cast<std::size_t>(n)] = 1;
    }
    for (std::size_t n = 0; n < points.size(); ++n) {
      if (on_boundary[n]) continue;
      const Vec3& p = mesh.points[n];
      points[n].x += 0.6 * std::sin(std::numbers::pi * p.x / 3.0) * std::sin(std::numbers::pi * p.y / 2.0);
    }
  }
  std::vector<MovableNode> interior() const {
    std::vector<MovableNode> movable;
    for (std::size_t n = 0; n < points.size(); ++n) {
      if (!on_boundary[n]) movable.push_back({static_cast<NodeId>(n), {Vec3{1, 0, 0}, Vec3{0, 1, 0}}, 2});
    }
    return movable;
  }
};

TEST(QualityStep, ShearedInteriorIsMadeOrthogonalAgainAndTheBoundaryStays) {
  ShearedBlock block;
  const mesh::SolverFaces faces(block.mesh, block.points);
  const auto before = mesh::solver_quality(block.mesh, block.points).summary;
  const double floor = worst_jacobian(block.mesh, block.points);
  ASSERT_GT(before.max_non_orthogonality.value, 25.0);
  const std::vector<MovableNode> movable = block.interior();
  const QualityStepResult r = improve_for_solver(block.mesh, faces, block.points, movable, floor);
  const auto after = mesh::solver_quality(block.mesh, block.points).summary;
  EXPECT_GT(r.nodes_moved, 0u);
  EXPECT_LT(r.worst_after, r.worst_before);
  // The undeformed block is orthogonal: the step takes back most of the shear.
  EXPECT_LT(after.max_non_orthogonality.value, 0.5 * before.max_non_orthogonality.value);
  EXPECT_LT(after.max_skewness.value, before.max_skewness.value);
  EXPECT_GE(worst_jacobian(block.mesh, block.points), floor);
  for (std::size_t n = 0; n < block.points.size(); ++n) {
    if (block.on_boundary[n]) {
      EXPECT_EQ(block.points[n], block.mesh.points[n]) << "boundary node " << n << " moved";
    }
  }
}

TEST(QualityStep, ASlipNodeMovesAlongItsLineOnly) {
  ShearedBlock block;
  // The bottom's nodes between the corners slip along y = 0, pulled aside to shear the cells above.
  std::vector<MovableNode> movable = block.interior();
  const mesh::Patch& bottom = *block.mesh.find_patch("bottom");
  std::vector<std::size_t> slipping;
  for (const NodeId n : bottom.nodes) {
    const auto i = static_cast<std::size_t>(n);
    const Vec3& p = block.mesh.points[i];
    if (p.x <= 0.0 || p.x >= 3.0) continue;
    block.points[i].x += 0.15 * std::sin(std::numbers::pi * p.x / 3.0);
    movable.push_back({n, {Vec3{1, 0, 0}}, 1});
    slipping.push_back(i);
  }
  const std::vector<Vec3> start = block.points;
  const mesh::SolverFaces faces(block.mesh, block.points);
  const double floor = worst_jacobian(block.mesh, block.points);
  improve_for_solver(block.mesh, faces, block.points, movable, floor);
  bool slid = false;
  for (const std::size_t i : slipping) {
    EXPECT_EQ(block.points[i].y, 0.0) << "slip node " << i << " left its line";
    slid = slid || block.points[i].x != start[i].x;
  }
  EXPECT_TRUE(slid);
  EXPECT_GE(worst_jacobian(block.mesh, block.points), floor);
}

TEST(QualityStep, NoCellIsMovedBelowTheFloor) {
  ShearedBlock block;
  const mesh::SolverFaces faces(block.mesh, block.points);
  // A floor above the worst cell: no cell may end below min(its node's worst before, floor).
  const auto q_before = mesh::scaled_jacobians(block.mesh.cells, block.points);
  const double floor = 0.9;
  improve_for_solver(block.mesh, faces, block.points, block.interior(), floor);
  const auto q_after = mesh::scaled_jacobians(block.mesh.cells, block.points);
  const double worst_before = *std::min_element(q_before.begin(), q_before.end());
  EXPECT_GE(*std::min_element(q_after.begin(), q_after.end()), std::min(worst_before, floor));
}

}  // namespace
}  // namespace hotmesh::deform::detail
