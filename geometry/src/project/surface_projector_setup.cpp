// hotmesh geometry: the surface projector's set-up (surface_projector.hpp): the patches of
// B-spline and deformed faces; every patch sampled on its initial grid and refined into
// sub-patches within a deviation bound, with the derivative bounds of each grid cell and the
// report of where the normal vanishes; the bounding-volume tree over the sub-patches. The
// queries are surface_projector.cpp.
#include "hotmesh/geometry/surface_projector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "project/surface_projector_detail.hpp"

namespace hotmesh::geometry {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Second derivatives are sampled at a sub-patch's corners and centre; their maxima times this
/// stand for the maxima over the sub-patch in its deviation bound.
constexpr double kDerivativeSafety = 2.0;
/// Sub-patch refinement stops after this many halvings of a patch's initial cell (at most 4096
/// sub-patches per cell; beyond it sub-patches keep their larger deviation, pruning less).
constexpr int kMaxSplitDepth = 12;
/// Sub-patches per tree leaf.
constexpr std::uint32_t kLeafSize = 2;
/// Distances within this (relative to the scale) are tied.
constexpr double kTie = 1e-10;

Vec3 min(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 max(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

bool finite(const SurfaceDerivatives& d) {
  return is_finite(d.point) && is_finite(d.du) && is_finite(d.dv) && is_finite(d.duu) && is_finite(d.duv) &&
         is_finite(d.dvv);
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

/// The smaller eigenvalue of the symmetric 2x2 matrix m.
double smaller_eigenvalue(const detail::Sym2& m) {
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
    const double threshold = detail::kDegenerateNormal * cells_[k].normal_scale;
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

}  // namespace hotmesh::geometry
