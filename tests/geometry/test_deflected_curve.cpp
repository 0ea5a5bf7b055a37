// Tests of DeflectedCurve: the stages c_lambda = r + lambda D of section 4.3, D held constant
// beyond the FEM range, and the exact B-spline of a stage (polynomial and rational r).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "curve_fixtures.hpp"
#include "hotmesh/geometry/deflected_curve.hpp"
#include "hotmesh/geometry/interpolation.hpp"

namespace hotmesh::geometry {
namespace {

/// A deflection interpolant on [a, b] through a smooth field, in the given form.
BSplineCurve2d interpolant_on(const BSplineCurve2d& r, double a, double b, int q, DeflectionForm form) {
  std::vector<double> t;
  std::vector<Vec2> v;
  for (int j = 0; j <= 8; ++j) {
    const double s = a + (b - a) * j / 8.0;
    const Vec2 delta{0.1 * std::sin(4.0 * s), 0.05 * std::cos(3.0 * s)};
    t.push_back(s);
    v.push_back(form == DeflectionForm::curve ? r.point(s) + delta : delta);
  }
  return interpolate(t, v, q);
}

TEST(DeflectedCurve, StagesInterpolateBetweenUndeformedAndDeflected) {
  const BSplineCurve2d r = test::s_curve();
  for (const DeflectionForm form : {DeflectionForm::curve, DeflectionForm::displacement}) {
    const DeflectedCurve curve(r, interpolant_on(r, 0.2, 0.9, 3, form), form);
    for (const double t : {0.25, 0.5, 0.7}) {
      const Vec2 r_t = r.point(t);
      const Vec2 c_t = curve.point(t, 1.0);
      EXPECT_EQ(curve.point(t, 0.0), r_t);
      EXPECT_NEAR(distance(curve.point(t, 0.25), r_t + 0.25 * (c_t - r_t)), 0.0, 1e-14);
      EXPECT_NEAR(distance(curve.deflection(t), c_t - r_t), 0.0, 1e-14);
    }
  }
}

TEST(DeflectedCurve, DeflectionIsConstantBeyondTheNodes) {
  const BSplineCurve2d r = test::s_curve();
  const DeflectedCurve curve(r, interpolant_on(r, 0.2, 0.9, 1, DeflectionForm::displacement),
                             DeflectionForm::displacement);
  const Vec2 first = curve.deflection(0.2);
  const Vec2 last = curve.deflection(0.9);
  EXPECT_NEAR(first.x, 0.1 * std::sin(0.8), 1e-14);
  for (const double t : {0.0, 0.05, 0.19}) EXPECT_NEAR(distance(curve.deflection(t), first), 0.0, 1e-14);
  for (const double t : {0.91, 0.99, 1.0}) EXPECT_NEAR(distance(curve.deflection(t), last), 0.0, 1e-14);
  // Beyond the nodes the stage moves rigidly: same derivatives as r.
  EXPECT_EQ(curve.derivatives(0.1, 0.7).first, r.derivatives(0.1).first);
}

TEST(DeflectedCurve, PiecesSplitAtEveryKnotAndAtTheNodeRange) {
  const BSplineCurve2d r = test::s_curve();  // knots 0.35, 0.65
  const DeflectedCurve curve(r, interpolant_on(r, 0.2, 0.9, 1, DeflectionForm::curve), DeflectionForm::curve);
  std::vector<double> begins;
  for (const auto& piece : curve.pieces()) begins.push_back(piece.begin);
  EXPECT_THAT(begins, ::testing::Contains(0.2));
  EXPECT_THAT(begins, ::testing::Contains(0.35));
  EXPECT_THAT(begins, ::testing::Contains(::testing::DoubleNear(0.9, 1e-15)));
  EXPECT_EQ(curve.pieces().front().region, DeflectedCurve::Region::before);
  EXPECT_EQ(curve.pieces().back().region, DeflectedCurve::Region::after);
  EXPECT_EQ(curve.pieces()[curve.piece_at(0.5)].region, DeflectedCurve::Region::inside);
}

TEST(DeflectedCurve, StageBSplineIsExactForPolynomialAndRationalCurves) {
  for (const BSplineCurve2d& r : {test::s_curve(), test::quarter_circle(1.5)}) {
    for (const DeflectionForm form : {DeflectionForm::curve, DeflectionForm::displacement}) {
      for (const int q : {1, 3}) {
        const DeflectedCurve curve(r, interpolant_on(r, 0.1, 0.8, q, form), form);
        for (const double lambda : {0.0, 0.4, 1.0}) {
          const BSplineCurve2d stage = curve.stage(lambda);
          EXPECT_EQ(stage.is_rational(), r.is_rational());
          for (int i = 0; i <= 200; ++i) {
            const double t = i / 200.0;
            ASSERT_NEAR(distance(stage.point(t), curve.point(t, lambda)), 0.0, 1e-12)
                << "form " << to_string(form) << " q " << q << " lambda " << lambda << " t " << t;
          }
        }
      }
    }
  }
}

/// max |stage(lambda)(t) - c_lambda(t)| over a dense sampling.
double stage_error(const DeflectedCurve& curve, double lambda) {
  const BSplineCurve2d stage = curve.stage(lambda);
  double worst = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double t = curve.first_parameter() + (curve.last_parameter() - curve.first_parameter()) * i / 400.0;
    worst = std::max(worst, distance(stage.point(t), curve.point(t, lambda)));
  }
  return worst;
}

// Issue 18, item 1: FEM nodes on a curve's ends or knots, to rounding (a face end, the joint of
// two faces), gave knots a rounding apart that the exact stage could not split at.
TEST(DeflectedCurve, StageIsExactWhenNodesLieOnKnotsToRounding) {
  const BSplineCurve2d r = test::s_curve();  // knots 0.35, 0.65
  const double eps = 4e-16;
  for (const auto& [a, b] : {std::pair{0.0 + eps, 1.0 - eps}, std::pair{0.35 + eps, 0.65 - eps},
                             std::pair{0.35 - eps, 0.65 + eps}, std::pair{0.1, 0.65 - eps}}) {
    for (const int q : {1, 2, 3, 5}) {
      const DeflectedCurve curve(r, interpolant_on(r, a, b, q, DeflectionForm::displacement),
                                 DeflectionForm::displacement);
      EXPECT_LT(stage_error(curve, 1.0), 1e-12) << "FEM range [" << a << ", " << b << "], q " << q;
    }
  }
}

// Issue 18, item 2: averaged knots of a cubic interpolant through evenly spaced nodes fall on
// the nodes to rounding, which are the knots of the polyline through them (2D without CAD).
TEST(DeflectedCurve, StageIsExactForOddDegreesOnThePolylineOfTheNodes) {
  std::vector<double> t;
  std::vector<Vec2> points;
  std::vector<Vec2> deflections;
  for (int j = 0; j <= 30; ++j) {
    t.push_back(j / 30.0);
    points.push_back({j / 30.0, 0.2 * std::sin(5.0 * j / 30.0)});
    deflections.push_back({0.0, 0.01 * j / 30.0});
  }
  const BSplineCurve2d polyline = BSplineCurve2d::polyline(t, points);
  for (const int q : {3, 5}) {
    const DeflectedCurve curve(polyline, interpolate(t, deflections, q), DeflectionForm::displacement);
    EXPECT_LT(stage_error(curve, 1.0), 1e-12) << "q " << q;
    EXPECT_LT(stage_error(curve, 0.5), 1e-12) << "q " << q;
  }
}

TEST(DeflectedCurve, WithoutDeflectionEveryStageIsTheCurve) {
  const DeflectedCurve curve(test::quarter_circle());
  EXPECT_FALSE(curve.interpolant().has_value());
  EXPECT_EQ(curve.point(0.3, 1.0), curve.point(0.3, 0.0));
  EXPECT_EQ(curve.stage(1.0).poles(), test::quarter_circle().poles());
}

TEST(DeflectedCurve, RejectsInterpolantOutsideTheCurve) {
  const BSplineCurve2d r = test::quarter_circle();
  const BSplineCurve2d wide = BSplineCurve2d::polyline(std::vector<double>{-0.1, 1.0}, std::vector<Vec2>{{0, 0}, {1, 1}});
  EXPECT_THROW(DeflectedCurve(r, wide, DeflectionForm::curve), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::geometry
