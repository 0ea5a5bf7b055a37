// Tests of CurveProjector: cold starts find the global closest point on adversarial curves
// (S-shapes, hairpins with near-touching branches, corners), normals are orthogonal to the
// curve, warm starts agree with cold ones, and concurrent use gives the serial results.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "curve_fixtures.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/geometry/interpolation.hpp"

namespace hotmesh::geometry {
namespace {

using test::brute_force_closest;

/// The projection is a global minimum and its normal is orthogonal to the curve there.
void expect_global_and_orthogonal(const CurveProjector& projector, Vec2 p, double lambda) {
  const CurveProjection q = projector.project(p, lambda);
  const test::BruteForce reference = brute_force_closest(projector.curve(), p, lambda);
  EXPECT_NEAR(q.distance, reference.distance, 1e-9) << "p = (" << p.x << ", " << p.y << ")";
  EXPECT_NEAR(distance(q.point, projector.curve().point(q.parameter, lambda)), 0.0, 1e-12);
  EXPECT_NEAR(norm(q.normal), 1.0, 1e-12);
  const Vec2 tangent = projector.curve().derivatives(q.parameter, lambda).first;
  const bool interior = q.parameter > projector.curve().first_parameter() + 1e-9 &&
                        q.parameter < projector.curve().last_parameter() - 1e-9;
  if (interior && norm(tangent) > 0.0) {
    EXPECT_NEAR(dot(q.normal, tangent) / norm(tangent), 0.0, 1e-9) << "p = (" << p.x << ", " << p.y << ")";
  }
}

TEST(CurveProjector, ColdStartIsGlobalOnAnSCurve) {
  const CurveProjector projector{DeflectedCurve(test::s_curve())};
  for (int i = 0; i <= 12; ++i) {
    for (int j = 0; j <= 12; ++j) expect_global_and_orthogonal(projector, {-1.0 + 0.33 * i, -1.0 + 0.33 * j}, 0.0);
  }
}

TEST(CurveProjector, ColdStartPicksTheNearerOfNearTouchingBranches) {
  const double gap = 1e-3;
  const CurveProjector projector{DeflectedCurve(test::hairpin(gap))};
  EXPECT_LT(projector.sampling_deviation(), 1e-2);
  for (const double x : {0.5, 3.0, 7.7, 9.99}) {
    for (const double f : {-5.0, 0.1, 0.45, 0.55, 0.9, 6.0}) {
      const Vec2 p{x, f * gap};
      const CurveProjection q = projector.project(p, 0.0);
      EXPECT_NEAR(q.distance, std::abs(p.y - (f < 0.5 ? 0.0 : gap)), 1e-12) << x << " " << f;
      EXPECT_EQ(q.parameter < 0.5, f < 0.5) << x << " " << f;
      expect_global_and_orthogonal(projector, p, 0.0);
    }
  }
}

TEST(CurveProjector, PartialStagesOfADeflectionThatClosesTheGap) {
  // The upper branch of a hairpin with gap 0.2 is pushed down by 0.19: at lambda = 1 the
  // branches are 0.01 apart. Every stage is searched globally.
  const BSplineCurve2d r = test::hairpin(0.2);
  std::vector<double> t;
  std::vector<Vec2> d;
  for (int j = 0; j <= 40; ++j) {
    t.push_back(j / 40.0);
    d.push_back({0.0, t.back() > 0.55 ? -0.19 : 0.0});
  }
  const DeflectedCurve curve(r, interpolate(t, d, 1), DeflectionForm::displacement);
  const CurveProjector projector(curve);
  for (const double lambda : {0.0, 0.5, 0.9, 1.0}) {
    for (const double x : {1.0, 4.2, 8.0}) {
      for (const double y : {-0.05, 0.004, 0.006, 0.02, 0.1, 0.3}) expect_global_and_orthogonal(projector, {x, y}, lambda);
    }
  }
}

TEST(CurveProjector, CornerOfAPolylineGetsTheBisectorNormal) {
  const BSplineCurve2d line =
      BSplineCurve2d::polyline(std::vector<double>{0.0, 0.5, 1.0}, std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}});
  const CurveProjector projector{DeflectedCurve(line)};
  const CurveProjection q = projector.project({1.5, -0.5}, 0.0);
  EXPECT_EQ(q.parameter, 0.5);
  EXPECT_NEAR(q.distance, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(q.normal.x, -std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(q.normal.y, std::sqrt(0.5), 1e-15);
  // From either side with a warm start too.
  EXPECT_EQ(projector.project({1.5, -0.5}, 0.0, 0.2).parameter, 0.5);
  EXPECT_EQ(projector.project({1.5, -0.5}, 0.0, 0.9).parameter, 0.5);
  // Inside the corner the nearer leg wins.
  EXPECT_NEAR(projector.project({0.8, 0.1}, 0.0).point.y, 0.0, 1e-15);
  EXPECT_NEAR(projector.project({0.95, 0.6}, 0.0).point.x, 1.0, 1e-15);
}

TEST(CurveProjector, EndsAndCentresOfCircles) {
  const CurveProjector projector{DeflectedCurve(test::quarter_circle(2.0))};
  const CurveProjection centre = projector.project({0.0, 0.0}, 0.0);
  EXPECT_NEAR(centre.distance, 2.0, 1e-14);
  const CurveProjection beyond_end = projector.project({3.0, -1.0}, 0.0);
  EXPECT_EQ(beyond_end.parameter, 0.0);
  EXPECT_NEAR(distance(beyond_end.point, Vec2{2.0, 0.0}), 0.0, 1e-15);
  const CurveProjection on_curve = projector.project(projector.curve().point(0.37, 0.0), 0.0);
  EXPECT_NEAR(on_curve.parameter, 0.37, 1e-12);
  EXPECT_NEAR(on_curve.distance, 0.0, 1e-14);
}

TEST(CurveProjector, WarmStartFromANearbyProjectionAgreesWithColdStart) {
  const CurveProjector projector{DeflectedCurve(test::s_curve())};
  double hint = projector.project(projector.curve().point(0.05, 0.0), 0.0).parameter;
  int total_iterations = 0;
  for (int i = 1; i <= 100; ++i) {
    // A point walking along the S, a little off it, as a sliding node does.
    const Vec2 p = projector.curve().point(0.05 + 0.009 * i, 0.0) + Vec2{0.01, -0.02};
    const CurveProjection warm = projector.project(p, 0.0, hint);
    const CurveProjection cold = projector.project(p, 0.0);
    EXPECT_NEAR(warm.parameter, cold.parameter, 1e-12) << i;
    EXPECT_LE(warm.iterations, 8) << i;  // crossing a knot costs an iteration or two
    total_iterations += warm.iterations;
    hint = warm.parameter;
  }
  EXPECT_LE(total_iterations, 450);  // large moves along the S here: 4.5 per projection at most
}

TEST(CurveProjector, CrossesKnotsThatDifferOnlyByRounding) {
  // r has a knot at 20/60; the cubic interpolant through 400 nodes has one within rounding of
  // it. Newton must not stall on the sliver between them.
  std::vector<Vec2> poles;
  for (int i = 0; i < 63; ++i) poles.push_back({0.5 + 0.05 * std::sin(0.7 * i), 0.02 * i});
  std::vector<double> knots(4, 0.0);
  for (int i = 1; i < 60; ++i) knots.push_back(i / 60.0);
  knots.insert(knots.end(), 4, 1.0);
  const BSplineCurve2d r(3, std::move(knots), std::move(poles));
  // The interpolation parameters come from projecting the nodes on r, as in reconstruct().
  const CurveProjector on_r{DeflectedCurve(r)};
  std::vector<double> t;
  std::vector<Vec2> d;
  for (int j = 0; j < 400; ++j) {
    t.push_back(on_r.project(r.point(j / 399.0), 0.0).parameter);
    d.push_back(r.point(t.back()) + Vec2{0.01 * std::sin(9.0 * t.back()), 0.005 * std::cos(5.0 * t.back())});
  }
  const CurveProjector projector{DeflectedCurve(r, interpolate(t, d, 3), DeflectionForm::curve)};
  for (const auto& piece : projector.curve().pieces()) EXPECT_GT(piece.end - piece.begin, 1e-12);
  for (const Vec2 p : {Vec2{0.541398, 0.421465}, Vec2{0.535505, 0.416783}, Vec2{0.539121, 0.419293}}) {
    const CurveProjection cold = projector.project(p, 0.5);
    const CurveProjection warm = projector.project(p, 0.5, 20.0 / 60.0);
    EXPECT_NEAR(warm.parameter, cold.parameter, 1e-12);
    EXPECT_NEAR(dot(warm.point - p, projector.curve().derivatives(warm.parameter, 0.5).first), 0.0, 1e-12);
  }
}

TEST(CurveProjector, ConcurrentProjectionsMatchSerialOnes) {
  const CurveProjector projector{DeflectedCurve(test::hairpin(0.01))};
  std::vector<Vec2> points;
  for (int i = 0; i < 2000; ++i) points.push_back({std::fmod(0.37 * i, 11.0), 0.02 * std::sin(1.3 * i)});
  std::vector<double> serial(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) serial[i] = projector.project(points[i], 0.5).parameter;
  std::vector<double> parallel(points.size());
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] {
      for (std::size_t i = k; i < points.size(); i += 4) parallel[i] = projector.project(points[i], 0.5).parameter;
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(parallel, serial);
}

}  // namespace
}  // namespace hotmesh::geometry
