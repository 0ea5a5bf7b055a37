// hotmesh geometry (internal): deflection fields joined along edges that cross a face's
// parameter rectangle (trace_joins.hpp).
#include "reconstruct/trace_joins.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "hotmesh/geometry/trim_region.hpp"
#include "reconstruct/cad_face_set.hpp"
#include "spline/bspline_basis.hpp"

namespace hotmesh::geometry::detail {
namespace {

/// The parameters of `points` on the face of `projector`, each search started from the last
/// point's; false if a point is farther than `tolerance` from it.
bool project_points(const SurfaceProjector& projector, std::span<const Vec3> points, double tolerance,
                    std::vector<std::array<double, 2>>& out) {
  SurfaceParameter hint;
  for (const Vec3& p : points) {
    const SurfaceProjection q = projector.project(p, hint);
    if (!(q.distance <= tolerance)) return false;
    out.push_back({q.where.u, q.where.v});
    hint = q.where;
  }
  return true;
}

bool along_u(int side) { return side < 2; }

/// The poles a side may grow to while its spans are halved: this many times those it was
/// fitted with, and at least kMinPolesAlong.
constexpr std::size_t kMaxPolesAlong = 16;
constexpr std::size_t kMinPolesAlong = 256;

/// The knots of a field along its side.
const std::vector<double>& side_knots(const BSplineSurface& f, int side) {
  return along_u(side) ? f.u_knots() : f.v_knots();
}
int side_degree(const BSplineSurface& f, int side) { return along_u(side) ? f.u_degree() : f.v_degree(); }

/// Where the fields of a side-on-face edge are compared and fitted: 8 points per knot span of
/// a's side and its last point, as the parameter x along the side.
std::vector<double> side_points(const BSplineSurface& a, int side) {
  constexpr int kPerSpan = 8;
  const std::vector<double>& knots = side_knots(a, side);
  const auto p = static_cast<std::size_t>(side_degree(a, side));
  std::vector<double> out;
  for (std::size_t i = p; i + p + 1 < knots.size(); ++i) {
    if (knots[i + 1] <= knots[i]) continue;
    for (int k = 0; k < kPerSpan; ++k) out.push_back(knots[i] + (knots[i + 1] - knots[i]) * k / kPerSpan);
  }
  out.push_back(knots[knots.size() - p - 1]);
  return out;
}

/// The point of a face's rectangle at parameter x along its side.
std::array<double, 2> on_side_at(const BSplineSurface& f, int side, double x) {
  const ParameterRectangle r = f.domain();
  if (along_u(side)) return {x, side == 0 ? r.v_first : r.v_last};
  return {side == 2 ? r.u_first : r.u_last, x};
}

/// Whether side `side` of face a has a corner pole that a frozen side of a shares.
bool corners_frozen(std::size_t a, int side, std::span<const FaceSide> frozen) {
  return std::any_of(frozen.begin(), frozen.end(), [&](const FaceSide& s) {
    return s.face == a && along_u(s.side) != along_u(side);  // the sides across its ends
  });
}

/// The smoothness penalty of a correction against its fit at the edge's points: small, so the
/// fit rules where the points decide the poles and the penalty only where they do not (the
/// poles beside the edge), which a plain least-change correction leaves spiky. On a fence
/// trimming a plate (TraceJoins.AFootThatTrimsBothFacesIsJoined), 1e-6 stalls at a gap of 2e-8
/// (the penalty holds the fit back), 1e-10 meets 1e-10 of the size after 3 halvings, and
/// smaller ones let the correction swing more at the nodes beside the edge.
constexpr double kSmoothness = 1e-10;

/// `field` plus a correction that adds change[k] at at[k] (least squares) and is smoothest
/// where they leave it free: the thin-plate energy of the correction's poles over the pole grid
/// (second differences along u and v, twice the mixed ones) as a kSmoothness penalty. Only the
/// poles that act at the points and a ring around them change (the ring lets the correction
/// fade out smoothly), not those of `frozen` sides (v first, v last, u first, u last).
BSplineSurface corrected(const BSplineSurface& field, std::span<const Vec2> at, std::span<const Vec3> change,
                         const std::array<bool, 4>& frozen) {
  const std::size_t nu = field.u_count(), nv = field.v_count();
  const int p = field.u_degree(), q = field.v_degree();
  const auto index = [nv](std::size_t i, std::size_t j) { return i * nv + j; };
  // The basis functions at each point: (pole, value).
  std::vector<std::vector<std::pair<std::size_t, double>>> rows(at.size());
  std::vector<char> acting(nu * nv, 0);
  for (std::size_t k = 0; k < at.size(); ++k) {
    const std::size_t su = find_span(field.u_knots(), p, nu, at[k].x);
    const std::size_t sv = find_span(field.v_knots(), q, nv, at[k].y);
    BasisDerivatives bu{}, bv{};
    basis_derivatives(field.u_knots(), p, su, at[k].x, 0, bu);
    basis_derivatives(field.v_knots(), q, sv, at[k].y, 0, bv);
    for (int a = 0; a <= p; ++a) {
      for (int b = 0; b <= q; ++b) {
        const std::size_t pole = index(su - static_cast<std::size_t>(p - a), sv - static_cast<std::size_t>(q - b));
        rows[k].emplace_back(pole, bu[0][static_cast<std::size_t>(a)] * bv[0][static_cast<std::size_t>(b)]);
        acting[pole] = 1;
      }
    }
  }
  std::vector<int> unknown(nu * nv, -1);
  int count = 0;
  for (std::size_t i = 0; i < nu; ++i) {
    for (std::size_t j = 0; j < nv; ++j) {
      if ((frozen[0] && j == 0) || (frozen[1] && j + 1 == nv) || (frozen[2] && i == 0) || (frozen[3] && i + 1 == nu)) continue;
      bool near = false;
      for (std::size_t a = i > 0 ? i - 1 : 0; a <= std::min(i + 1, nu - 1) && !near; ++a) {
        for (std::size_t b = j > 0 ? j - 1 : 0; b <= std::min(j + 1, nv - 1) && !near; ++b) near = acting[index(a, b)] != 0;
      }
      if (near) unknown[index(i, j)] = count++;
    }
  }
  if (count == 0) return field;
  // Normal equations of the fit and the penalty, a tiny multiple of the identity against round-off.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(count, 3);
  const auto add_row = [&](const std::vector<std::pair<std::size_t, double>>& row, double weight, const Vec3* value) {
    for (const auto& [pa, wa] : row) {
      const int ua = unknown[pa];
      if (ua < 0) continue;
      for (const auto& [pb, wb] : row) {
        if (unknown[pb] >= 0) entries.emplace_back(ua, unknown[pb], weight * wa * wb);
      }
      if (value != nullptr) {
        rhs(ua, 0) += weight * wa * value->x, rhs(ua, 1) += weight * wa * value->y, rhs(ua, 2) += weight * wa * value->z;
      }
    }
  };
  for (std::size_t k = 0; k < at.size(); ++k) add_row(rows[k], 1.0, &change[k]);
  for (std::size_t i = 0; i < nu; ++i) {
    for (std::size_t j = 0; j < nv; ++j) {
      if (i + 2 < nu) add_row({{index(i, j), 1.0}, {index(i + 1, j), -2.0}, {index(i + 2, j), 1.0}}, kSmoothness, nullptr);
      if (j + 2 < nv) add_row({{index(i, j), 1.0}, {index(i, j + 1), -2.0}, {index(i, j + 2), 1.0}}, kSmoothness, nullptr);
      if (i + 1 < nu && j + 1 < nv) {
        add_row({{index(i, j), 1.0}, {index(i + 1, j), -1.0}, {index(i, j + 1), -1.0}, {index(i + 1, j + 1), 1.0}},
                2.0 * kSmoothness, nullptr);
      }
    }
  }
  for (int u = 0; u < count; ++u) entries.emplace_back(u, u, 1e-6 * kSmoothness);
  Eigen::SparseMatrix<double> normal(count, count);
  normal.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return field;
  const Eigen::MatrixXd delta = ldlt.solve(rhs);
  std::vector<Vec3> poles = field.poles();
  for (std::size_t k = 0; k < poles.size(); ++k) {
    if (const int u = unknown[k]; u >= 0) poles[k] = poles[k] + Vec3{delta(u, 0), delta(u, 1), delta(u, 2)};
  }
  return BSplineSurface(p, q, field.u_knots(), field.v_knots(), std::move(poles));
}

/// Halves the knot spans of `field` that hold the points, in both directions; false if none.
bool halve_spans_at(BSplineSurface& field, std::span<const Vec2> at) {
  std::set<double> u_middles, v_middles;
  for (const Vec2& x : at) {
    const std::size_t su = find_span(field.u_knots(), field.u_degree(), field.u_count(), x.x);
    const std::size_t sv = find_span(field.v_knots(), field.v_degree(), field.v_count(), x.y);
    u_middles.insert(0.5 * (field.u_knots()[su] + field.u_knots()[su + 1]));
    v_middles.insert(0.5 * (field.v_knots()[sv] + field.v_knots()[sv + 1]));
  }
  bool inserted = false;
  for (const double u : u_middles) inserted |= insert_knot(field, true, u);
  for (const double v : v_middles) inserted |= insert_knot(field, false, v);
  return inserted;
}

}  // namespace

int side_holding(const BSplineSurface& face, std::span<const std::array<double, 2>> params) {
  const ParameterRectangle r = face.domain();
  const double du = 1e-9 * (r.u_last - r.u_first), dv = 1e-9 * (r.v_last - r.v_first);
  const std::array<std::pair<int, double>, 4> fixed{{{1, r.v_first}, {1, r.v_last}, {0, r.u_first}, {0, r.u_last}}};
  for (int side = 0; side < 4; ++side) {
    const int c = fixed[static_cast<std::size_t>(side)].first;  // no structured binding: the lambda captures it
    const double value = fixed[static_cast<std::size_t>(side)].second;
    const double slack = c == 0 ? du : dv;
    const bool on = std::all_of(params.begin(), params.end(), [&](const auto& p) {
      return std::abs(p[static_cast<std::size_t>(c)] - value) <= slack;
    });
    if (on) return side;
  }
  return -1;
}

std::vector<TracedEdge> crossing_edges(std::span<const CadFace> faces, std::span<const SurfaceProjector> projectors,
                                       double tolerance) {
  std::map<int, std::vector<std::pair<std::size_t, const FaceEdge*>>> named;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (const FaceEdge& e : faces[f].edges) named[e.edge].emplace_back(f, &e);
  }
  std::vector<TracedEdge> out;
  for (const auto& entry : named) {
    const auto& on = entry.second;  // no structured binding: the lambda captures it
    const auto other = std::find_if(on.begin(), on.end(), [&](const auto& x) { return x.first != on.front().first; });
    if (other == on.end()) continue;
    TracedEdge edge{on.front().first, other->first, {}, {}, on.front().second->points};
    if (!project_points(projectors[edge.a], edge.points, tolerance, edge.on_a) ||
        !project_points(projectors[edge.b], edge.points, tolerance, edge.on_b)) {
      continue;
    }
    if (side_holding(faces[edge.a].surface, edge.on_a) >= 0 && side_holding(faces[edge.b].surface, edge.on_b) >= 0) {
      continue;
    }
    out.push_back(std::move(edge));
  }
  return out;
}

std::vector<double> join_sides_to_faces(std::vector<BSplineSurface>& fields, std::span<const CadFace> faces,
                                        std::span<const SurfaceProjector> projectors,
                                        std::span<const SideOnFace> edges, std::span<const FaceSide> frozen,
                                        double tolerance) {
  std::vector<double> largest(edges.size(), 0.0);
  const std::vector<BSplineSurface> fitted = fields;
  const auto poles_along = [](const BSplineSurface& f, int side) { return along_u(side) ? f.u_count() : f.v_count(); };
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const SideOnFace& e = edges[k];
    BSplineSurface refined = fields[e.a];  // a's field before the fit, knots inserted
    const BSplineSurface& b = fields[e.b];
    const bool keep_corners = corners_frozen(e.a, e.side, frozen);
    // Halvings stop at kMaxHalvings, or once the side has kMaxPolesAlong times the poles it was
    // fitted with (at least kMinPolesAlong): a degree-1 field converges too slowly to pay for more.
    const std::size_t budget = std::max(kMinPolesAlong, kMaxPolesAlong * poles_along(fitted[e.a], e.side));
    for (int halvings = 0;; ++halvings) {
      largest[k] = 0.0;
      // b's parameters at the side's points, then a's row fitted to b's field there.
      std::vector<double> xs = side_points(refined, e.side);
      std::vector<SideTarget> targets;
      std::vector<std::array<double, 2>> on_b;
      SurfaceParameter hint;
      for (const double x : xs) {
        const auto [t, s] = on_side_at(refined, e.side, x);
        const SurfaceProjection q = projectors[e.b].project(faces[e.a].surface.point(t, s), hint);
        hint = q.where;
        on_b.push_back({q.where.u, q.where.v});
        targets.push_back({x, b.point(q.where.u, q.where.v) - refined.point(t, s)});
      }
      BSplineSurface joined = refined;
      fit_side_row(joined, e.side, targets, keep_corners);
      std::vector<double> gaps;
      for (std::size_t i = 0; i < xs.size(); ++i) {
        const auto [t, s] = on_side_at(joined, e.side, xs[i]);
        gaps.push_back(distance(joined.point(t, s), b.point(on_b[i][0], on_b[i][1])));
        largest[k] = std::max(largest[k], gaps.back());
      }
      fields[e.a] = joined;
      if (halvings == kMaxHalvings || largest[k] <= tolerance || poles_along(refined, e.side) >= budget) break;
      // The spans where the fields differ by more than a tenth of the tolerance, halved.
      const std::vector<double>& knots = side_knots(refined, e.side);
      const int degree = side_degree(refined, e.side);
      const std::size_t count = knots.size() - static_cast<std::size_t>(degree) - 1;
      std::set<double> middles;
      for (std::size_t i = 0; i < xs.size(); ++i) {
        if (gaps[i] <= 0.1 * tolerance) continue;
        const std::size_t span = find_span(knots, degree, count, xs[i]);
        middles.insert(0.5 * (knots[span] + knots[span + 1]));
      }
      bool inserted = false;
      for (const double x : middles) inserted |= insert_knot(refined, along_u(e.side), x);
      if (!inserted) break;
    }
  }
  return largest;
}

std::vector<double> join_across_faces(std::vector<BSplineSurface>& fields, std::span<const CadFace> faces,
                                      std::span<const SurfaceProjector> projectors, std::span<const TracedEdge> edges,
                                      std::span<const FaceSide> frozen, double tolerance) {
  std::vector<double> largest(edges.size(), 0.0);
  const auto frozen_sides = [&](std::size_t face) {
    std::array<bool, 4> out{};
    for (const FaceSide& s : frozen) {
      if (s.face == face) out[static_cast<std::size_t>(s.side)] = true;
    }
    return out;
  };
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const TracedEdge& e = edges[k];
    std::vector<Vec2> trace_a, trace_b;
    for (std::size_t i = 0; i < e.points.size(); ++i) {
      trace_a.push_back({e.on_a[i][0], e.on_a[i][1]});
      trace_b.push_back({e.on_b[i][0], e.on_b[i][1]});
    }
    const std::size_t budget_a = std::max<std::size_t>(4096, 16 * fields[e.a].poles().size());
    const std::size_t budget_b = std::max<std::size_t>(4096, 16 * fields[e.b].poles().size());
    BSplineSurface refined_a = fields[e.a], refined_b = fields[e.b];  // before the correction, knots inserted
    for (int halvings = 0;; ++halvings) {
      // Points along the edge, 129 at the start and twice as many at each halving: a's
      // parameters there from its trace (a Catmull-Rom spline through the trace's points), b's
      // those of the same point of the wall (a projection started from b's trace).
      const std::size_t n = static_cast<std::size_t>(128) << halvings;
      std::vector<Vec2> at_a, at_b;
      std::vector<Vec3> to_a, to_b;
      for (std::size_t i = 0; i <= n; ++i) {
        const double x = static_cast<double>(trace_a.size() - 1) * static_cast<double>(i) / static_cast<double>(n);
        at_a.push_back(curve_point(trace_a, x));
        const Vec2 start = curve_point(trace_b, x);
        const SurfaceProjection q = projectors[e.b].project(faces[e.a].surface.point(at_a.back().x, at_a.back().y),
                                                            {0, start.x, start.y});
        at_b.push_back({q.where.u, q.where.v});
        const Vec3 half = 0.5 * (refined_b.point(at_b.back().x, at_b.back().y) - refined_a.point(at_a.back().x, at_a.back().y));
        to_a.push_back(half);
        to_b.push_back(-1.0 * half);
      }
      const BSplineSurface joined_a = corrected(refined_a, at_a, to_a, frozen_sides(e.a));
      const BSplineSurface joined_b = corrected(refined_b, at_b, to_b, frozen_sides(e.b));
      std::vector<Vec2> wide_a, wide_b;  // where the joined fields still differ
      largest[k] = 0.0;
      for (std::size_t i = 0; i < at_a.size(); ++i) {
        const double gap = distance(joined_a.point(at_a[i].x, at_a[i].y), joined_b.point(at_b[i].x, at_b[i].y));
        largest[k] = std::max(largest[k], gap);
        if (gap > 0.1 * tolerance) wide_a.push_back(at_a[i]), wide_b.push_back(at_b[i]);
      }
      fields[e.a] = joined_a;
      fields[e.b] = joined_b;
      largest[k] = std::max(largest[k], traced_gap(fields, e));
      if (halvings == kMaxHalvings || largest[k] <= tolerance || refined_a.poles().size() >= budget_a ||
          refined_b.poles().size() >= budget_b) {
        break;
      }
      const bool a_halved = halve_spans_at(refined_a, wide_a);
      const bool b_halved = halve_spans_at(refined_b, wide_b);
      if (!a_halved && !b_halved) break;
    }
  }
  return largest;
}

double traced_gap(const std::vector<BSplineSurface>& fields, const TracedEdge& edge) {
  double gap = 0.0;
  for (std::size_t k = 0; k < edge.points.size(); ++k) {
    gap = std::max(gap, distance(fields[edge.a].point(edge.on_a[k][0], edge.on_a[k][1]),
                                 fields[edge.b].point(edge.on_b[k][0], edge.on_b[k][1])));
  }
  return gap;
}

}  // namespace hotmesh::geometry::detail
