// Tests of hotmesh::setup::deflected_walls, the walls of a case at a stage of its motion for
// ParaView: in 2D each wall is its curve at the stage, corners included; in 3D a surface of
// revolution whose points lie on the meridional curve and cover the angle of the wall's patch
// (also across theta = pi).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "../geometry/curve_fixtures.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/setup/deflected_walls.hpp"

namespace hotmesh::setup {
namespace {

using geometry::Axis;
using io::PolyData;
using geometry::BSplineCurve2d;
using geometry::DeflectedCurve;
using geometry::Vec2;
using geometry::Vec3;

constexpr double kDegree = std::numbers::pi / 180.0;

/// A mesh of `points` with one patch "wall" made of all of them (no cells: the walls need
/// only the patch's nodes).
mesh::Mesh wall_nodes(std::vector<Vec3> points, int dimension) {
  mesh::Mesh m;
  m.dimension = dimension;
  m.points = std::move(points);
  mesh::Patch wall{"wall", 1, {}, {}};
  for (std::size_t i = 0; i < m.points.size(); ++i) wall.nodes.push_back(static_cast<mesh::NodeId>(i));
  m.patches.push_back(std::move(wall));
  return m;
}

TEST(DeflectedWalls, PlanarWallIsItsCurveAtTheStageThroughItsCorner) {
  // A wall along y = 0 whose deflection (displacement form, degree 1) lifts x >= 1 by 0.5:
  // at stage lambda its corner (1, 0) stays and the far end is at (2, 0.5 lambda).
  const BSplineCurve2d r(1, {0, 0, 2, 2}, {{0, 0}, {2, 0}});
  const BSplineCurve2d d(1, {0, 0, 1, 2, 2}, {{0, 0}, {0, 0}, {0, 0.5}});
  deform::PatchMotion wall{"wall", deform::BoundaryRole::sliding,
                           std::make_shared<geometry::PlanarCurveShape>(DeflectedCurve(r, d, geometry::DeflectionForm::displacement))};
  const mesh::Mesh m = wall_nodes({{0, 0, 0.25}, {2, 0, 0.25}}, 2);
  const PolyData walls = deflected_walls(m, std::span(&wall, 1), 0.5);
  ASSERT_EQ(walls.lines.size(), 1u);
  EXPECT_TRUE(walls.polygons.empty());
  bool corner = false;
  for (const Vec3& p : walls.points) {
    EXPECT_EQ(p.z, 0.25);  // in the plane of the patch
    const double y = p.x <= 1.0 ? 0.0 : 0.5 * 0.5 * (p.x - 1.0);
    EXPECT_NEAR(p.y, y, 1e-14) << p.x;
    corner = corner || (p.x == 1.0 && p.y == 0.0);
  }
  EXPECT_TRUE(corner) << "the corner is drawn as a corner";
  EXPECT_EQ(walls.points.back().x, 2.0);
  EXPECT_NEAR(walls.points.back().y, 0.25, 1e-15);
  ASSERT_EQ(walls.cell_data.size(), 1u);
  EXPECT_EQ(std::get<std::vector<std::int32_t>>(walls.cell_data[0].values), std::vector<std::int32_t>{1});
}

TEST(DeflectedWalls, RevolvedWallLiesOnItsMeridionalCurveOverThePatchAngleAcrossPi) {
  // A quarter circle of radius 2 in (r, z) about the z axis: a sphere's zone.
  const Axis axis({0, 0, 0}, {0, 0, 1});
  deform::PatchMotion wall{"wall", deform::BoundaryRole::sliding,
                           std::make_shared<geometry::RevolvedShape>(DeflectedCurve(geometry::test::quarter_circle(2.0)), axis)};
  // The patch covers 170 to 190 degrees, through theta = pi.
  const mesh::Mesh m = wall_nodes({axis.to_cartesian({2, 170 * kDegree, 0}), axis.to_cartesian({2, -170 * kDegree, 0}),
                                   axis.to_cartesian({1, 175 * kDegree, 1})},
                                  3);
  const PolyData walls = deflected_walls(m, std::span(&wall, 1), 1.0);
  EXPECT_TRUE(walls.lines.empty());
  ASSERT_FALSE(walls.polygons.empty());
  for (const Vec3& p : walls.points) {
    const geometry::Cylindrical c = axis.to_cylindrical(p);
    EXPECT_NEAR(c.r * c.r + c.z * c.z, 4.0, 1e-12);
    if (c.r < 1e-9) continue;  // the pole, at no angle
    const double theta = c.theta < 0.0 ? c.theta + 2.0 * std::numbers::pi : c.theta;
    EXPECT_GE(theta, 170 * kDegree - 1e-12);
    EXPECT_LE(theta, 190 * kDegree + 1e-12);
  }
  const auto& patch = std::get<std::vector<std::int32_t>>(walls.cell_data[0].values);
  EXPECT_EQ(patch.size(), walls.polygons.size());
  for (const auto& quad : walls.polygons) EXPECT_EQ(quad.size(), 4u);
}

TEST(DeflectedWalls, PatchesWithoutShapeAreLeftOut) {
  const deform::PatchMotion fixed{"wall", deform::BoundaryRole::fixed, nullptr};
  const PolyData walls = deflected_walls(wall_nodes({{0, 0, 0}}, 2), std::span(&fixed, 1), 1.0);
  EXPECT_TRUE(walls.points.empty());
  EXPECT_TRUE(walls.lines.empty());
}

}  // namespace
}  // namespace hotmesh::setup
