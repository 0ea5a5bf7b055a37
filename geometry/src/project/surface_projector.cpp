// hotmesh geometry: closest points on parametric surface patches (see surface_projector.hpp),
// the queries: branch and bound over the sub-patch tree and box-constrained Newton with the
// full Hessian on each patch (the sampling and the tree are built in surface_projector_setup.cpp).
// Why not CGAL's AABB tree: its primitives are fixed triangles or segments and its queries return
// the one closest primitive; here a query wants every sub-patch whose lower bound (distance to its
// triangles minus its deviation) beats the best distance found so far, and runs Newton from it,
// so the pruning bound changes during the traversal. A small tree of our own does that directly.
#include "hotmesh/geometry/surface_projector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "project/surface_projector_detail.hpp"

namespace hotmesh::geometry {

namespace {

using detail::kDegenerateNormal;
using detail::Sym2;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Cell bounds are sampled: maxima are used times kMaximumSafety, minima times kMinimumSafety.
constexpr double kMaximumSafety = 1.25;
constexpr double kMinimumSafety = 0.8;
/// Newton steps shorter than this (relative to the scale) skip the descent check: f is flat to
/// rounding there and the quadratic model is good.
constexpr double kLocalStep = 1e-7;
/// After a full Newton step (Hessian, no bound hit) shorter than this (relative to the scale),
/// Newton stops: quadratic convergence puts the next step below rounding.
constexpr double kFinalStep = 1e-8;
/// The Hessian is used where it is positive definite with this margin against J^T J.
constexpr double kDefiniteMargin = 1e-3;
/// A point this close to an edge of its rectangle (relative to the scale) is on it.
constexpr double kBoundary = 1e-10;
/// Minima found during one global search that later sub-patches are checked against.
constexpr int kRememberedMinima = 8;

double squared(const Vec3& v) { return dot(v, v); }

double box_squared_distance(const Vec3& lo, const Vec3& hi, const Vec3& p) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
    sum += d * d;
  }
  return sum;
}

/// Closest point to p on triangle (a, b, c) as a + s (b - a) + t (c - a) (Ericson, Real-Time
/// Collision Detection, 5.1.5): returns the squared distance, s and t.
double triangle_squared_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double& s, double& t) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = dot(ab, ap);
  const double d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    s = 0.0, t = 0.0;
  } else {
    const Vec3 bp = p - b;
    const double d3 = dot(ab, bp);
    const double d4 = dot(ac, bp);
    const Vec3 cp = p - c;
    const double d5 = dot(ab, cp);
    const double d6 = dot(ac, cp);
    const double va = d3 * d6 - d5 * d4;
    const double vb = d5 * d2 - d1 * d6;
    const double vc = d1 * d4 - d3 * d2;
    if (d3 >= 0.0 && d4 <= d3) {
      s = 1.0, t = 0.0;
    } else if (d6 >= 0.0 && d5 <= d6) {
      s = 0.0, t = 1.0;
    } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
      s = d1 / (d1 - d3), t = 0.0;
    } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
      s = 0.0, t = d2 / (d2 - d6);
    } else if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
      t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      s = 1.0 - t;
    } else {
      const double denominator = va + vb + vc;
      s = vb / denominator;
      t = vc / denominator;
      if (!std::isfinite(s) || !std::isfinite(t)) s = 0.0, t = 0.0;  // a degenerate triangle
    }
  }
  return squared(a + s * ab + t * ac - p);
}

/// The step d on the free parameters (0 on the others) from M d = -g: M the Hessian H where it
/// is positive definite with a margin against the Gauss-Newton matrix J^T J, else J^T J with a
/// tiny Levenberg shift (it stays invertible where the parametrisation degenerates: S_u = 0 at a
/// pole). Returns whether H was used; d stays 0 if M is singular.
bool newton_step(const Sym2& h, const Sym2& gn, const double (&g)[2], const bool (&free)[2], double (&d)[2]) {
  d[0] = 0.0, d[1] = 0.0;
  const double shift = 1e-12 * (gn.uu + gn.vv);
  if (free[0] && free[1]) {
    const double det_h = h.uu * h.vv - h.uv * h.uv;
    const double det_gn = gn.uu * gn.vv - gn.uv * gn.uv;
    const bool definite = h.uu > kDefiniteMargin * gn.uu && h.vv > kDefiniteMargin * gn.vv && det_h > 0.0 &&
                          det_h > kDefiniteMargin * kDefiniteMargin * det_gn;
    const Sym2 m = definite ? h : Sym2{gn.uu + shift, gn.uv, gn.vv + shift};
    const double det = m.uu * m.vv - m.uv * m.uv;
    if (!(det > 0.0)) return false;
    d[0] = -(m.vv * g[0] - m.uv * g[1]) / det;
    d[1] = -(m.uu * g[1] - m.uv * g[0]) / det;
    return definite;
  }
  const int k = free[0] ? 0 : 1;
  const double hk = k == 0 ? h.uu : h.vv;
  const double gk = k == 0 ? gn.uu : gn.vv;
  const bool definite = hk > 0.0 && hk > kDefiniteMargin * gk;
  const double m = definite ? hk : gk + shift;
  if (!(m > 0.0)) return false;
  d[k] = -g[k] / m;
  return definite;
}

}  // namespace

SurfaceDerivatives SurfaceProjector::evaluate(int patch, double u, double v) const {
  return patches_[static_cast<std::size_t>(patch)].evaluate(u, v);
}

// The last step, shorter than the tolerance, is still taken if f does not grow: without it, a
// point moved along the surface by less than the tolerance would be put back where the search
// started (a sliding node moved 1e-11 along a face by the solver, put back at every Newton step).
void SurfaceProjector::take_short_step(const Vec3& p, int patch, const double (&lo)[2], const double (&hi)[2],
                                       const double (&d)[2], double (&x)[2], SurfaceDerivatives& e, double& f) const {
  const double last[2] = {std::clamp(x[0] + d[0], lo[0], hi[0]), std::clamp(x[1] + d[1], lo[1], hi[1])};
  if (last[0] == x[0] && last[1] == x[1]) return;
  const SurfaceDerivatives e_last = evaluate(patch, last[0], last[1]);
  const double f_last = squared(e_last.point - p);
  if (f_last <= f) x[0] = last[0], x[1] = last[1], e = e_last, f = f_last;
}

// Closest point on one patch: minimise f(u, v) = |r|^2 / 2, r = S(u, v) - p, over its rectangle.
//   gradient  g = (r.S_u, r.S_v)
//   Hessian   H = [S_u.S_u + r.S_uu   S_u.S_v + r.S_uv]
//                 [S_u.S_v + r.S_uv   S_v.S_v + r.S_vv]
// Projected Newton with an active set (Bertsekas, SIAM J. Control Optim. 20, 1982): a parameter
// at a bound of the rectangle stays there while its gradient, or its Newton step, points
// outwards; the step is Newton's on the other parameter (a 1D problem along that edge), and with
// both fixed (a corner) the search ends. Where H is not clearly positive definite (far out on the
// concave side, near a saddle) J^T J replaces it and still gives a descent direction. The step
// is projected onto the rectangle and halved until f does not grow. Newton stops after a step
// that moves the point by less than the tolerance (taken, so that a point of the surface
// projects onto itself to rounding), or after a full Newton step shorter than kFinalStep
// (quadratic convergence puts the next one below rounding).
SurfaceProjector::Local SurfaceProjector::newton_in_rectangle(const Vec3& p, int patch, double u, double v) const {
  const ParameterRectangle& box = patches_[static_cast<std::size_t>(patch)].domain;
  const double lo[2] = {box.u_first, box.v_first};
  const double hi[2] = {box.u_last, box.v_last};
  double x[2] = {std::clamp(u, lo[0], hi[0]), std::clamp(v, lo[1], hi[1])};
  SurfaceDerivatives e = evaluate(patch, x[0], x[1]);
  double f = squared(e.point - p);
  int iteration = 0;
  bool converged = false;
  while (iteration < max_iterations_) {
    ++iteration;
    const Vec3 r = e.point - p;
    const double g[2] = {dot(r, e.du), dot(r, e.dv)};
    const Sym2 gn{dot(e.du, e.du), dot(e.du, e.dv), dot(e.dv, e.dv)};
    const Sym2 h{gn.uu + dot(r, e.duu), gn.uv + dot(r, e.duv), gn.vv + dot(r, e.dvv)};
    bool free[2];
    for (int k = 0; k < 2; ++k) free[k] = !((x[k] <= lo[k] && g[k] > 0.0) || (x[k] >= hi[k] && g[k] < 0.0));
    double d[2] = {0.0, 0.0};
    bool full = false;
    for (int pass = 0; pass < 2 && (free[0] || free[1]); ++pass) {
      full = newton_step(h, gn, g, free, d);
      bool outwards = false;
      for (int k = 0; k < 2; ++k) {
        if (free[k] && ((x[k] <= lo[k] && d[k] < 0.0) || (x[k] >= hi[k] && d[k] > 0.0))) {
          free[k] = false;
          outwards = true;
        }
      }
      if (!outwards) break;
      d[0] = 0.0, d[1] = 0.0;
    }
    const double length = norm(d[0] * e.du + d[1] * e.dv);
    if (!std::isfinite(length)) break;
    if (length <= tolerance_) {  // a corner, a stationary point, or one within the tolerance
      take_short_step(p, patch, lo, hi, d, x, e, f);
      converged = true;
      break;
    }
    // Line search on the projected path clamp(x + alpha d).
    double alpha = 1.0;
    double next[2] = {x[0], x[1]};
    SurfaceDerivatives e_next;
    double f_next = kInfinity;
    bool clipped = false;
    bool accepted = false;
    for (int halving = 0; halving < 40; ++halving, alpha *= 0.5) {
      clipped = false;
      for (int k = 0; k < 2; ++k) {
        const double t = x[k] + alpha * d[k];
        next[k] = std::clamp(t, lo[k], hi[k]);
        clipped = clipped || next[k] != t;
      }
      if (next[0] == x[0] && next[1] == x[1]) break;
      e_next = evaluate(patch, next[0], next[1]);
      f_next = squared(e_next.point - p);
      if (f_next <= f || alpha * length <= kLocalStep * scale_) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {  // no decrease left at rounding level
      converged = true;
      break;
    }
    x[0] = next[0], x[1] = next[1];
    e = e_next;
    f = f_next;
    if (full && alpha == 1.0 && !clipped && length <= kFinalStep * scale_) {
      converged = true;
      break;
    }
  }
  return {{patch, x[0], x[1]}, e, std::sqrt(f), iteration, converged};
}

bool SurfaceProjector::better(const Local& a, const Local& b, int hint_patch) const {
  if (a.distance < b.distance - tie_) return true;
  if (a.distance > b.distance + tie_) return false;
  if (a.converged != b.converged) return a.converged;
  if (a.where.patch == b.where.patch) return false;  // the first found (a warm start's) stays
  const auto rank = [hint_patch](int patch) { return patch == hint_patch ? -1 : patch; };
  return rank(a.where.patch) < rank(b.where.patch);
}

// A sub-patch next to a minimum F found on its patch (distance d: p lies on F's normal, at d)
// holds no nearer point when the surface over the parameter box R spanning F and the sub-patch is
// one gently curved sheet. Bounds on its normal curvature and on the length of the image of a
// segment from F within R:
//   kappa <= max |II(t, t)| / min |J t|^2 <= bending / metric,  l <= max|S_u| du + max|S_v| dv,
// with bending = max(|n.S_uu|, |n.S_vv|) + |n.S_uv| (the second fundamental form: free of the
// parametrisation's own acceleration) and du, dv the extents of R. If kappa l <= 1, the normal
// turns by at most a radian over R: the sheet is a graph over F's tangent plane; if moreover
// 2 d kappa <= 1, its curvature radius is at least twice d, and the ball of radius d about p,
// tangent to the sheet at F, cannot reach into it. This takes the sheet not to overlap itself
// within R (no helicoidal ramp stacked within a few knot spans), as no CAD face does. The bounds
// are the samples' in the initial grid cells that R overlaps, maxima times 1.25 and the minimum
// times 0.8.
bool SurfaceProjector::outside_ball(const SubPatch& sub, const Minimum& m) const {
  if (m.where.patch != sub.patch) return false;
  const Cells& cells = cells_[static_cast<std::size_t>(sub.patch)];
  const ParameterRectangle& r = sub.rect;
  const double u0 = std::min(r.u_first, m.where.u);
  const double u1 = std::max(r.u_last, m.where.u);
  const double v0 = std::min(r.v_first, m.where.v);
  const double v1 = std::max(r.v_last, m.where.v);
  // The cells [first, last] of one direction that hold [a, b].
  const auto cell_range = [](const std::vector<double>& lines, double a, double b, std::size_t& first,
                             std::size_t& last) {
    const std::size_t n = lines.size() - 1;
    const auto after = static_cast<std::size_t>(std::upper_bound(lines.begin(), lines.end(), a) - lines.begin());
    const auto at = static_cast<std::size_t>(std::lower_bound(lines.begin(), lines.end(), b) - lines.begin());
    first = std::min(n - 1, std::max<std::size_t>(after, 1) - 1);
    last = std::min(n - 1, std::max<std::size_t>(at, 1) - 1);
  };
  std::size_t i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  cell_range(cells.us, u0, u1, i0, i1);
  cell_range(cells.vs, v0, v1, j0, j1);
  CellBounds b{0.0, 0.0, 0.0, kInfinity};
  const std::size_t nv = cells.vs.size() - 1;
  for (std::size_t i = i0; i <= i1; ++i) {
    for (std::size_t j = j0; j <= j1; ++j) {
      const CellBounds& c = cells.bounds[i * nv + j];
      b = {std::max(b.du, c.du), std::max(b.dv, c.dv), std::max(b.bending, c.bending), std::min(b.metric, c.metric)};
    }
  }
  const double kappa = kMaximumSafety * b.bending / (kMinimumSafety * b.metric);
  const double length = kMaximumSafety * (b.du * (u1 - u0) + b.dv * (v1 - v0));
  return kappa * length <= 1.0 && 2.0 * m.distance * kappa <= 1.0;
}

// Branch and bound over the tree, nearer child first. A sub-patch may hold a point nearer than
// the best found when its box is within the best distance, and then when its triangles are
// within the best distance plus its deviation; unless a minimum already found rules it out
// (outside_ball), Newton starts from the triangles' nearest point. Newton runs on the whole
// patch, so its result may lie outside the sub-patch it started from.
SurfaceProjector::Local SurfaceProjector::global_search(const Vec3& p, const SurfaceParameter& hint,
                                                        const Local* seed, RimCache& rim) const {
  Local best{{-1, 0.0, 0.0}, {}, kInfinity, 0, false};
  int iterations = 0;
  Minimum minima[kRememberedMinima];
  int found = 0;
  if (seed != nullptr) {
    best = *seed;
    iterations = seed->iterations;
    if (seed->converged && !seed->on_rim) minima[found++] = {seed->where, seed->distance};
  }
  const auto examine = [&](const SubPatch& sub) {
    const double bound = best.distance + tie_;
    if (box_squared_distance(sub.box.lo, sub.box.hi, p) > bound * bound) return;
    const auto& c = sub.corner;  // at (u0, v0), (u1, v0), (u0, v1), (u1, v1)
    const ParameterRectangle& r = sub.rect;
    double s1 = 0.0, t1 = 0.0, s2 = 0.0, t2 = 0.0;
    const double d1 = triangle_squared_distance(p, c[0], c[1], c[3], s1, t1);
    const double d2 = triangle_squared_distance(p, c[0], c[3], c[2], s2, t2);
    if (std::sqrt(std::min(d1, d2)) - sub.deviation > bound) return;
    for (int i = 0; i < std::min(found, kRememberedMinima); ++i) {
      if (outside_ball(sub, minima[i])) return;
    }
    const double hu = r.u_last - r.u_first;
    const double hv = r.v_last - r.v_first;
    const double u = r.u_first + (d1 <= d2 ? (s1 + t1) * hu : s2 * hu);
    const double v = r.v_first + (d1 <= d2 ? t1 * hv : (s2 + t2) * hv);
    const Local local = newton(p, sub.patch, u, v, &rim);
    iterations += local.iterations;
    if (local.converged && !local.on_rim) minima[found++ % kRememberedMinima] = {local.where, local.distance};
    if (better(local, best, hint.patch)) best = local;
  };
  std::uint32_t stack[96];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = tree_[stack[--top]];
    const double bound = best.distance + tie_;
    if (box_squared_distance(node.box.lo, node.box.hi, p) > bound * bound) continue;
    if (node.count == 0) {
      const Node& a = tree_[node.first];
      const Node& b = tree_[node.first + 1];
      const bool a_nearer =
          box_squared_distance(a.box.lo, a.box.hi, p) <= box_squared_distance(b.box.lo, b.box.hi, p);
      stack[top++] = a_nearer ? node.first + 1 : node.first;  // the farther child, visited later
      stack[top++] = a_nearer ? node.first : node.first + 1;
      continue;
    }
    for (std::uint32_t i = node.first; i < node.first + node.count; ++i) examine(subs_[i]);
  }
  best.iterations = iterations;
  return best;
}

// On an edge: at a bound of the rectangle, or so near one that the point is within
// kBoundary of the edge (Newton may stop a rounding error short of it).
bool SurfaceProjector::on_boundary(const SurfaceParameter& where, const SurfaceDerivatives& d) const {
  const ParameterRectangle& r = patches_[static_cast<std::size_t>(where.patch)].domain;
  const double reach = kBoundary * scale_;
  const double su = norm(d.du);
  const double sv = norm(d.dv);
  return (where.u - r.u_first) * su <= reach || (r.u_last - where.u) * su <= reach ||
         (where.v - r.v_first) * sv <= reach || (r.v_last - where.v) * sv <= reach;
}

// Unit normal S_u x S_v. Where it vanishes, its limit along the ray x + t (a, b), t > 0, from
// the point towards the rectangle's centre:
//   S_u(t) x S_v(t) = n0 + t n1 + t^2 n2 + ...,   n0 = S_u x S_v,
//   n1 = S_u' x S_v + S_u x S_v',   n2 = S_u' x S_v' (exact where S_u = S_v = 0),
//   S_u' = a S_uu + b S_uv,   S_v' = a S_uv + b S_vv;
// the first term that does not vanish gives the direction (at a sphere's pole, S_u = 0 and n1 is
// b S_uv x S_v). Failing those, the normal a little way inside, then the direction to p.
Vec3 SurfaceProjector::unit_normal(const SurfaceParameter& where, const SurfaceDerivatives& d, const Vec3& p) const {
  const auto k = static_cast<std::size_t>(where.patch);
  const double threshold = kDegenerateNormal * cells_[k].normal_scale;
  const Vec3 n0 = cross(d.du, d.dv);
  if (norm(n0) > threshold) return n0 / norm(n0);
  const ParameterRectangle& r = patches_[k].domain;
  double a = 0.5 * (r.u_first + r.u_last) - where.u;
  double b = 0.5 * (r.v_first + r.v_last) - where.v;
  if (a == 0.0 && b == 0.0) a = r.u_last - r.u_first;
  const Vec3 su = a * d.duu + b * d.duv;
  const Vec3 sv = a * d.duv + b * d.dvv;
  const Vec3 n1 = cross(su, d.dv) + cross(d.du, sv);
  const double n1_scale = norm(su) * norm(d.dv) + norm(d.du) * norm(sv);
  if (norm(n1) > kDegenerateNormal * n1_scale && norm(n1) > 0.0) return n1 / norm(n1);
  const Vec3 n2 = cross(su, sv);
  if (norm(n2) > 0.0 && is_finite(n2)) return n2 / norm(n2);
  const SurfaceDerivatives near = evaluate(where.patch, where.u + 1e-6 * a, where.v + 1e-6 * b);
  const Vec3 n3 = cross(near.du, near.dv);
  if (norm(n3) > 0.0 && is_finite(n3)) return n3 / norm(n3);
  const double length = distance(p, d.point);
  return length > 0.0 ? (p - d.point) / length : Vec3{0.0, 0.0, 1.0};
}

SurfaceProjection SurfaceProjector::finish(const Vec3& p, const Local& local) const {
  SurfaceProjection result;
  result.point = local.value.point;
  result.where = local.where;
  result.distance = distance(p, local.value.point);
  result.on_boundary = local.on_rim || on_boundary(local.where, local.value);
  result.iterations = local.iterations;
  // On a trimming loop, p off it: the direction to p, the distance's gradient there (as at a
  // corner of a curve: the surface's normal would let a node slide on over the loop).
  result.normal = local.on_rim && result.distance > tolerance_ ? (p - result.point) / result.distance
                                                               : unit_normal(local.where, local.value, p);
  return result;
}

SurfaceProjection SurfaceProjector::project(const Vec3& p, const SurfaceParameter& hint) const {
  if (!is_finite(p)) {
    SurfaceProjection none;
    none.distance = std::numeric_limits<double>::quiet_NaN();
    return none;
  }
  const bool warm = hint.patch >= 0 && static_cast<std::size_t>(hint.patch) < patches_.size() &&
                    std::isfinite(hint.u) && std::isfinite(hint.v);
  // Newton from sub-patches over a hole lands at one minimum outside it, again and again.
  RimCache rim;
  if (!warm) return finish(p, global_search(p, {}, nullptr, rim));
  const Local local = newton(p, hint.patch, hint.u, hint.v, &rim);
  if (!verify_ && local.converged && !local.on_rim && !on_boundary(local.where, local.value)) {
    SurfaceProjection result = finish(p, local);
    result.from_hint = true;
    return result;
  }
  // A nearer point may lie on another patch (near a shared edge or a concave corner) or on a
  // fold of the same one: a global search with the warm result as the distance to beat visits
  // only the sub-patches that could hold one.
  const Local best = global_search(p, hint, &local, rim);
  SurfaceProjection result = finish(p, best);
  result.from_hint = best.where.patch == local.where.patch && best.where.u == local.where.u &&
                     best.where.v == local.where.v;
  return result;
}

SurfaceProjection SurfaceProjector::at(const SurfaceParameter& where) const {
  const std::size_t k = std::min(static_cast<std::size_t>(std::max(where.patch, 0)), patches_.size() - 1);
  const ParameterRectangle& r = patches_[k].domain;
  const SurfaceParameter clamped{static_cast<int>(k), std::clamp(where.u, r.u_first, r.u_last),
                                 std::clamp(where.v, r.v_first, r.v_last)};
  const SurfaceDerivatives d = evaluate(clamped.patch, clamped.u, clamped.v);
  return finish(d.point, {clamped, d, 0.0, 0, true});
}

}  // namespace hotmesh::geometry