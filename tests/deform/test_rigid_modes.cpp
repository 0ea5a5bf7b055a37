// Tests of the check that the boundary conditions remove every rigid-body motion: a channel
// between sliding walls with slip ends needs no fixed patch and both linear solvers converge
// on it; roles that leave a translation or a rotation free are refused naming the motion (a
// sector between coaxial sliding cylinders with periodic sides turns about its axis); the
// axis of a free rotation is where the constraints put it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "constraints/rigid_modes.hpp"
#include "test_shapes.hpp"
#include "test_support.hpp"

namespace hotmesh::deform {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// ---- a 2D channel: the floor rises by a ramp and slides, the ceiling slides ----

std::shared_ptr<test::TestCurveShape> ramp_floor() {
  return std::make_shared<test::TestCurveShape>(
      std::vector<Vec3>{{0, 0, 0}, {0.9, 0, 0}, {1.1, 0, 0}, {2, 0, 0}}, [](const Vec3& p, double lambda) {
        return p + Vec3{0.0, lambda * (p.x <= 0.9 ? 0.0 : p.x >= 1.1 ? 0.2 : 0.2 * (p.x - 0.9) / 0.2), 0.0};
      });
}

Mesh channel() {
  return mesh::structured_quads(mesh::uniform_line(0.0, 2.0, 21), mesh::uniform_line(0.0, 1.0, 12), {"inlet", "outlet", "floor", "ceiling"});
}

std::vector<PatchMotion> sliding_channel() {
  auto still = std::make_shared<test::TestCurveShape>(std::vector<Vec3>{{0, 1, 0}, {2, 1, 0}},
                                                      [](const Vec3& p, double) { return p; });
  return {{"inlet", BoundaryRole::slip},
          {"outlet", BoundaryRole::slip},
          {"floor", BoundaryRole::sliding, ramp_floor()},
          {"ceiling", BoundaryRole::sliding, still}};
}

MotionResult run_channel(LinearSolverKind linear) {
  SolverOptions options;
  options.increments = 2;
  options.newton_tolerance = 1e-8;
  options.pcg_tolerance = 1e-8;
  options.max_pcg_iterations = 5000;
  options.linear = linear;
  return move_mesh(channel(), sliding_channel(), {}, options);
}

TEST(RigidModes, SlidingChannelWithSlipEndsNeedsNoFixedPatch) {
  // Slip inlet and outlet stop the translation along the channel, the walls the translation
  // across it, both the rotation: every rigid motion is removed, and the stiffness on the free
  // degrees of freedom is positive definite. Both linear solvers converge on it, to one mesh.
  const Mesh mesh = channel();
  const MotionResult pcg = run_channel(LinearSolverKind::jacobi_pcg);
  const MotionResult amg = run_channel(LinearSolverKind::amg);
  for (const MotionResult* r : {&pcg, &amg}) {
    ASSERT_TRUE(r->success) << r->message;
    EXPECT_GT(r->summary.min_scaled_jacobian, 0.5);
    for (const IncrementRecord& increment : r->increments) {
      EXPECT_TRUE(increment.accepted);
      EXPECT_EQ(increment.split_depth, 0);
      for (std::size_t k = 0; k + 1 < increment.newton.size(); ++k) {
        EXPECT_TRUE(increment.newton[k].pcg_converged) << "increment " << increment.increment << ", step " << k;
      }
    }
    for (NodeId n : mesh.find_patch("floor")->nodes) {
      EXPECT_LT(ramp_floor()->project(r->points[static_cast<std::size_t>(n)], 1.0, geometry::kNoHint).distance, 1e-9);
    }
    for (NodeId n : mesh.find_patch("inlet")->nodes) EXPECT_NEAR(r->points[static_cast<std::size_t>(n)].x, 0.0, 1e-12);
    for (NodeId n : mesh.find_patch("outlet")->nodes) EXPECT_NEAR(r->points[static_cast<std::size_t>(n)].x, 2.0, 1e-12);
  }
  double largest = 0.0;
  for (std::size_t n = 0; n < mesh.node_count(); ++n) largest = std::max(largest, distance(pcg.points[n], amg.points[n]));
  EXPECT_LT(largest, 1e-6);
}

std::string refusal(const Mesh& mesh, const std::vector<PatchMotion>& motions) {
  try {
    move_mesh(mesh, motions, {}, {});
  } catch (const FreeRigidMotion& e) {
    return e.what();
  }
  return "(not refused)";
}

TEST(RigidModes, ChannelThatCanTranslateAlongItselfIsRefused) {
  // Without the inlet and outlet (a mesh whose ends belong to no patch), nothing stops the
  // channel from moving along its walls.
  Mesh mesh = channel();
  std::erase_if(mesh.patches, [](const Patch& p) { return p.name == "inlet" || p.name == "outlet"; });
  auto motions = sliding_channel();
  motions.erase(motions.begin(), motions.begin() + 2);
  const std::string message = refusal(mesh, motions);
  EXPECT_THAT(message, HasSubstr("the patch roles leave the mesh free to move as a rigid body: it can translate along x."));
  EXPECT_THAT(message, Not(HasSubstr("rotate")));
}

TEST(RigidModes, SquareWithSlipWallsOnlyIsHeld) {
  // Slip walls all round: no wall may move off its plane, which stops every rigid motion.
  const Mesh mesh = test::unit_square(3, 3);
  std::vector<PatchMotion> motions;
  for (const Patch& p : mesh.patches) motions.push_back({p.name, BoundaryRole::slip});
  const MotionResult r = move_mesh(mesh, motions, {}, {});
  ASSERT_TRUE(r.success) << r.message;
  for (std::size_t n = 0; n < mesh.node_count(); ++n) EXPECT_EQ(r.points[n], mesh.points[n]);
}

// ---- 3D: a sector between coaxial cylinders ----

constexpr double kSector = 10.0;  // degrees

std::vector<PatchMotion> coaxial_sector(BoundaryRole sides) {
  std::vector<PatchMotion> m{{"inner", BoundaryRole::sliding, test::deflected_cylinder(1.0, 0.1, 0.0, 8)},
                             {"outer", BoundaryRole::sliding, test::deflected_cylinder(2.0, 0.0, 0.0, 8)},
                             {"bottom", BoundaryRole::slip},
                             {"top", BoundaryRole::slip},
                             {"per_lo", sides},
                             {"per_hi", sides}};
  if (sides == BoundaryRole::periodic) {
    m[4].partner = "per_hi";
    m[4].angle = kSector * std::numbers::pi / 180.0;
  }
  return m;
}

TEST(RigidModes, PeriodicSectorBetweenCoaxialCylindersTurningAboutItsAxisIsRefused) {
  // Sliding cylinders and slip ends hold the sector radially and axially, the periodic sides
  // turn with it: it can still turn about the axis.
  const Mesh mesh = test::annular_sector(3, 2, 2, 1.0, 2.0, 0.0, 1.0, kSector);
  const std::string message = refusal(mesh, coaxial_sector(BoundaryRole::periodic));
  EXPECT_THAT(message, HasSubstr("it can rotate about the axis through (0, 0, 0.5) along (0, 0, 1)."));
  EXPECT_THAT(message, Not(HasSubstr("translate")));
}

TEST(RigidModes, SectorBetweenCoaxialCylindersWithSlipSidesIsHeld) {
  // Slip sides (planes through the axis) stop the rotation.
  const Mesh mesh = test::annular_sector(3, 2, 4, 1.0, 2.0, 0.0, 1.0, kSector);
  const MotionResult r = move_mesh(mesh, coaxial_sector(BoundaryRole::slip), {}, {});
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.summary.inverted_cells, 0u);
}

// ---- the check itself ----

TEST(RigidModes, OneFixedNodeLeavesTheRotationAboutIt) {
  const Mesh mesh = test::unit_square(2, 2);
  detail::RigidModes modes(mesh);
  modes.fix({0.5, 1.0, 0.0});
  EXPECT_EQ(modes.free_motions(), std::vector<std::string>{"rotate about the point (0.5, 1)"});
  modes.constrain({0.0, 0.0, 0.0}, {-1.0, 1.0, 0.0});  // crosses that rotation
  EXPECT_TRUE(modes.free_motions().empty());
}

TEST(RigidModes, RadialNormalsLeaveTheTurnAboutTheirAxisAndTheShiftAlongIt) {
  // Nodes held along normals towards the line through (1, 2, *) along z: the mesh can turn
  // about that line and slide along it, nothing else.
  const Mesh mesh = test::unit_cube(2);
  detail::RigidModes modes(mesh);
  const Vec3 axis{1.0, 2.0, 0.0};
  for (int k = 0; k < 12; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 12.0;
    const Vec3 x = axis + Vec3{std::cos(t), std::sin(t), 0.1 * k};
    modes.constrain(x, x - Vec3{axis.x, axis.y, x.z});
  }
  EXPECT_EQ(modes.free_motions(),
            (std::vector<std::string>{"translate along z", "rotate about the axis through (1, 2, 0.5) along (0, 0, 1)"}));
}

// A run with nothing to move starts at a residual rounding leaves (the curved walls' normals
// are not exact): it must end at once, not fail for want of a relative reduction of noise.
TEST(RigidModes, SectorWithNothingToMoveEndsAtTheUndeformedMesh) {
  const Mesh mesh = test::annular_sector(3, 2, 4, 1.0, 2.0, 0.0, 1.0, kSector);
  std::vector<PatchMotion> motions = coaxial_sector(BoundaryRole::slip);
  motions[0].shape = test::deflected_cylinder(1.0, 0.0, 0.0, 8);
  const MotionResult r = move_mesh(mesh, motions, {}, {});
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.increments.size(), 16u);  // no increment split
  for (std::size_t n = 0; n < mesh.node_count(); ++n) EXPECT_LT(distance(r.points[n], mesh.points[n]), 1e-12);
}

}  // namespace
}  // namespace hotmesh::deform
