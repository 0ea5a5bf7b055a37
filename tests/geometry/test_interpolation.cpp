// Tests of eq. (21), banded B-spline interpolation with averaged knots: the knot vector of
// The NURBS Book eq. (9.8), interpolation conditions, and exact reproduction of polynomials.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "hotmesh/geometry/interpolation.hpp"

namespace hotmesh::geometry {
namespace {

TEST(AveragedKnots, FollowEquationNinePointEight) {
  const std::vector<double> t{0.0, 0.1, 0.3, 0.6, 0.7, 1.0};
  EXPECT_EQ(averaged_knots(t, 1), (std::vector<double>{0, 0, 0.1, 0.3, 0.6, 0.7, 1, 1}));
  const std::vector<double> cubic = averaged_knots(t, 3);
  ASSERT_EQ(cubic.size(), 10u);
  EXPECT_NEAR(cubic[4], (0.1 + 0.3 + 0.6) / 3, 1e-15);
  EXPECT_NEAR(cubic[5], (0.3 + 0.6 + 0.7) / 3, 1e-15);
  EXPECT_EQ(cubic[3], 0.0);
  EXPECT_EQ(cubic[6], 1.0);
}

TEST(Interpolate, PassesThroughEveryPointForEveryDegree) {
  std::vector<double> t;
  std::vector<Vec2> v;
  for (int j = 0; j < 17; ++j) {
    t.push_back(j / 16.0 + 0.01 * std::sin(3.0 * j) * (j > 0 && j < 16));
    v.push_back({std::cos(5.0 * j), std::sin(2.0 * j) + j});
  }
  for (int q = 1; q <= 5; ++q) {
    const BSplineCurve2d c = interpolate(t, v, q);
    EXPECT_EQ(c.degree(), q);
    EXPECT_EQ(c.poles().size(), t.size());
    for (std::size_t j = 0; j < t.size(); ++j) EXPECT_NEAR(distance(c.point(t[j]), v[j]), 0.0, 1e-12) << q << " " << j;
  }
}

TEST(Interpolate, ReproducesPolynomialsOfItsDegree) {
  std::vector<double> t;
  for (int j = 0; j <= 12; ++j) t.push_back(std::pow(j / 12.0, 1.3));  // non-uniform
  for (int q = 1; q <= 5; ++q) {
    const auto f = [q](double s) { return Vec2{std::pow(s - 0.3, q) + 2.0 * s, 1.0 - std::pow(s, q)}; };
    std::vector<Vec2> v;
    for (const double s : t) v.push_back(f(s));
    const BSplineCurve2d c = interpolate(t, v, q);
    for (int i = 0; i <= 100; ++i) EXPECT_NEAR(distance(c.point(i / 100.0), f(i / 100.0)), 0.0, 1e-12) << q;
  }
}

TEST(Interpolate, RejectsTooFewOrUnorderedParameters) {
  const std::vector<Vec2> v{{0, 0}, {1, 0}, {2, 0}};
  EXPECT_THROW(interpolate(std::vector<double>{0, 0.5, 1}, v, 3), std::invalid_argument);
  EXPECT_THROW(interpolate(std::vector<double>{0, 0.5, 0.5}, v, 1), std::invalid_argument);
  EXPECT_THROW(interpolate(std::vector<double>{0, 1}, v, 1), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::geometry
