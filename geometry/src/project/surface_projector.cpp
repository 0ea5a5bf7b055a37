// hotmesh geometry: closest points on parametric surface patches (see surface_projector.hpp):
// sub-patch sampling with a deviation bound, a bounding-volume tree over the sub-patches, and
// box-constrained Newton with the full Hessian on each patch.
// Why not CGAL's AABB tree: its primitives are fixed triangles or segments and its queries return
// the one closest primitive; here a query wants every sub-patch whose lower bound (distance to its
// triangles minus its deviation) beats the best distance found so far, and runs Newton from it,
// so the pruning bound changes during the traversal. A small tree of our own does that directly.
#include "hotmesh/geometry/surface_projector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace hotmesh::geometry {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Second derivatives are sampled at a sub-patch's corners and centre; their maxima times this
/// stand for the maxima over the sub-patch in its deviation bound.
constexpr double kDerivativeSafety = 2.0;
/// Cell bounds are sampled: maxima are used times kMaximumSafety, minima times kMinimumSafety.
constexpr double kMaximumSafety = 1.25;
constexpr double kMinimumSafety = 0.8;
/// Sub-patch refinement stops after this many halvings of a patch's initial cell (at most 4096
/// sub-patches per cell; beyond it sub-patches keep their larger deviation, pruning less).
constexpr int kMaxSplitDepth = 12;
/// Sub-patches per tree leaf.
constexpr std::uint32_t kLeafSize = 2;
/// A normal |S_u x S_v| below this times the patch's largest |S_u| |S_v| vanishes.
constexpr double kDegenerateNormal = 1e-8;
/// Newton steps shorter than this (relative to the scale) skip the descent check: f is flat to
/// rounding there and the quadratic model is good.
constexpr double kLocalStep = 1e-7;
/// After a full Newton step (Hessian, no bound hit) shorter than this (relative to the scale),
/// Newton stops: quadratic convergence puts the next step below rounding.
constexpr double kFinalStep = 1e-8;
/// The Hessian is used where it is positive definite with this margin against J^T J.
constexpr double kDefiniteMargin = 1e-3;
/// Distances within this (relative to the scale) are tied.
constexpr double kTie = 1e-10;
/// A point this close to an edge of its rectangle (relative to the scale) is on it.
constexpr double kBoundary = 1e-10;
/// Minima found during one global search that later sub-patches are checked against.
constexpr int kRememberedMinima = 8;

double squared(const Vec3& v) { return dot(v, v); }

Vec3 min(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 max(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

double box_squared_distance(const Vec3& lo, const Vec3& hi, const Vec3& p) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
    sum += d * d;
  }
  return sum;
}

bool finite(const SurfaceDerivatives& d) {
  return is_finite(d.point) && is_finite(d.du) && is_finite(d.dv) && is_finite(d.duu) && is_finite(d.duv) &&
         is_finite(d.dvv);
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

/// Grid lines of one direction of a patch: the breaks inside [first, last] and both ends, each
/// interval split evenly so that there are at least `grid` intervals in all.
std::vector<double> grid_lines(double first, double last, const std::vector<double>& breaks, int grid) {
  std::vector<double> ends{first};
  for (const double t : breaks) {
    if (t > ends.back() && t < last) ends.push_back(t);
  }
  ends.push_back(last);
  const auto intervals = static_cast<int>(ends.size()) - 1;
  const int splits = std::max(1, (grid + intervals - 1) / intervals);
  std::vector<double> lines;
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
    for (int k = 0; k < splits; ++k) lines.push_back(ends[i] + (ends[i + 1] - ends[i]) * k / splits);
  }
  lines.push_back(last);
  return lines;
}

bool same_rectangle(const ParameterRectangle& a, const ParameterRectangle& b) {
  const double du = 1e-12 * (std::abs(a.u_first) + std::abs(a.u_last) + (a.u_last - a.u_first));
  const double dv = 1e-12 * (std::abs(a.v_first) + std::abs(a.v_last) + (a.v_last - a.v_first));
  return std::abs(a.u_first - b.u_first) <= du && std::abs(a.u_last - b.u_last) <= du &&
         std::abs(a.v_first - b.v_first) <= dv && std::abs(a.v_last - b.v_last) <= dv;
}

const char* edge_name(PatchEdge edge) {
  switch (edge) {
    case PatchEdge::u_first: return "u = u_first";
    case PatchEdge::u_last: return "u = u_last";
    case PatchEdge::v_first: return "v = v_first";
    case PatchEdge::v_last: return "v = v_last";
  }
  return "?";
}

/// A symmetric 2x2 matrix [uu uv; uv vv].
struct Sym2 {
  double uu;
  double uv;
  double vv;
};

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

/// The smaller eigenvalue of the symmetric 2x2 matrix m.
double smaller_eigenvalue(const Sym2& m) {
  const double half_trace = 0.5 * (m.uu + m.vv);
  const double half_gap = 0.5 * (m.uu - m.vv);
  return half_trace - std::sqrt(half_gap * half_gap + m.uv * m.uv);
}

}  // namespace

SurfacePatch bspline_patch(BSplineSurface surface) {
  auto shared = std::make_shared<const BSplineSurface>(std::move(surface));
  SurfacePatch patch;
  patch.domain = shared->domain();
  patch.u_breaks = shared->u_breakpoints();
  patch.v_breaks = shared->v_breakpoints();
  patch.evaluate = [shared](double u, double v) { return shared->derivatives(u, v); };
  return patch;
}

SurfacePatch displaced_patch(BSplineSurface surface, BSplineSurface displacement, double scale) {
  if (!same_rectangle(surface.domain(), displacement.domain())) {
    throw std::invalid_argument("displaced patch: the displacement field's parameter rectangle differs from the face's");
  }
  if (!std::isfinite(scale)) throw std::invalid_argument("displaced patch: the scale must be finite");
  auto s = std::make_shared<const BSplineSurface>(std::move(surface));
  auto d = std::make_shared<const BSplineSurface>(std::move(displacement));
  SurfacePatch patch;
  patch.domain = s->domain();
  patch.u_breaks = s->u_breakpoints();
  patch.v_breaks = s->v_breakpoints();
  const std::vector<double> du = d->u_breakpoints();
  const std::vector<double> dv = d->v_breakpoints();
  patch.u_breaks.insert(patch.u_breaks.end(), du.begin(), du.end());
  patch.v_breaks.insert(patch.v_breaks.end(), dv.begin(), dv.end());
  std::sort(patch.u_breaks.begin(), patch.u_breaks.end());
  std::sort(patch.v_breaks.begin(), patch.v_breaks.end());
  patch.evaluate = [s, d, scale](double u, double v) { return s->derivatives(u, v) + scale * d->derivatives(u, v); };
  return patch;
}

std::string DegeneracyReport::describe() const {
  std::ostringstream out;
  for (const Edge& e : edges) {
    out << "patch " << e.patch << ": the normal vanishes along the edge " << edge_name(e.edge)
        << (e.collapsed ? " (collapsed to one point: a pole)" : "") << "\n";
  }
  for (const SurfaceParameter& p : points) {
    out << "patch " << p.patch << ": the normal vanishes inside at (u, v) = (" << p.u << ", " << p.v << ")\n";
  }
  return out.str();
}

// ---- set-up -------------------------------------------------------------------------------

struct SurfaceProjector::Grid {
  std::vector<double> us;
  std::vector<double> vs;
  std::vector<SurfaceDerivatives> values;  // values[i * vs.size() + j] at (us[i], vs[j])
  const SurfaceDerivatives& at(std::size_t i, std::size_t j) const { return values[i * vs.size() + j]; }
};

SurfaceProjector::SurfaceProjector(std::vector<SurfacePatch> patches, const SurfaceProjectorOptions& options)
    : patches_(std::move(patches)), max_iterations_(std::max(1, options.max_iterations)),
      verify_(options.verify_warm_starts) {
  if (patches_.empty()) throw std::invalid_argument("surface projector: no patch");
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    const SurfacePatch& patch = patches_[i];
    const ParameterRectangle& r = patch.domain;
    if (!patch.evaluate) throw std::invalid_argument("surface projector: patch " + std::to_string(i) + " has no evaluator");
    if (!(std::isfinite(r.u_first) && std::isfinite(r.u_last) && std::isfinite(r.v_first) &&
          std::isfinite(r.v_last) && r.u_first < r.u_last && r.v_first < r.v_last)) {
      throw std::invalid_argument("surface projector: patch " + std::to_string(i) +
                                  " has an empty or non-finite parameter rectangle");
    }
  }
  if (patches_.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument("surface projector: too many patches");
  }
  sample(options);
  // Sub-patches wholly outside a trimmed patch's loops, where a binding loop holds nodes in,
  // hold no point it answers: left out of the search.
  std::erase_if(subs_, [this](const SubPatch& sub) {
    const TrimRegion* region = patches_[static_cast<std::size_t>(sub.patch)].region.get();
    return region != nullptr && region->excludes(sub.rect);
  });
  build_tree();
  sample_rims();
  tolerance_ = options.tolerance * scale_;
  tie_ = kTie * scale_;
}

SurfaceDerivatives SurfaceProjector::evaluate(int patch, double u, double v) const {
  return patches_[static_cast<std::size_t>(patch)].evaluate(u, v);
}

void SurfaceProjector::sample(const SurfaceProjectorOptions& options) {
  // 1. Each patch on its initial grid; the length scale from all samples.
  std::vector<Grid> grids(patches_.size());
  Vec3 lo{kInfinity, kInfinity, kInfinity};
  Vec3 hi = -lo;
  cells_.assign(patches_.size(), Cells{});
  for (std::size_t k = 0; k < patches_.size(); ++k) {
    const SurfacePatch& patch = patches_[k];
    Grid& grid = grids[k];
    const int n = std::max(1, options.initial_grid);
    grid.us = grid_lines(patch.domain.u_first, patch.domain.u_last, patch.u_breaks, n);
    grid.vs = grid_lines(patch.domain.v_first, patch.domain.v_last, patch.v_breaks, n);
    for (const double u : grid.us) {
      for (const double v : grid.vs) {
        const SurfaceDerivatives d = patch.evaluate(u, v);
        if (!finite(d)) {
          std::ostringstream message;
          message << "surface projector: patch " << k << " does not evaluate to finite values at (u, v) = (" << u
                  << ", " << v << ")";
          throw std::invalid_argument(message.str());
        }
        grid.values.push_back(d);
        lo = min(lo, d.point);
        hi = max(hi, d.point);
      }
    }
  }
  scale_ = norm(hi - lo);
  if (!(scale_ > 0.0)) scale_ = std::max({1.0, std::abs(lo.x), std::abs(lo.y), std::abs(lo.z)});
  target_ = options.sampling_deviation * scale_;

  // 2. Every grid cell refined into sub-patches within the target deviation.
  subs_.clear();
  for (std::size_t k = 0; k < patches_.size(); ++k) {
    const Grid& grid = grids[k];
    Cells& cells = cells_[k];
    cells.us = grid.us;
    cells.vs = grid.vs;
    const std::size_t nv = grid.vs.size() - 1;
    cells.bounds.assign((grid.us.size() - 1) * nv, CellBounds{0.0, 0.0, 0.0, kInfinity});
    for (std::size_t i = 0; i + 1 < grid.us.size(); ++i) {
      for (std::size_t j = 0; j < nv; ++j) {
        refine(static_cast<int>(k), i * nv + j, {grid.us[i], grid.us[i + 1], grid.vs[j], grid.vs[j + 1]},
               {grid.at(i, j), grid.at(i + 1, j), grid.at(i, j + 1), grid.at(i + 1, j + 1)}, 0);
      }
    }
  }
  report_degeneracies(grids);
}

// Deviation of a sub-patch from the two triangles through its corners. Linear interpolation on a
// triangle with vertices x_i (barycentric lambda_i at x) leaves, by Taylor expansion about x,
//   e(x) = 1/2 sum_i lambda_i D2S(xi_i)[x_i - x, x_i - x],
// and with |S_uu| <= M_uu, |S_uv| <= M_uv, |S_vv| <= M_vv, 2|ab| <= a^2 h_v/h_u + b^2 h_u/h_v:
//   |e| <= 1/2 sum_i lambda_i q(x_i - x),  q(a, b) = a^2 (M_uu + M_uv h_v/h_u) + b^2 (M_vv + M_uv h_u/h_v),
// a quadratic form, so the sum is the variance of the vertices, at most 1/3 of the largest
// q(x_i - x_j) <= h_u^2 M_uu + 2 h_u h_v M_uv + h_v^2 M_vv:
//   deviation = (h_u^2 M_uu + 2 h_u h_v M_uv + h_v^2 M_vv) / 6.
// Bilinear interpolation of the corners (within their box) leaves at most
// (h_u^2 M_uu + h_v^2 M_vv) / 8: the corners' box enlarged by that holds the sub-patch.
// The maxima M are those sampled at the corners and the centre, times kDerivativeSafety.
void SurfaceProjector::refine(int patch, std::size_t cell, const ParameterRectangle& rect,
                              const std::array<SurfaceDerivatives, 4>& corners, int depth) {
  const double um = 0.5 * (rect.u_first + rect.u_last);
  const double vm = 0.5 * (rect.v_first + rect.v_last);
  const SurfaceDerivatives centre = evaluate(patch, um, vm);
  note(patch, cell, centre);
  for (const SurfaceDerivatives& c : corners) note(patch, cell, c);
  double m_uu = norm(centre.duu);
  double m_uv = norm(centre.duv);
  double m_vv = norm(centre.dvv);
  for (const SurfaceDerivatives& c : corners) {
    m_uu = std::max(m_uu, norm(c.duu));
    m_uv = std::max(m_uv, norm(c.duv));
    m_vv = std::max(m_vv, norm(c.dvv));
  }
  m_uu *= kDerivativeSafety, m_uv *= kDerivativeSafety, m_vv *= kDerivativeSafety;
  const double hu = rect.u_last - rect.u_first;
  const double hv = rect.v_last - rect.v_first;
  const double along_u = hu * hu * m_uu + hu * hv * m_uv;
  const double along_v = hv * hv * m_vv + hu * hv * m_uv;
  const double deviation = (along_u + along_v) / 6.0;
  if (!std::isfinite(deviation)) {
    throw std::invalid_argument("surface projector: patch " + std::to_string(patch) +
                                " has non-finite derivatives inside its rectangle");
  }
  if (deviation > target_ && depth < kMaxSplitDepth) {
    const auto& [c00, c10, c01, c11] = corners;
    if (along_u >= along_v) {  // halve in u
      const SurfaceDerivatives b = evaluate(patch, um, rect.v_first);
      const SurfaceDerivatives t = evaluate(patch, um, rect.v_last);
      refine(patch, cell, {rect.u_first, um, rect.v_first, rect.v_last}, {c00, b, c01, t}, depth + 1);
      refine(patch, cell, {um, rect.u_last, rect.v_first, rect.v_last}, {b, c10, t, c11}, depth + 1);
    } else {  // halve in v
      const SurfaceDerivatives l = evaluate(patch, rect.u_first, vm);
      const SurfaceDerivatives r = evaluate(patch, rect.u_last, vm);
      refine(patch, cell, {rect.u_first, rect.u_last, rect.v_first, vm}, {c00, c10, l, r}, depth + 1);
      refine(patch, cell, {rect.u_first, rect.u_last, vm, rect.v_last}, {l, r, c01, c11}, depth + 1);
    }
    return;
  }
  SubPatch sub{{corners[0].point, corners[1].point, corners[2].point, corners[3].point}, rect, deviation, {}, patch};
  const double enlarge = (hu * hu * m_uu + hv * hv * m_vv) / 8.0 + 1e-12 * scale_;
  sub.box = {sub.corner[0], sub.corner[0]};
  for (const Vec3& c : sub.corner) sub.box = {min(sub.box.lo, c), max(sub.box.hi, c)};
  sub.box.lo -= Vec3{enlarge, enlarge, enlarge};
  sub.box.hi += Vec3{enlarge, enlarge, enlarge};
  subs_.push_back(sub);
}

void SurfaceProjector::note(int patch, std::size_t cell, const SurfaceDerivatives& d) {
  Cells& cells = cells_[static_cast<std::size_t>(patch)];
  cells.normal_scale = std::max(cells.normal_scale, norm(d.du) * norm(d.dv));
  CellBounds& b = cells.bounds[cell];
  b.du = std::max(b.du, norm(d.du));
  b.dv = std::max(b.dv, norm(d.dv));
  const Vec3 normal = cross(d.du, d.dv);
  const double length = norm(normal);
  if (length > 0.0) {
    const Vec3 n = normal / length;
    b.bending = std::max(b.bending, std::max(std::abs(dot(n, d.duu)), std::abs(dot(n, d.dvv))) + std::abs(dot(n, d.duv)));
  }
  b.metric = std::min(b.metric, smaller_eigenvalue({dot(d.du, d.du), dot(d.du, d.dv), dot(d.dv, d.dv)}));
}

// An edge whose every initial-grid sample has a vanishing normal is reported (and collapsed if
// all its samples coincide); so are interior samples with a vanishing normal.
void SurfaceProjector::report_degeneracies(const std::vector<Grid>& grids) {
  report_ = {};
  for (std::size_t k = 0; k < grids.size(); ++k) {
    const Grid& g = grids[k];
    const auto patch = static_cast<int>(k);
    const double threshold = kDegenerateNormal * cells_[k].normal_scale;
    const auto degenerate = [&](const SurfaceDerivatives& d) { return norm(cross(d.du, d.dv)) <= threshold; };
    const std::size_t nu = g.us.size();
    const std::size_t nv = g.vs.size();
    const auto check_edge = [&](PatchEdge edge, bool along_u, std::size_t fixed) {
      const std::size_t count = along_u ? nu : nv;
      bool all = true;
      bool collapsed = true;
      const Vec3 first = along_u ? g.at(0, fixed).point : g.at(fixed, 0).point;
      for (std::size_t i = 0; i < count; ++i) {
        const SurfaceDerivatives& d = along_u ? g.at(i, fixed) : g.at(fixed, i);
        all = all && degenerate(d);
        collapsed = collapsed && distance(d.point, first) <= 1e-9 * scale_;
      }
      if (all) report_.edges.push_back({patch, edge, collapsed});
    };
    check_edge(PatchEdge::u_first, false, 0);
    check_edge(PatchEdge::u_last, false, nu - 1);
    check_edge(PatchEdge::v_first, true, 0);
    check_edge(PatchEdge::v_last, true, nv - 1);
    for (std::size_t i = 1; i + 1 < nu; ++i) {
      for (std::size_t j = 1; j + 1 < nv; ++j) {
        if (degenerate(g.at(i, j))) report_.points.push_back({patch, g.us[i], g.vs[j]});
      }
    }
  }
}

void SurfaceProjector::build_tree() {
  if (subs_.size() >= std::numeric_limits<std::uint32_t>::max() / 2) {
    throw std::invalid_argument("surface projector: too many sub-patches");
  }
  std::vector<std::uint32_t> order(subs_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  tree_.assign(1, Node{});
  tree_.reserve(2 * subs_.size() / kLeafSize + 2);
  build_node(order, 0, static_cast<std::uint32_t>(order.size()), 0);
  // Sub-patches in tree order, so that every leaf holds a contiguous range.
  std::vector<SubPatch> sorted;
  sorted.reserve(subs_.size());
  for (const std::uint32_t i : order) sorted.push_back(subs_[i]);
  subs_ = std::move(sorted);
}

// Top-down: a node's sub-patches are split at the median of their box centres along the longest
// axis of the centres' extent; the two children take the next two free slots.
void SurfaceProjector::build_node(std::vector<std::uint32_t>& order, std::uint32_t first, std::uint32_t count,
                                  std::uint32_t index) {
  Box box = subs_[order[first]].box;
  Vec3 centre_lo = 0.5 * (box.lo + box.hi);
  Vec3 centre_hi = centre_lo;
  for (std::uint32_t i = first; i < first + count; ++i) {
    const Box& b = subs_[order[i]].box;
    box = {min(box.lo, b.lo), max(box.hi, b.hi)};
    const Vec3 c = 0.5 * (b.lo + b.hi);
    centre_lo = min(centre_lo, c);
    centre_hi = max(centre_hi, c);
  }
  if (count <= kLeafSize) {
    tree_[index] = {box, first, count};
    return;
  }
  const Vec3 extent = centre_hi - centre_lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t half = count / 2;
  const auto begin = order.begin() + static_cast<std::ptrdiff_t>(first);
  std::nth_element(begin, begin + static_cast<std::ptrdiff_t>(half), begin + static_cast<std::ptrdiff_t>(count), [&](std::uint32_t a, std::uint32_t b) {
    return subs_[a].box.lo[axis] + subs_[a].box.hi[axis] < subs_[b].box.lo[axis] + subs_[b].box.hi[axis];
  });
  const auto children = static_cast<std::uint32_t>(tree_.size());
  tree_.push_back({});
  tree_.push_back({});
  tree_[index] = {box, children, 0};
  build_node(order, first, half, children);
  build_node(order, first + half, count - half, children + 1);
}

// ---- queries ------------------------------------------------------------------------------

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
