// hotmesh tests: curves built in code for the geometry tests (arcs, S-shapes, hairpins with
// near-touching branches) and a brute-force closest point to check projections against.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "hotmesh/geometry/bspline_curve.hpp"
#include "hotmesh/geometry/deflected_curve.hpp"

namespace hotmesh::geometry::test {

/// Rational quadratic quarter circle of `radius` about `centre`, from angle 0 to 90 degrees,
/// parameter range [0, 1].
inline BSplineCurve2d quarter_circle(double radius = 1.0, Vec2 centre = {0.0, 0.0}) {
  return BSplineCurve2d(2, {0, 0, 0, 1, 1, 1},
                        {centre + Vec2{radius, 0.0}, centre + Vec2{radius, radius}, centre + Vec2{0.0, radius}},
                        {1.0, std::numbers::sqrt2 / 2.0, 1.0});
}

/// Cubic S-shaped curve over [0, 1] with two interior knots: two opposite bends.
inline BSplineCurve2d s_curve() {
  return BSplineCurve2d(3, {0, 0, 0, 0, 0.35, 0.65, 1, 1, 1, 1},
                        {{0, 0}, {2, 0}, {2, 1}, {0, 1}, {0, 2}, {2, 2}});
}

/// A hairpin: two branches of length 10 along x at y = 0 and y = gap, joined by a U-turn at
/// x ~ 10; quadratic, parameter range [0, 1].
inline BSplineCurve2d hairpin(double gap) {
  return BSplineCurve2d(2, {0, 0, 0, 0.45, 0.5, 0.55, 1, 1, 1},
                        {{0, 0}, {10, 0}, {10 + gap, 0}, {10 + gap, gap}, {10, gap}, {0, gap}});
}

/// Where a brute-force search ends: the parameter, and the value there (for a closest point,
/// its distance).
struct BruteForce {
  double parameter;
  double distance;
};

/// The smallest value of f over [a, b]: the best of samples + 1 evenly spaced points, refined
/// by golden sections between its neighbours; `distance` is f there.
template <class F>
BruteForce sampled_minimum(const F& f, double a, double b, int samples) {
  int best = 0;
  double best_value = f(a);
  for (int i = 1; i <= samples; ++i) {
    const double v = f(a + (b - a) * i / samples);
    if (v < best_value) {
      best_value = v;
      best = i;
    }
  }
  double lo = a + (b - a) * std::max(best - 1, 0) / samples;
  double hi = a + (b - a) * std::min(best + 1, samples) / samples;
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int k = 0; k < 200; ++k) {
    const double x1 = hi - phi * (hi - lo);
    const double x2 = lo + phi * (hi - lo);
    if (f(x1) < f(x2)) {
      hi = x2;
    } else {
      lo = x1;
    }
  }
  const double t = 0.5 * (lo + hi);
  return {t, f(t)};
}

/// Closest point of c_lambda to p by dense sampling plus golden-section refinement.
inline BruteForce brute_force_closest(const DeflectedCurve& curve, Vec2 p, double lambda, int samples = 200000) {
  return sampled_minimum([&](double t) { return distance(curve.point(t, lambda), p); }, curve.first_parameter(),
                         curve.last_parameter(), samples);
}

}  // namespace hotmesh::geometry::test
