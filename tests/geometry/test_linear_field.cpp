// Tests of LinearField, the linear interpolation of a wall's table over a triangulation of its
// nodes (`degree: 1` on a wall without CAD, issue 49 item 8): a piecewise-linear deflection with
// a table node on every kink is reproduced exactly, with no overshoot (where the smooth
// interpolation overshoots by 4 % of the bump); exact at scattered nodes on a curved wall; a
// linear field reproduced; outside the table the nearest triangle's edge; a wall that folds
// over its mean plane refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/linear_field.hpp"
#include "hotmesh/geometry/scattered_field.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::HasSubstr;

/// A bump 0.35 high, piecewise linear in x: flat, up from x = 0.5 to its ridge at 1, down to 1.5, flat.
double tent(double x) { return 0.35 * std::clamp(1.0 - std::abs(x - 1.0) / 0.5, 0.0, 1.0); }

/// The floor [0, 2] x [0, 1] (z = 0) as a 21 x 11 grid of table nodes (one on every kink of the
/// tent), deflected upwards by the tent.
void tent_table(std::vector<Vec3>& points, std::vector<Vec3>& values) {
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 10; ++j) {
      points.push_back({0.1 * i, 0.1 * j, 0.0});
      values.push_back({0.0, 0.0, tent(0.1 * i)});
    }
  }
}

TEST(LinearField, PiecewiseLinearDeflectionWithANodeOnEveryKinkIsExactWithoutOvershoot) {
  std::vector<Vec3> points, values;
  tent_table(points, values);
  const LinearField linear(points, values);
  EXPECT_EQ(linear.report().points, points.size());
  EXPECT_EQ(linear.report().triangles, 2u * 20u * 10u);
  const ScatteredField smooth(points, values);
  double smooth_top = 0.0, linear_error = 0.0;
  for (int i = 0; i <= 400; ++i) {
    for (int j = 0; j <= 100; ++j) {
      const Vec3 x{0.005 * i, 0.01 * j, 0.0};
      const Vec3 d = linear(x);
      linear_error = std::max(linear_error, std::abs(d.z - tent(x.x)) + std::abs(d.x) + std::abs(d.y));
      smooth_top = std::max(smooth_top, std::abs(smooth(x).z - tent(x.x)));
      EXPECT_LE(d.z, 0.35 + 1e-15);
      EXPECT_GE(d.z, -1e-15);
    }
  }
  EXPECT_LT(linear_error, 1e-14);
  // what degree 1 no longer does: the smooth interpolation overshoots next to the kinks
  EXPECT_GT(smooth_top, 0.005);
}

TEST(LinearField, ExactAtScatteredNodesOfACurvedWallAndBetweenThem) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points, values;
  for (int k = 0; k < 400; ++k) {
    const double x = 3.0 * unit(random), y = 2.0 * unit(random);
    points.push_back({x, y, 0.3 * std::sin(x) * std::cos(y)});
    values.push_back({unit(random) - 0.5, unit(random), -unit(random)});
  }
  const LinearField field(points, values);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_EQ(field(points[k]), values[k]) << k;
    EXPECT_EQ(field.outside(points[k]), 0.0);
  }
  // between the nodes: within the values' range, component by component
  for (int k = 0; k < 2000; ++k) {
    const double x = 0.2 + 2.6 * unit(random), y = 0.2 + 1.6 * unit(random);
    const Vec3 d = field({x, y, 0.3 * std::sin(x) * std::cos(y)});
    EXPECT_GE(d.x, -0.5);
    EXPECT_LE(d.x, 0.5);
    EXPECT_GE(d.y, 0.0);
    EXPECT_LE(d.y, 1.0);
    EXPECT_LE(d.z, 0.0);
  }
}

TEST(LinearField, ReproducesALinearFieldAndTakesTheNearestEdgeOutside) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto linear = [](const Vec3& p) { return Vec3{0.1 + 0.02 * p.x, -0.03 * p.y, 0.05 * p.x - 0.01 * p.y}; };
  std::vector<Vec3> points{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}}, values;
  for (int k = 0; k < 100; ++k) points.push_back({unit(random), unit(random), 1.0});
  for (const Vec3& p : points) values.push_back(linear(p));
  const LinearField field(points, values);
  for (int k = 0; k < 500; ++k) {
    const Vec3 x{unit(random), unit(random), 1.0 + 0.01 * (unit(random) - 0.5)};  // off the plane: projected
    EXPECT_LT(distance(field(x), linear({x.x, x.y, 1.0})), 1e-14);
  }
  // beyond the edge x = 1: the value at the nearest point of the edge, and how far out
  EXPECT_LT(distance(field({1.3, 0.4, 1.0}), linear({1.0, 0.4, 1.0})), 1e-14);
  EXPECT_EQ(field.outside({1.3, 0.4, 1.0}), 0.0);  // within a triangle's size of the table
  EXPECT_GT(field.outside({3.0, 0.4, 1.0}), 0.0);
  EXPECT_LT(field.outside({3.0, 0.4, 1.0}), 2.0);
  EXPECT_LT(distance(field({-0.5, -0.5, 1.0}), linear({0.0, 0.0, 1.0})), 1e-14);  // beyond a corner
}

TEST(LinearField, AWallThatFoldsOverItsMeanPlaneIsRefused) {
  // a pipe all round: its upper and lower halves lie over one another
  std::vector<Vec3> points, values;
  for (int i = 0; i <= 10; ++i) {
    for (int k = 0; k < 16; ++k) {
      const double theta = 2.0 * M_PI * (k + 0.25) / 16.0;
      points.push_back({0.5 * i, std::cos(theta), std::sin(theta)});
      values.push_back({0.0, 0.01 * std::cos(theta), 0.01 * std::sin(theta)});
    }
  }
  try {
    const LinearField field(points, values);
    ADD_FAILURE() << "a pipe triangulated over one plane";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("give its CAD faces, or degree 2 or more for the smooth interpolation"));
  }
  EXPECT_NO_THROW(ScatteredField(points, values));  // the smooth interpolation takes it
}

TEST(LinearField, TooFewOrCollinearNodesAndConflictingDuplicatesAreRefused) {
  EXPECT_THROW(LinearField({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{}, {}, {}}), InputError);
  EXPECT_THROW(LinearField({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}}, {{}, {}, {}, {1, 0, 0}}), InputError);
  const LinearField merged({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}}, {{}, {}, {1, 0, 0}, {1, 0, 0}});
  EXPECT_EQ(merged.report().merged_duplicates, 1u);
  EXPECT_EQ(merged.report().triangles, 1u);
}

}  // namespace
}  // namespace hotmesh::geometry
