// hotmesh geometry (internal): deflection fields joined along edges that cross a face's
// parameter rectangle (trace_joins.hpp).
#include "trace_joins.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "bspline_basis.hpp"
#include "cad_face_set.hpp"

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

double traced_gap(const std::vector<BSplineSurface>& fields, const TracedEdge& edge) {
  double gap = 0.0;
  for (std::size_t k = 0; k < edge.points.size(); ++k) {
    gap = std::max(gap, distance(fields[edge.a].point(edge.on_a[k][0], edge.on_a[k][1]),
                                 fields[edge.b].point(edge.on_b[k][0], edge.on_b[k][1])));
  }
  return gap;
}

}  // namespace hotmesh::geometry::detail
