// The corners of a deflected curve (DeflectedCurve::corners, BoundaryShape::features) and
// projections kept to a segment between corners (CurveProjector::project with a range): a flat
// wall that a degree-1 FEM deflection folds into a ramp, whose corners A and B are known.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/curve_projector.hpp"

namespace hotmesh::geometry {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// The wall y = 0, x in [0, 2] (parameter x / 2), deflected by dy = 0 before x = 0.9, 0.5
/// after x = 1.1, linear between: corners A (0.9, 0) and B (1.1, 0.5), each turning by
/// atan(0.5 / 0.2) = 68.2 degrees. `kink` adds a small bend of the table at x = 0.5.
DeflectedCurve ramp(double kink = 0.0) {
  const std::vector<double> ends{0.0, 1.0};
  const std::vector<Vec2> wall{{0.0, 0.0}, {2.0, 0.0}};
  std::vector<double> t;
  std::vector<Vec2> d;
  for (const double x : {0.0, 0.5, 0.9, 1.1, 2.0}) {
    t.push_back(x / 2.0);
    d.push_back({0.0, x <= 0.9 ? (x == 0.5 ? kink : 0.0) : x >= 1.1 ? 0.5 : 0.5 * (x - 0.9) / 0.2});
  }
  return {BSplineCurve2d::polyline(ends, wall), BSplineCurve2d::polyline(t, d), DeflectionForm::displacement};
}

TEST(CurveCorners, FindsTheFoldsOfTheDeflectedWallAndTheirAngles) {
  const auto corners = ramp().corners(25.0 * kDegree);
  ASSERT_EQ(corners.size(), 2u);
  EXPECT_DOUBLE_EQ(corners[0].parameter, 0.45);
  EXPECT_DOUBLE_EQ(corners[1].parameter, 0.55);
  const double fold = std::atan2(0.5, 0.2);
  EXPECT_NEAR(corners[0].angle, fold, 1e-12);
  EXPECT_NEAR(corners[1].angle, fold, 1e-12);
}

TEST(CurveCorners, BendsBelowTheAngleAreNotCorners) {
  // The kink at x = 0.5 turns by atan(0.02 / 0.5) + atan(0.02 / 0.4) = 5.2 degrees.
  EXPECT_EQ(ramp(0.02).corners(25.0 * kDegree).size(), 2u);
  EXPECT_EQ(ramp(0.02).corners(5.0 * kDegree).size(), 3u);
  EXPECT_TRUE(ramp().corners(70.0 * kDegree).empty());
  EXPECT_TRUE(DeflectedCurve(BSplineCurve2d::polyline(std::vector<double>{0.0, 1.0},
                                                      std::vector<Vec2>{{0.0, 0.0}, {1.0, 0.0}}))
                  .corners(1.0 * kDegree)
                  .empty());
}

TEST(CurveCorners, AShapeReportsTheCornersOfItsCurve) {
  const PlanarCurveShape shape(ramp());
  const auto features = shape.features(25.0 * kDegree);
  ASSERT_EQ(features.size(), 2u);
  EXPECT_DOUBLE_EQ(features[1].parameter, 0.55);
  EXPECT_TRUE(PlaneShape({0, 0, 0}, {0, 1, 0}).features(1.0 * kDegree).empty());
}

TEST(CurveCorners, AProjectionKeptToASegmentDoesNotCrossItsCorner) {
  const CurveProjector projector(ramp());
  // Just above the flat before A, near the ramp's foot: the whole curve's closest point is on
  // the ramp; kept to the segment before A it is on the flat, or A itself.
  const Vec2 p{0.95, 0.2};
  const CurveProjection free = projector.project(p, 1.0);
  EXPECT_GT(free.parameter, 0.45);
  const ParameterRange before_a{-1.0, 0.45};
  const CurveProjection kept = projector.project(p, 1.0, kNoCurveHint, before_a);
  EXPECT_LE(kept.parameter, 0.45);
  EXPECT_NEAR(kept.point.x, 0.9, 1e-12);  // the flat's closest point to p is its end, A
  EXPECT_NEAR(kept.point.y, 0.0, 1e-12);
  // A warm start on the ramp is clamped into the segment too.
  const CurveProjection warm = projector.project(p, 1.0, 0.5, before_a);
  EXPECT_LE(warm.parameter, 0.45);
  EXPECT_NEAR(warm.distance, kept.distance, 1e-12);
  // Inside its segment a point projects as it would on the whole curve.
  const Vec2 q{0.4, 0.1};
  EXPECT_NEAR(projector.project(q, 1.0, kNoCurveHint, before_a).parameter, projector.project(q, 1.0).parameter, 1e-14);
  // On the ramp's own segment, the point before A goes to the ramp.
  const CurveProjection on_ramp = projector.project(p, 1.0, kNoCurveHint, {0.45, 0.55});
  EXPECT_NEAR(on_ramp.parameter, free.parameter, 1e-12);
}

}  // namespace
}  // namespace hotmesh::geometry
