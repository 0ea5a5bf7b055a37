// Tests of passive surfaces (section 6.1) and rotational periodicity: a passive face follows
// its rim by the spring analogy; periodic faces of an annular sector match after the motion,
// an axisymmetric motion with periodic faces equals the same motion with the faces slipping,
// a twisting motion keeps them matched, and faces that do not match are named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "test_shapes.hpp"
#include "test_support.hpp"

namespace hotmesh::deform {
namespace {

using ::testing::HasSubstr;

constexpr double kSector = 10.0;  // degrees

std::vector<PatchMotion> sector_motions(std::shared_ptr<geometry::BoundaryShape> inner, BoundaryRole sides) {
  std::vector<PatchMotion> m{{"inner", BoundaryRole::prescribed, std::move(inner)},
                             {"outer", BoundaryRole::fixed},
                             {"bottom", BoundaryRole::fixed},
                             {"top", BoundaryRole::slip},
                             {"per_lo", sides},
                             {"per_hi", sides}};
  if (sides == BoundaryRole::periodic) {
    m[4].partner = "per_hi";
    m[4].angle = kSector * std::numbers::pi / 180.0;
  }
  return m;
}

TEST(Periodic, AxisymmetricMotionWithPeriodicFacesEqualsSlipFaces) {
  const Mesh mesh = test::annular_sector(6, 4, 6, 1.0, 2.0, 0.0, 1.0, kSector);
  SolverOptions tight;
  tight.increments = 4;
  tight.newton_tolerance = 1e-9;
  tight.pcg_tolerance = 1e-10;
  const auto shape = test::deflected_cylinder(1.0, 0.3, 0.0, 10);
  const MotionResult periodic = move_mesh(mesh, sector_motions(shape, BoundaryRole::periodic), {}, tight);
  const MotionResult slip = move_mesh(mesh, sector_motions(shape, BoundaryRole::slip), {}, tight);
  ASSERT_TRUE(periodic.success) << periodic.message;
  ASSERT_TRUE(slip.success) << slip.message;
  EXPECT_EQ(periodic.periodic_pairs, 7u * 7u);
  EXPECT_LT(periodic.max_periodic_mismatch / periodic.length_scale, 1e-12);
  double largest = 0.0;
  for (std::size_t n = 0; n < mesh.node_count(); ++n) largest = std::max(largest, distance(periodic.points[n], slip.points[n]));
  EXPECT_LT(largest, 1e-7);
}

TEST(Periodic, TwistingMotionKeepsThePeriodicFacesMatched) {
  // The inner wall turns about the axis by 2 degrees: the sector's faces must turn with it,
  // which slip faces could not do.
  const Mesh mesh = test::annular_sector(6, 4, 4, 1.0, 2.0, 0.0, 1.0, kSector);
  auto twist = std::make_shared<test::AffineShape>(
      std::array<Vec3, 3>{{{std::cos(0.035) - 1.0, -std::sin(0.035), 0}, {std::sin(0.035), std::cos(0.035) - 1.0, 0}, {0, 0, 0}}},
      Vec3{});
  const MotionResult r = move_mesh(mesh, sector_motions(twist, BoundaryRole::periodic), {}, {});
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_LT(r.max_periodic_mismatch / r.length_scale, 1e-9);
  // The faces really moved: a node in the middle of per_lo turned.
  double turned = 0.0;
  for (NodeId n : mesh.find_patch("per_lo")->nodes) {
    const Vec3 a = mesh.points[static_cast<std::size_t>(n)], b = r.points[static_cast<std::size_t>(n)];
    turned = std::max(turned, std::abs(std::atan2(b.y, b.x) - std::atan2(a.y, a.x)));
  }
  EXPECT_GT(turned, 0.005);
}

TEST(Periodic, FacesThatDoNotMatchAreNamed) {
  const Mesh mesh = test::annular_sector(3, 2, 2, 1.0, 2.0, 0.0, 1.0, kSector);
  auto motions = sector_motions(test::deflected_cylinder(1.0, 0.1, 0.0, 10), BoundaryRole::periodic);
  motions[4].angle = -motions[4].angle;  // the wrong way round
  try {
    move_mesh(mesh, motions, {}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("periodic patches 'per_lo' and 'per_hi' do not match by a rotation of -10 degrees"));
    EXPECT_THAT(e.what(), HasSubstr("12 nodes of 'per_lo' have no partner"));
  }
}

TEST(Passive, FaceFollowsItsRimBySprings) {
  // A cube whose top moves up by 0.2; its side xmin is passive: with a uniform grid the spring
  // analogy interpolates the rim linearly, so the face's nodes rise by 0.2 z.
  const Mesh mesh = test::unit_cube(4);
  auto up = std::make_shared<test::AffineShape>(std::array<Vec3, 3>{}, Vec3{0, 0, 0.2});
  const std::vector<PatchMotion> motions{{"xmin", BoundaryRole::passive}, {"xmax", BoundaryRole::slip},
                                         {"ymin", BoundaryRole::slip},    {"ymax", BoundaryRole::slip},
                                         {"zmin", BoundaryRole::fixed},   {"zmax", BoundaryRole::prescribed, up}};
  const MotionResult r = move_mesh(mesh, motions, {}, {});
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.passive_nodes, 3u * 5u);  // its nodes off the top and bottom rows
  for (NodeId n : mesh.find_patch("xmin")->nodes) {
    const Vec3 a = mesh.points[static_cast<std::size_t>(n)], b = r.points[static_cast<std::size_t>(n)];
    EXPECT_NEAR(b.z - a.z, 0.2 * a.z, 1e-12);
    EXPECT_NEAR(b.x, a.x, 1e-12);
    EXPECT_NEAR(b.y, a.y, 1e-12);
  }
}

TEST(Passive, SurfaceAcrossPeriodicFacesMovesAxisymmetrically) {
  // The top of an annular sector is passive and its sides periodic: its inner rim rises with
  // the inner wall, its outer rim stays. The spring analogy on the surface is rotationally
  // symmetric, so all of the top's nodes at one radius rise alike, those on the periodic edges
  // too: the rim node of a slave edge is known through its master (the stator well's inlet and
  // outlet, samples/stator_well, are such surfaces).
  const Mesh mesh = test::annular_sector(6, 4, 4, 1.0, 2.0, 0.0, 1.0, kSector);
  auto motions = sector_motions(test::deflected_cylinder(1.0, 0.0, 0.2, 10), BoundaryRole::periodic);
  motions[3].role = BoundaryRole::passive;  // top
  const MotionResult r = move_mesh(mesh, motions, {}, {});
  ASSERT_TRUE(r.success) << r.message;
  std::map<long, std::vector<double>> rise_at_radius;  // radius in 1e-6, rise of each node
  for (NodeId n : mesh.find_patch("top")->nodes) {
    const Vec3 a = mesh.points[static_cast<std::size_t>(n)], b = r.points[static_cast<std::size_t>(n)];
    rise_at_radius[std::lround(std::hypot(a.x, a.y) * 1e6)].push_back(b.z - a.z);
  }
  ASSERT_EQ(rise_at_radius.size(), 7u);
  for (const auto& [radius, rises] : rise_at_radius) {
    ASSERT_EQ(rises.size(), 5u);  // theta 0 (per_lo) to 10 degrees (per_hi)
    for (double rise : rises) EXPECT_NEAR(rise, rises[2], 1e-12) << "radius " << static_cast<double>(radius) * 1e-6;
  }
  EXPECT_NEAR(rise_at_radius.begin()->second[0], 0.2, 1e-12);   // inner rim
  EXPECT_NEAR(rise_at_radius.rbegin()->second[0], 0.0, 1e-12);  // outer rim
  EXPECT_GT(std::next(rise_at_radius.begin())->second[0], 0.1);  // the first ring inside follows
}

TEST(Passive, SurfaceWithoutRimIsRefused) {
  // The passive wall meets only slip walls: nothing drives it.
  const Mesh mesh = test::unit_square(3, 3);
  const std::vector<PatchMotion> motions{{"xmin", BoundaryRole::fixed},
                                         {"xmax", BoundaryRole::passive},
                                         {"ymin", BoundaryRole::slip},
                                         {"ymax", BoundaryRole::slip}};
  try {
    move_mesh(mesh, motions, {}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("passive patch 'xmax': part of it (node 4 and its neighbours) touches no fixed, prescribed or sliding wall"));
  }
}

}  // namespace
}  // namespace hotmesh::deform
