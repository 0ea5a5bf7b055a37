// Tests of passive surfaces whose rim slides (section 6.1 with the sliding walls of section
// 4): the node an inlet shares with a sliding wall ends on the deflected wall and on the
// inlet's surface, the inlet's other nodes are the spring solution for the rim where it ended,
// and the mesh stays valid; in 2D (a channel with a tilted, shifted floor and passive ends) and
// in 3D (the top of an annular sector, an inlet meeting a sliding disc face that bulges and
// rises through it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "constraints/passive.hpp"
#include "constraints/periodic.hpp"
#include "test_shapes.hpp"
#include "test_support.hpp"

namespace hotmesh::deform {
namespace {

/// Largest distance between the nodes of `patch` where the run left them and where the spring
/// analogy puts them for the rim where the run left it: the surface follows its rim's final
/// positions, not the positions the rim was sent to.
double passive_mismatch(const Mesh& mesh, const MotionResult& r, const std::string& patch,
                        const detail::PeriodicCoupling& periodic = detail::PeriodicCoupling(3)) {
  const Patch& surface = *mesh.find_patch(patch);
  std::vector<char> rim(mesh.node_count(), 0);
  const auto code = [](BoundaryRole role) { return static_cast<NodeRoleCode>(1 + static_cast<int>(role)); };
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    const NodeRoleCode role = r.node_roles[n];
    rim[n] = role == code(BoundaryRole::fixed) || role == code(BoundaryRole::prescribed) ||
             role == code(BoundaryRole::sliding);
  }
  const detail::RimDisplacement moved = [&](NodeId n) -> std::optional<Vec3> {
    const auto i = static_cast<std::size_t>(n);
    if (!rim[i]) return std::nullopt;
    return r.points[i] - mesh.points[i];
  };
  const auto displacement = detail::PassiveSurface(mesh, mesh.points, surface, moved, periodic).solve(moved);
  double worst = 0.0;
  for (std::size_t k = 0; k < surface.nodes.size(); ++k) {
    const auto i = static_cast<std::size_t>(surface.nodes[k]);
    worst = std::max(worst, distance(r.points[i], mesh.points[i] + displacement[k]));
  }
  return worst;
}

// ---- 2D: a channel whose floor slides and whose inlet and outlet are passive ----

/// The floor y = 0 (its CAD line runs past both ends of the channel) deflected by
/// (0.1, 0.1 + 0.05 x): shifted downstream, raised and tilted. The deflected floor is the line
/// y = 0.095 + 0.05 x.
std::shared_ptr<test::TestCurveShape> shifted_floor() {
  return std::make_shared<test::TestCurveShape>(
      std::vector<Vec3>{{-1, 0, 0}, {3, 0, 0}},
      [](const Vec3& p, double lambda) { return p + lambda * Vec3{0.1, 0.1 + 0.05 * p.x, 0.0}; });
}
double deflected_floor(double x) { return 0.095 + 0.05 * x; }

Mesh channel() {
  return mesh::structured_quads(mesh::uniform_line(0.0, 2.0, 21), mesh::uniform_line(0.0, 1.0, 11), {"inlet", "outlet", "floor", "ceiling"});
}

std::vector<PatchMotion> channel_motions(BoundaryRole ceiling) {
  auto still = std::make_shared<test::TestCurveShape>(std::vector<Vec3>{{-1, 1, 0}, {3, 1, 0}},
                                                      [](const Vec3& p, double) { return p; });
  return {{"inlet", BoundaryRole::passive},
          {"outlet", BoundaryRole::passive},
          {"floor", BoundaryRole::sliding, shifted_floor()},
          {"ceiling", ceiling, ceiling == BoundaryRole::sliding ? still : nullptr}};
}

void expect_channel_ends_on_floor_and_inlet(const Mesh& mesh, const MotionResult& r) {
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_GT(r.summary.min_scaled_jacobian, 0.5);
  EXPECT_EQ(r.summary.inverted_cells, 0u);
  // The corners the floor shares with the inlet (node 0) and the outlet (node 21) end where
  // the deflected floor crosses the planes x = 0 and x = 2: on both surfaces.
  const Vec3 inlet_corner = r.points[0], outlet_corner = r.points[21];
  EXPECT_NEAR(inlet_corner.x, 0.0, 1e-12);
  EXPECT_NEAR(inlet_corner.y, deflected_floor(0.0), 1e-9);
  EXPECT_NEAR(outlet_corner.x, 2.0, 1e-12);
  EXPECT_NEAR(outlet_corner.y, deflected_floor(2.0), 1e-9);
  // Every floor node on the deflected floor; the inlet and outlet still straight and where
  // they were, their nodes the spring solution for the corners where these ended.
  for (NodeId n : mesh.find_patch("floor")->nodes) {
    const Vec3& p = r.points[static_cast<std::size_t>(n)];
    EXPECT_NEAR(p.y, deflected_floor(p.x), 1e-9) << "floor node " << n;
  }
  for (NodeId n : mesh.find_patch("inlet")->nodes) EXPECT_NEAR(r.points[static_cast<std::size_t>(n)].x, 0.0, 1e-12);
  for (NodeId n : mesh.find_patch("outlet")->nodes) EXPECT_NEAR(r.points[static_cast<std::size_t>(n)].x, 2.0, 1e-12);
  EXPECT_LT(passive_mismatch(mesh, r, "inlet"), 1e-12);
  EXPECT_LT(passive_mismatch(mesh, r, "outlet"), 1e-12);
}

TEST(PassiveSliding, InletCornerEndsOnTheDeflectedFloorAndOnTheInlet) {
  const Mesh mesh = channel();
  SolverOptions options;
  options.increments = 4;
  const MotionResult r = move_mesh(mesh, channel_motions(BoundaryRole::fixed), {}, options);
  expect_channel_ends_on_floor_and_inlet(mesh, r);
  // The inlet's nodes between its corners are spaced as the spring analogy spaces them: evenly.
  const Patch& inlet = *mesh.find_patch("inlet");
  for (std::size_t k = 0; k < inlet.nodes.size(); ++k) {
    const double y0 = mesh.points[static_cast<std::size_t>(inlet.nodes[k])].y;
    EXPECT_NEAR(r.points[static_cast<std::size_t>(inlet.nodes[k])].y, deflected_floor(0.0) * (1.0 - y0) + y0, 1e-12);
  }
}

TEST(PassiveSliding, ChannelBetweenSlidingWallsWithPassiveEndsNeedsNoFixedPatch) {
  // Nothing is fixed: the corners, held on the floor or ceiling and on the inlet or outlet,
  // hold the mesh in place.
  const Mesh mesh = channel();
  const MotionResult r = move_mesh(mesh, channel_motions(BoundaryRole::sliding), {}, {});
  expect_channel_ends_on_floor_and_inlet(mesh, r);
  for (NodeId n : mesh.find_patch("ceiling")->nodes) EXPECT_NEAR(r.points[static_cast<std::size_t>(n)].y, 1.0, 1e-9);
}

// ---- 3D: an inlet meeting a sliding disc face ----

constexpr double kSector = 10.0;  // degrees

/// An annular sector: the disc face (inner) slides over its deflected shape, the casing
/// (outer) and the floor are fixed, the sides periodic, and the top z = 1 is the passive inlet.
std::vector<PatchMotion> disc_sector(std::shared_ptr<geometry::BoundaryShape> face) {
  std::vector<PatchMotion> motions{{"inner", BoundaryRole::sliding, std::move(face)}, {"outer", BoundaryRole::fixed},
                                   {"bottom", BoundaryRole::fixed},                  {"top", BoundaryRole::passive},
                                   {"per_lo", BoundaryRole::periodic},               {"per_hi", BoundaryRole::periodic}};
  motions[4].partner = "per_hi";
  motions[4].angle = kSector * std::numbers::pi / 180.0;
  return motions;
}

TEST(PassiveSliding, InletOnASlidingDiscFaceStaysPlanarAndMeetsTheDeflectedFace) {
  // The face's material point at the inlet rises to z = 1.1; the face's nodes slide down it to
  // where it crosses the inlet, and the inlet stays in its plane.
  const Mesh mesh = test::annular_sector(6, 4, 8, 1.0, 2.0, 0.0, 1.0, kSector);
  const auto face = test::deflected_cylinder(1.0, 0.15, 0.1, 20);
  const double angle = kSector * std::numbers::pi / 180.0;
  SolverOptions options;
  options.increments = 4;
  const MotionResult r = move_mesh(mesh, disc_sector(face), {}, options);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.summary.inverted_cells, 0u);
  EXPECT_GT(r.summary.min_scaled_jacobian, 0.3);
  EXPECT_LT(r.max_periodic_mismatch, 1e-12);

  // Where the deflected face crosses z = 1: its material point z' with z' (1 + rise) = 1.
  const double crossing_z = 1.0 / 1.1, crossing_r = 1.0 + 4.0 * 0.15 * crossing_z * (1.0 - crossing_z);
  const Patch& inner = *mesh.find_patch("inner");
  std::size_t shared = 0;
  for (NodeId n : mesh.find_patch("top")->nodes) {
    const auto i = static_cast<std::size_t>(n);
    EXPECT_NEAR(r.points[i].z, 1.0, 1e-9) << "inlet node " << n;  // on the inlet's plane
    if (!std::binary_search(inner.nodes.begin(), inner.nodes.end(), n)) continue;
    ++shared;  // on the deflected face too
    EXPECT_LT(face->project(r.points[i], 1.0, geometry::kNoHint).distance, 1e-9) << "rim node " << n;
    EXPECT_NEAR(std::hypot(r.points[i].x, r.points[i].y), crossing_r, 2e-3) << "rim node " << n;
  }
  EXPECT_EQ(shared, 5u);
  for (NodeId n : inner.nodes) {
    EXPECT_LT(face->project(r.points[static_cast<std::size_t>(n)], 1.0, geometry::kNoHint).distance, 1e-9);
  }
  detail::PeriodicCoupling periodic(3);
  periodic.add(mesh, *mesh.find_patch("per_lo"), *mesh.find_patch("per_hi"), geometry::Axis(), angle, 1e-9);
  EXPECT_LT(passive_mismatch(mesh, r, "top", periodic), 1e-12);
}

TEST(PassiveSliding, ResumingMakesTheSameMovesAsTheInletFollowsItsRim) {
  // The surface is solved from where its rim stands, which a checkpoint holds: a resumed run
  // moves it as the uninterrupted run does, to the bit.
  const Mesh mesh = test::annular_sector(4, 2, 6, 1.0, 2.0, 0.0, 1.0, kSector);
  const auto motions = disc_sector(test::deflected_cylinder(1.0, 0.15, 0.1, 20));
  SolverOptions options;
  options.increments = 3;
  std::vector<MotionCheckpoint> checkpoints;
  MotionObservers observers;
  observers.checkpoint = [&checkpoints](const MotionCheckpoint& c) { checkpoints.push_back(c); };
  const MotionResult straight = move_mesh(mesh, motions, {}, options, observers);
  ASSERT_TRUE(straight.success) << straight.message;
  ASSERT_EQ(checkpoints.size(), 3u);
  for (const MotionCheckpoint& c : {checkpoints[0], checkpoints[1]}) {
    const MotionResult resumed = move_mesh(mesh, motions, {}, options, {}, nullptr, &c);
    ASSERT_TRUE(resumed.success) << resumed.message;
    ASSERT_EQ(resumed.points.size(), straight.points.size());
    EXPECT_EQ(std::memcmp(resumed.points.data(), straight.points.data(), straight.points.size() * sizeof(Vec3)), 0)
        << "resumed after increment " << c.finished_increments;
  }
}

}  // namespace
}  // namespace hotmesh::deform
