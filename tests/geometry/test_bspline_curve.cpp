// Tests of BSplineCurve2d: de Boor evaluation of points and derivatives (checked against exact
// circles and finite differences), spans at knots, validation, reversal, reparametrisation and
// exchanged coordinates.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "curve_fixtures.hpp"
#include "hotmesh/geometry/bspline_curve.hpp"

namespace hotmesh::geometry {
namespace {

using test::quarter_circle;
using test::s_curve;

TEST(BSplineCurve2d, RationalQuarterCircleLiesOnTheCircle) {
  const BSplineCurve2d arc = quarter_circle(2.0, {1.0, -1.0});
  for (int i = 0; i <= 50; ++i) {
    const double t = i / 50.0;
    const CurveDerivatives2d d = arc.derivatives(t);
    const Vec2 radius = d.point - Vec2{1.0, -1.0};
    EXPECT_NEAR(norm(radius), 2.0, 1e-14) << t;
    EXPECT_NEAR(dot(radius, d.first), 0.0, 1e-13) << t;  // tangent orthogonal to the radius
    // Curvature of a circle of radius 2: |c' x c''| / |c'|^3 = 1/2.
    EXPECT_NEAR(std::abs(cross(d.first, d.second)) / std::pow(norm(d.first), 3), 0.5, 1e-12) << t;
  }
  EXPECT_NEAR(arc.point(0.5).x, 1.0 + std::sqrt(2.0), 1e-14);
}

TEST(BSplineCurve2d, DerivativesMatchFiniteDifferences) {
  const BSplineCurve2d curve = s_curve();
  const double h = 1e-5;
  for (const double t : {0.1, 0.3, 0.5, 0.8, 0.95}) {
    const CurveDerivatives2d d = curve.derivatives(t);
    const Vec2 fd1 = (curve.point(t + h) - curve.point(t - h)) / (2 * h);
    const Vec2 fd2 = (curve.derivatives(t + h).first - curve.derivatives(t - h).first) / (2 * h);
    EXPECT_NEAR(distance(d.first, fd1), 0.0, 1e-8) << t;
    EXPECT_NEAR(distance(d.second, fd2), 0.0, 1e-6) << t;
  }
}

TEST(BSplineCurve2d, PolylineSpansGiveOneSidedDerivativesAtKnots) {
  const std::vector<double> t{0.0, 0.5, 1.0};
  const std::vector<Vec2> q{{0, 0}, {1, 0}, {1, 2}};
  const BSplineCurve2d line = BSplineCurve2d::polyline(t, q);
  EXPECT_EQ(line.span_at(0.5), 2u);
  EXPECT_EQ(line.span_at(1.0), 2u);
  EXPECT_EQ(line.span_at(0.0), 1u);
  EXPECT_EQ(line.derivatives(0.5, 1).first, (Vec2{2, 0}));
  EXPECT_EQ(line.derivatives(0.5, 2).first, (Vec2{0, 4}));
  EXPECT_EQ(line.point(0.75), (Vec2{1, 1}));
  EXPECT_EQ(line.breakpoints(), (std::vector<double>{0.0, 0.5, 1.0}));
}

TEST(BSplineCurve2d, ReversedAndReparametrizedTraceTheSamePoints) {
  const BSplineCurve2d arc = quarter_circle();
  const BSplineCurve2d back = arc.reversed();
  const BSplineCurve2d moved = arc.reparametrized(2.0, 6.0);
  for (int i = 0; i <= 10; ++i) {
    const double t = i / 10.0;
    EXPECT_NEAR(distance(arc.point(t), back.point(1.0 - t)), 0.0, 1e-15);
    EXPECT_NEAR(distance(arc.point(t), moved.point(2.0 + 4.0 * t)), 0.0, 1e-15);
  }
  EXPECT_EQ(moved.first_parameter(), 2.0);
  EXPECT_EQ(moved.last_parameter(), 6.0);
  EXPECT_EQ(arc.translated({1, 2}).point(0.0), (Vec2{2, 2}));
}

// A rational arc about (1, -1) with its coordinates exchanged is the mirror arc about (-1, 1):
// every point (a, b) becomes (b, a), weights and all.
TEST(BSplineCurve2d, SwappedCoordinatesMirrorEveryPointInTheDiagonal) {
  const BSplineCurve2d arc = quarter_circle(2.0, {1.0, -1.0});
  const BSplineCurve2d mirror = arc.swapped_coordinates();
  for (int i = 0; i <= 10; ++i) {
    const Vec2 p = arc.point(i / 10.0), q = mirror.point(i / 10.0);
    EXPECT_NEAR(distance(q, Vec2{p.y, p.x}), 0.0, 1e-15) << i;
    EXPECT_NEAR(distance(q, Vec2{-1.0, 1.0}), 2.0, 1e-14) << i;
  }
}

TEST(BSplineCurve2d, RejectsInvalidDefinitions) {
  const auto make = [](int degree, std::vector<double> knots, std::vector<Vec2> poles, std::vector<double> w = {}) {
    return BSplineCurve2d(degree, std::move(knots), std::move(poles), std::move(w));
  };
  EXPECT_THROW(make(0, {0, 1}, {{0, 0}}), std::invalid_argument);
  EXPECT_THROW(make(1, {0, 0, 1}, {{0, 0}, {1, 0}}), std::invalid_argument);            // knot count
  EXPECT_THROW(make(1, {0, 0.5, 1, 1}, {{0, 0}, {1, 0}}), std::invalid_argument);       // not clamped
  EXPECT_THROW(make(1, {0, 0, 1, 0.5}, {{0, 0}, {1, 0}}), std::invalid_argument);       // decreasing
  EXPECT_THROW(make(1, {0, 0, 1, 1}, {{0, 0}, {1, 0}}, {1, -1}), std::invalid_argument);  // weight
  EXPECT_THROW(make(1, {0, 0, 0.5, 0.5, 1, 1}, {{0, 0}, {1, 0}, {2, 0}, {3, 0}}), std::invalid_argument);
  EXPECT_THROW(make(1, {0, 0, 1, 1}, {{0, 0}, {std::numeric_limits<double>::quiet_NaN(), 0}}), std::invalid_argument);
  EXPECT_NO_THROW(make(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}, {{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}}));
}

}  // namespace
}  // namespace hotmesh::geometry
