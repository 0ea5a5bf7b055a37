// hotmesh sample duct3d: the closest point of a two-parameter patch X(t, s) to a point p, by
// Gauss-Newton on (t, s) clamped to a parameter rectangle. Used for the exact deflected floor
// (duct_floor.cpp) and for the bilinear quads of a mesh's floor (floor_distance.cpp).
//
// Each step minimises |X + X_t dt + X_s ds - p|^2 (the 2 x 2 normal equations); a parameter on
// a bound of the rectangle whose descent direction points out of it is held there and the other
// one moves alone. The fixed point satisfies the first-order condition (X - p) . X_t = 0,
// (X - p) . X_s = 0 (or its bound-constrained form). Near the surface (distance << radius of
// curvature) the convergence is fast: the rate is about distance / radius.
#pragma once

#include <algorithm>
#include <cmath>

#include "duct_floor.hpp"

namespace hotmesh::samples::duct3d::detail {

struct Rectangle {
  double t0 = 0.0, t1 = 1.0, s0 = 0.0, s1 = 1.0;
};

/// `evaluate(t, s)` returns a FloorPoint (X and its first derivatives).
template <class Evaluate>
Closest closest_on_patch(const Evaluate& evaluate, const Vec3& p, double t, double s, const Rectangle& r) {
  const double scale = std::max(r.t1 - r.t0, r.s1 - r.s0);
  t = std::clamp(t, r.t0, r.t1);
  s = std::clamp(s, r.s0, r.s1);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const FloorPoint f = evaluate(t, s);
    const Vec3 residual = f.x - p;
    const double a = dot(f.xt, f.xt), b = dot(f.xt, f.xs), c = dot(f.xs, f.xs);
    const double gt = -dot(f.xt, residual), gs = -dot(f.xs, residual);  // the descent direction
    const bool hold_t = (t <= r.t0 && gt < 0.0) || (t >= r.t1 && gt > 0.0);
    const bool hold_s = (s <= r.s0 && gs < 0.0) || (s >= r.s1 && gs > 0.0);
    double dt = 0.0, ds = 0.0;
    if (!hold_t && !hold_s) {
      const double det = a * c - b * b;
      if (!(det > 0.0)) break;  // a degenerate patch: keep the point reached
      dt = (gt * c - gs * b) / det;
      ds = (a * gs - b * gt) / det;
    } else if (!hold_t) {
      dt = gt / a;
    } else if (!hold_s) {
      ds = gs / c;
    }
    const double nt = std::clamp(t + dt, r.t0, r.t1);
    const double ns = std::clamp(s + ds, r.s0, r.s1);
    const double step = std::hypot(nt - t, ns - s);
    t = nt;
    s = ns;
    if (step <= 1e-14 * scale) break;
  }
  const Vec3 x = evaluate(t, s).x;
  return {t, s, x, distance(x, p)};
}

}  // namespace hotmesh::samples::duct3d::detail
