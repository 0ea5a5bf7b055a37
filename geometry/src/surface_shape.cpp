// hotmesh geometry: section 4.2 on CAD faces (FEM nodes to (face, t, s), a deflection field
// d(t, s) per face) and the shapes of 3D walls that are not surfaces of revolution.
#include "hotmesh/geometry/surface_shape.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <shared_mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "field_joins.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "node_list.hpp"

namespace hotmesh::geometry {

namespace {

using detail::format;

struct Box {
  Vec3 lo;
  Vec3 hi;
  bool holds(const Vec3& p, double margin) const {
    return p.x >= lo.x - margin && p.x <= hi.x + margin && p.y >= lo.y - margin && p.y <= hi.y + margin &&
           p.z >= lo.z - margin && p.z <= hi.z + margin;
  }
};

/// The box of a face's poles, which holds the face (convex hull property, positive weights).
Box pole_box(const BSplineSurface& s) {
  Box b{s.poles().front(), s.poles().front()};
  for (const Vec3& p : s.poles()) {
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
  }
  return b;
}

void check_inputs(std::span<const CadFace> faces, const DeflectionSamples& samples,
                  const ReconstructionOptions& options) {
  if (samples.frame != SampleFrame::cartesian) {
    throw InputError::in(samples.source, std::string("a wall reconstructed on CAD faces needs a cartesian (x, y, z) "
                                                     "table, got a ") +
                                             to_string(samples.frame) + " one");
  }
  if (options.degree < 1 || options.degree > kMaxReconstructionDegree) {
    throw InputError::in(samples.source, "the degree of the deflected surface must be 1 to " +
                                             std::to_string(kMaxReconstructionDegree) + ", got " +
                                             std::to_string(options.degree));
  }
  if (!std::isfinite(options.tolerance) || options.tolerance < 0.0 || !(options.relative_tolerance > 0.0) ||
      !std::isfinite(options.relative_tolerance)) {
    throw InputError::in(samples.source, "the node distance tolerance must be a finite positive number");
  }
  if (samples.deflections.size() != samples.size()) {
    throw InputError::in(samples.source, "every FEM node needs a deflection");
  }
  if (samples.size() == 0) throw InputError::in(samples.source, "there are no FEM nodes");
  if (faces.empty()) throw InputError::in(samples.source, "no CAD faces to reconstruct the wall on");
  for (std::size_t j = 0; j < samples.size(); ++j) {
    if (!is_finite(samples.points[j]) || !is_finite(samples.deflections[j])) {
      throw InputError::in(samples.source, samples.label(j) + " has a coordinate or deflection that is not finite");
    }
  }
}

/// Where the FEM nodes lie on the faces: per face the field samples (t_j, s_j, delta_j) and the
/// sample indices.
struct PlacedSamples {
  std::vector<std::vector<FieldSample>> on_face;
  std::vector<std::vector<std::size_t>> index;
};

/// The point at fraction f along side 0..3 of a rectangle (v first, v last, u first, u last).
std::pair<double, double> on_side(const ParameterRectangle& r, int side, double f) {
  const double u = side < 2 ? r.u_first + f * (r.u_last - r.u_first) : (side == 2 ? r.u_first : r.u_last);
  const double v = side < 2 ? (side == 0 ? r.v_first : r.v_last) : r.v_first + f * (r.v_last - r.v_first);
  return {u, v};
}

/// The direction from a point of side `side` of a face into the face, across the edge: the
/// parameter derivative that points inward, less its part along the edge, unit.
Vec3 into_face(const SurfaceDerivatives& d, int side) {
  const Vec3 along = side < 2 ? d.du : d.dv;
  Vec3 w = side == 0 ? d.dv : side == 1 ? -d.dv : side == 2 ? d.du : -d.du;
  const double length2 = dot(along, along);
  if (length2 > 0.0) w = w - (dot(w, along) / length2) * along;
  return w / norm(w);
}

/// How far a wall turns across an edge of two faces, from the directions into each: 0 where
/// one face continues the other flat, pi where it folds back onto it. Unlike the angle
/// between the faces' normals it does not depend on how each face is oriented, so turns
/// beyond 90 degrees are told from their supplements.
double turn_angle(const Vec3& into_a, const Vec3& into_b) {
  return std::numbers::pi - std::acos(std::clamp(dot(into_a, into_b), -1.0, 1.0));
}

/// The largest difference between the deflections of two faces at sampled points of their
/// rectangles' edges that lie on the other face (its shared edges).
double edge_gap(std::span<const CadFace> faces, const std::vector<SurfaceProjector>& projectors,
                const std::vector<BSplineSurface>& fields, double tolerance) {
  constexpr int kPerEdge = 32;
  double gap = 0.0;
  for (std::size_t a = 0; a < faces.size(); ++a) {
    for (int k = 0; k <= 4 * kPerEdge + 3; ++k) {
      const auto [u, v] = on_side(faces[a].surface.domain(), k / (kPerEdge + 1),
                                  static_cast<double>(k % (kPerEdge + 1)) / kPerEdge);
      const Vec3 p = faces[a].surface.point(u, v);
      for (std::size_t b = 0; b < faces.size(); ++b) {
        if (b == a) continue;
        const SurfaceProjection q = projectors[b].project(p);
        if (q.distance > tolerance) continue;
        gap = std::max(gap, distance(fields[a].point(u, v), fields[b].point(q.where.u, q.where.v)));
      }
    }
  }
  return gap;
}

/// The sorted union of two lists of breakpoints.
std::vector<double> merged(std::vector<double> a, const std::vector<double>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

/// How far a face reaches beyond each of its free edges, as a fraction of its parameter range,
/// at least. A wall often ends where the CFD domain does (an inlet, the side of a sector), and
/// its deflection may carry its edge along that plane, away from the plane's nodes: beyond a
/// free edge the face goes on (its end pieces continued), so they still find it. It reaches
/// twice the largest deflection beyond the edge where that is farther (reaches()). Edges it
/// shares with another face of the wall, and collapsed edges (poles), do not reach.
constexpr double kFreeEdgeReach = 0.05;

/// The faces of a wall seen together: each on its own (undeformed) projector, their common
/// size, and for each side of each face's rectangle (v first, v last, u first, u last) the face
/// it is shared with (-1: a free edge) and whether it collapses to a point.
/// The faces joined through the shared sides `neighbours` lists (per face and side, the face
/// sharing it or -1) where `joined(a, b)` accepts the edge: a flood fill from each face not yet
/// in a group, so the groups come in order of their lowest face.
template <class Joined>
std::vector<std::vector<std::size_t>> face_groups(std::span<const std::array<int, 4>> neighbours, Joined joined) {
  std::vector<int> group(neighbours.size(), -1);
  std::vector<std::vector<std::size_t>> out;
  for (std::size_t start = 0; start < neighbours.size(); ++start) {
    if (group[start] >= 0) continue;
    out.emplace_back();
    std::vector<std::size_t> stack{start};
    group[start] = static_cast<int>(out.size() - 1);
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      out.back().push_back(f);
      for (const int n : neighbours[f]) {
        if (n >= 0 && group[static_cast<std::size_t>(n)] < 0 && joined(f, static_cast<std::size_t>(n))) {
          group[static_cast<std::size_t>(n)] = group[start];
          stack.push_back(static_cast<std::size_t>(n));
        }
      }
    }
  }
  return out;
}

struct FaceSet {
  std::vector<SurfaceProjector> projectors;
  std::vector<Box> boxes;
  double size = 0.0;
  std::vector<std::array<int, 4>> neighbours;
  std::vector<std::array<bool, 4>> collapsed;

  explicit FaceSet(std::span<const CadFace> faces) {
    Box all = pole_box(faces.front().surface);
    for (const CadFace& f : faces) {
      projectors.emplace_back(std::vector<SurfacePatch>{bspline_patch(f.surface)});
      boxes.push_back(pole_box(f.surface));
      all.lo = {std::min(all.lo.x, boxes.back().lo.x), std::min(all.lo.y, boxes.back().lo.y),
                std::min(all.lo.z, boxes.back().lo.z)};
      all.hi = {std::max(all.hi.x, boxes.back().hi.x), std::max(all.hi.y, boxes.back().hi.y),
                std::max(all.hi.z, boxes.back().hi.z)};
    }
    size = distance(all.lo, all.hi);
    for (std::size_t a = 0; a < faces.size(); ++a) find_edges(faces, a);
  }

  /// Groups of faces joined through shared edges.
  std::vector<std::vector<std::size_t>> groups() const {
    return face_groups(neighbours, [](std::size_t, std::size_t) { return true; });
  }

 private:
  /// A side is shared when 5 points along it lie on one other face (within 1e-6 of the size),
  /// collapsed when they are one point.
  void find_edges(std::span<const CadFace> faces, std::size_t a) {
    constexpr int kSamples = 5;
    const ParameterRectangle r = faces[a].surface.domain();
    std::array<int, 4> shared{-1, -1, -1, -1};
    std::array<bool, 4> point{};
    for (int side = 0; side < 4; ++side) {
      std::vector<Vec3> along;
      for (int k = 0; k < kSamples; ++k) {
        const auto [u, v] = on_side(r, side, (k + 0.5) / kSamples);
        along.push_back(faces[a].surface.point(u, v));
      }
      double length = 0.0;
      for (std::size_t k = 1; k < along.size(); ++k) length += distance(along[k], along[k - 1]);
      point[static_cast<std::size_t>(side)] = length <= 1e-9 * size;
      for (std::size_t b = 0; b < faces.size() && shared[static_cast<std::size_t>(side)] < 0; ++b) {
        const bool on_b = b != a && std::all_of(along.begin(), along.end(), [&](const Vec3& p) {
                            return projectors[b].project(p).distance <= 1e-6 * size;
                          });
        if (on_b) shared[static_cast<std::size_t>(side)] = static_cast<int>(b);
      }
    }
    neighbours.push_back(shared);
    collapsed.push_back(point);
  }
};

/// The edges the faces share side to side with parameters that correspond affinely (equal
/// fractions along both sides, or reversed), which join_fields can make the fields meet on,
/// and the corners those sides end at, grouped by the point of the wall they lie at.
struct EdgeJoins {
  std::vector<detail::SharedSide> sides;
  std::vector<std::vector<detail::FaceCorner>> corners;
  std::size_t shared = 0;  ///< shared sides, each counted once, joinable or not
};

EdgeJoins edge_joins(std::span<const CadFace> faces, const FaceSet& set) {
  const double tolerance = 1e-7 * set.size;
  constexpr int kSamples = 9;
  const auto point = [&](std::size_t f, int side, double fraction) {
    const auto [u, v] = on_side(faces[f].surface.domain(), side, fraction);
    return faces[f].surface.point(u, v);
  };
  const auto matches = [&](std::size_t a, int side_a, std::size_t b, int side_b, bool reversed) {
    for (int k = 0; k <= kSamples; ++k) {
      const double f = static_cast<double>(k) / kSamples;
      if (distance(point(a, side_a, f), point(b, side_b, reversed ? 1.0 - f : f)) > tolerance) return false;
    }
    return true;
  };
  EdgeJoins out;
  for (std::size_t a = 0; a < faces.size(); ++a) {
    for (int side_a = 0; side_a < 4; ++side_a) {
      const int n = set.neighbours[a][static_cast<std::size_t>(side_a)];
      if (n < 0) continue;
      const auto b = static_cast<std::size_t>(n);
      // Counted from the side that comes first, (face, side) in order, when b's matching side
      // points back; a side of a lying along part of b's side (no side of b matches) from a.
      bool found = false;
      for (int side_b = 0; side_b < 4 && !found; ++side_b) {
        for (const bool reversed : {false, true}) {
          if (!matches(a, side_a, b, side_b, reversed)) continue;
          found = true;
          if (std::pair(b, side_b) < std::pair(a, side_a) && set.neighbours[b][static_cast<std::size_t>(side_b)] == static_cast<int>(a)) break;
          ++out.shared;
          out.sides.push_back({{a, side_a}, {b, side_b}, reversed});
          break;
        }
      }
      if (!found) {
        const bool counted_from_b = b < a && std::find(set.neighbours[b].begin(), set.neighbours[b].end(), static_cast<int>(a)) !=
                                                 set.neighbours[b].end();
        if (!counted_from_b) ++out.shared;
      }
    }
  }
  // Corner c of a rectangle: (u first | u last) + 2 (v first | v last); the ends of side k.
  constexpr std::array<std::array<int, 2>, 4> kEnds{{{0, 1}, {2, 3}, {0, 2}, {1, 3}}};
  std::vector<std::pair<detail::FaceCorner, Vec3>> ends;
  for (const detail::SharedSide& s : out.sides) {
    for (const detail::FaceSide& fs : {s.a, s.b}) {
      for (const int c : kEnds[static_cast<std::size_t>(fs.side)]) {
        const bool seen = std::any_of(ends.begin(), ends.end(), [&](const auto& e) { return e.first.face == fs.face && e.first.corner == c; });
        if (seen) continue;
        const ParameterRectangle r = faces[fs.face].surface.domain();
        ends.push_back({{fs.face, c}, faces[fs.face].surface.point(c % 2 == 0 ? r.u_first : r.u_last, c < 2 ? r.v_first : r.v_last)});
      }
    }
  }
  std::vector<bool> grouped(ends.size(), false);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    if (grouped[i]) continue;
    out.corners.emplace_back();
    for (std::size_t j = i; j < ends.size(); ++j) {
      if (!grouped[j] && distance(ends[i].second, ends[j].second) <= tolerance) {
        grouped[j] = true;
        out.corners.back().push_back(ends[j].first);
      }
    }
  }
  return out;
}

/// The largest deflection a field gives (bounded by its largest pole: convex hull property).
double largest_pole(const BSplineSurface& field) {
  double largest = 0.0;
  for (const Vec3& p : field.poles()) largest = std::max(largest, norm(p));
  return largest;
}

/// The smallest speeds |S_t| and |S_s| of a face, sampled on a 9 x 9 grid.
std::pair<double, double> slowest(const BSplineSurface& s) {
  const ParameterRectangle r = s.domain();
  double along_t = std::numeric_limits<double>::infinity(), along_s = along_t;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 8; ++j) {
      const SurfaceDerivatives d =
          s.derivatives(r.u_first + (r.u_last - r.u_first) * i / 8.0, r.v_first + (r.v_last - r.v_first) * j / 8.0);
      along_t = std::min(along_t, norm(d.du));
      along_s = std::min(along_s, norm(d.dv));
    }
  }
  return {along_t, along_s};
}

/// Each face's rectangle with its free edges moved out by kFreeEdgeReach of its range, or by
/// twice `deflection` (the largest a stage gives) where that is farther.
std::vector<ParameterRectangle> reaches(std::span<const CadFace> faces, const FaceSet& set,
                                        std::span<const double> deflection) {
  std::vector<ParameterRectangle> out;
  for (std::size_t a = 0; a < faces.size(); ++a) {
    const ParameterRectangle r = faces[a].surface.domain();
    ParameterRectangle reach = r;
    const auto [speed_t, speed_s] = slowest(faces[a].surface);
    const auto beyond = [&](double range, double speed) {
      const double carried = speed > 0.0 ? 2.0 * deflection[a] / speed : 0.0;
      return std::min(std::max(kFreeEdgeReach * range, carried), range);
    };
    const double du = beyond(r.u_last - r.u_first, speed_t), dv = beyond(r.v_last - r.v_first, speed_s);
    for (std::size_t side = 0; side < 4; ++side) {
      if (set.neighbours[a][side] >= 0 || set.collapsed[a][side]) continue;
      if (side == 0) reach.v_first -= dv;
      if (side == 1) reach.v_last += dv;
      if (side == 2) reach.u_first -= du;
      if (side == 3) reach.u_last += du;
    }
    out.push_back(reach);
  }
  return out;
}

/// Faces that cannot carry a field d(t, s) are refused (item 6 of issue 23): one whose
/// parametrisation degenerates (a pole, a collapsed edge, a point inside where S_t x S_s
/// vanishes: (t, s) is not unique there), naming the FEM nodes nearest the degenerate spot;
/// and faces that share no edge with the rest of the wall (a face number mistyped, or a
/// separate part that needs its own patch).
void refuse_faces(std::span<const CadFace> faces, const FaceSet& set, const DeflectionSamples& samples) {
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const DegeneracyReport& report = set.projectors[f].degeneracies();
    if (report.empty()) continue;
    const ParameterRectangle r = faces[f].surface.domain();
    std::pair<double, double> spot{0.5 * (r.u_first + r.u_last), 0.5 * (r.v_first + r.v_last)};
    std::string where;
    if (!report.edges.empty()) {
      const auto edge = report.edges.front().edge;
      const int side = edge == PatchEdge::v_first ? 0 : edge == PatchEdge::v_last ? 1 : edge == PatchEdge::u_first ? 2 : 3;
      spot = on_side(r, side, 0.5);
      where = std::string(report.edges.front().collapsed ? "an edge collapses to one point (a pole)"
                                                         : "the surface's normal vanishes along an edge");
    } else {
      spot = {report.points.front().u, report.points.front().v};
      where = "the surface's normal vanishes inside it";
    }
    const Vec3 p = faces[f].surface.point(spot.first, spot.second);
    std::vector<std::size_t> order(samples.size());
    for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
    const std::size_t listed = std::min<std::size_t>(5, order.size());
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(listed), order.end(),
                      [&](std::size_t i, std::size_t j) { return distance(samples.points[i], p) < distance(samples.points[j], p); });
    std::string nodes;
    for (std::size_t k = 0; k < listed; ++k) {
      nodes += (k > 0 ? ", " : "") + samples.label(order[k]) + " at " + format(distance(samples.points[order[k]], p));
    }
    throw InputError::in(samples.source,
                         "CAD face " + std::to_string(faces[f].id) + ": its parametrisation degenerates (" + where +
                             ", at (" + format(p.x) + ", " + format(p.y) + ", " + format(p.z) +
                             ")): (t, s) is not unique there, so no deflection field d(t, s) can be fitted on it. "
                             "FEM nodes nearest that point: " + nodes +
                             ". Split the face in the CAD system so that no face has a pole, or, if the wall is a "
                             "surface of revolution, give the case's axis and `mode: meridional`");
  }
  const auto groups = set.groups();
  if (groups.size() <= 1) return;
  const auto ids = [&](const std::vector<std::size_t>& group) {
    std::string text;
    for (std::size_t k = 0; k < group.size(); ++k) text += (k > 0 ? ", " : "") + std::to_string(faces[group[k]].id);
    return text;
  };
  std::string parts;
  for (std::size_t g = 0; g < groups.size(); ++g) parts += (g > 0 ? "; " : "") + ids(groups[g]);
  throw InputError::in(samples.source, "the CAD faces of the wall do not join: they form " +
                                           std::to_string(groups.size()) + " separate parts (faces " + parts +
                                           ") sharing no edge. Check the face numbers (`hotmesh cad` lists them), or "
                                           "give each part its own patch");
}

}  // namespace

FaceDeflections reconstruct_on_faces(std::span<const CadFace> faces, const DeflectionSamples& samples,
                                     const ReconstructionOptions& options) {
  check_inputs(faces, samples, options);
  FaceDeflections out;
  SurfaceReconstructionReport& report = out.report;
  report.nodes = samples.size();
  report.degree = options.degree;

  const FaceSet set(faces);
  refuse_faces(faces, set, samples);
  const std::vector<SurfaceProjector>& projectors = set.projectors;
  const double size = set.size;
  report.tolerance = options.tolerance > 0.0 ? options.tolerance : options.relative_tolerance * size;

  // Every Q_j onto every face near it: a node within the tolerance of several faces (on the
  // edge they share) is a sample of each, so their fields agree there.
  PlacedSamples placed;
  placed.on_face.resize(faces.size());
  placed.index.resize(faces.size());
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const Vec3& q = samples.points[j];
    double nearest = std::numeric_limits<double>::infinity();
    std::vector<std::pair<std::size_t, SurfaceProjection>> near;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (!set.boxes[f].holds(q, report.tolerance)) continue;
      const SurfaceProjection p = projectors[f].project(q);
      nearest = std::min(nearest, p.distance);
      if (p.distance <= report.tolerance) near.emplace_back(f, p);
    }
    if (near.empty()) {  // its distance for the message, from every face
      for (const SurfaceProjector& projector : projectors) nearest = std::min(nearest, projector.project(q).distance);
      report.rejected_nodes.push_back({j, samples.label(j), nearest, 0.0});
      continue;
    }
    ++report.used_nodes;
    report.max_node_distance_to_cad = std::max(report.max_node_distance_to_cad, nearest);
    for (const auto& [f, p] : near) {
      placed.on_face[f].push_back({p.where.u, p.where.v, samples.deflections[j]});
      placed.index[f].push_back(j);
      out.placements.push_back({j, f, p.where.u, p.where.v, p.distance});
    }
  }
  if (!report.rejected_nodes.empty() && options.far_nodes == FarNodePolicy::reject) {
    const std::string how = options.tolerance > 0.0 ? "the given tolerance"
                                                    : "the default tolerance, " + format(options.relative_tolerance) +
                                                          " of the faces' size " + format(size);
    throw InputError::in(samples.source, std::to_string(report.rejected_nodes.size()) + " of " +
                                             std::to_string(samples.size()) + " FEM nodes are farther than " +
                                             format(report.tolerance) + " (" + how + ") from the CAD faces: " +
                                             detail::list_nodes(report.rejected_nodes));
  }

  // d(t, s) on each face through its nodes.
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const int id = faces[f].id;
    if (placed.on_face[f].empty()) {
      throw InputError::in(samples.source, "no FEM node lies on CAD face " + std::to_string(id) + " (within " +
                                               format(report.tolerance) +
                                               "): give only the faces the table covers, or a table that covers them");
    }
    SurfaceFitOptions fit_options;
    fit_options.degree = options.degree;
    fit_options.aspect = face_aspect(faces[f].surface);
    try {
      SurfaceFit fit = fit_surface_field(placed.on_face[f], faces[f].surface.domain(), fit_options);
      report.faces.push_back({id, placed.on_face[f].size(), fit.report});
      report.max_node_residual = std::max(report.max_node_residual, fit.report.max_residual);
      out.fields.push_back(std::move(fit.field));
    } catch (const InputError& e) {
      throw InputError::in(samples.source, "CAD face " + std::to_string(id) + ": " + e.what());
    }
  }
  // The fields made to meet along the edges the faces share (field_joins.hpp), and the fit's
  // residuals measured again on the joined fields.
  const EdgeJoins joins = edge_joins(faces, set);
  report.shared_edges = joins.shared;
  report.joined_edges = joins.sides.size() - detail::join_fields(out.fields, joins.sides, joins.corners).size();
  report.max_node_residual = 0.0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    SurfaceFitReport& fit = report.faces[f].fit;
    fit.u_poles = out.fields[f].u_count();  // knots inserted along joined edges add poles
    fit.v_poles = out.fields[f].v_count();
    fit.max_residual = 0.0;
    double squares = 0.0;
    for (const FieldSample& sample : placed.on_face[f]) {
      const double r = distance(out.fields[f].point(sample.u, sample.v), sample.value);
      fit.max_residual = std::max(fit.max_residual, r);
      squares += r * r;
    }
    fit.rms_residual = std::sqrt(squares / static_cast<double>(placed.on_face[f].size()));
    report.max_node_residual = std::max(report.max_node_residual, fit.max_residual);
  }
  report.max_edge_gap = edge_gap(faces, projectors, out.fields, report.tolerance);
  return out;
}

SurfaceShape::SurfaceShape(std::vector<CadFace> faces, std::vector<BSplineSurface> after,
                           std::vector<BSplineSurface> before)
    : faces_(std::move(faces)), after_(std::move(after)), before_(std::move(before)) {
  if (faces_.empty() || after_.size() != faces_.size() || (!before_.empty() && before_.size() != faces_.size())) {
    throw std::invalid_argument("SurfaceShape: one deflection field per face");
  }
  const auto same = [](const ParameterRectangle& a, const ParameterRectangle& b) {
    return a.u_first == b.u_first && a.u_last == b.u_last && a.v_first == b.v_first && a.v_last == b.v_last;
  };
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const ParameterRectangle r = faces_[f].surface.domain();
    if (!same(r, after_[f].domain()) || (!before_.empty() && !same(r, before_[f].domain()))) {
      throw std::invalid_argument("SurfaceShape: a deflection field's rectangle differs from its face's");
    }
  }
  const FaceSet set(faces_);
  neighbours_ = set.neighbours;
  std::vector<double> deflection(faces_.size());
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    deflection[f] = std::max(largest_pole(after_[f]), before_.empty() ? 0.0 : largest_pole(before_[f]));
  }
  reach_ = reaches(faces_, set, deflection);
}

// Stage lambda of the faces (section 4.3): S + (1 - lambda) d0 + lambda d1, d0 the deflection
// the run starts from (zero from the cold geometry, the previous run's on a restart).
// Beyond a free edge, the faces and fields continued (kFreeEdgeReach).
SurfaceDerivatives SurfaceShape::evaluate(std::size_t face, double t, double s, double lambda) const {
  SurfaceDerivatives d =
      faces_[face].surface.continued_derivatives(t, s) + lambda * after_[face].continued_derivatives(t, s);
  if (!before_.empty()) d = d + (1.0 - lambda) * before_[face].continued_derivatives(t, s);
  return d;
}

std::vector<int> SurfaceShape::faces_of(int key) const {
  if (key >= 0) return {key};
  if (key == kAllFaces) {
    std::vector<int> all(faces_.size());
    for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
    return all;
  }
  return regions_.at(static_cast<std::size_t>(-2 - key));  // under stages_mutex_
}

const SurfaceProjector& SurfaceShape::stage(double lambda, int faces) const {
  const std::pair key{lambda, faces};
  {
    const std::shared_lock read(stages_mutex_);
    const auto it = stages_.find(key);
    if (it != stages_.end()) return *it->second;
  }
  const std::unique_lock write(stages_mutex_);
  auto& slot = stages_[key];
  if (!slot) {
    std::vector<SurfacePatch> patches;
    for (const int index : faces_of(faces)) {
      const auto f = static_cast<std::size_t>(index);
      const BSplineSurface& s = faces_[f].surface;
      SurfacePatch patch;
      patch.evaluate = [this, f, lambda](double t, double u) { return evaluate(f, t, u, lambda); };
      patch.domain = reach_[f];
      patch.u_breaks = merged(s.u_breakpoints(), after_[f].u_breakpoints());
      patch.v_breaks = merged(s.v_breakpoints(), after_[f].v_breakpoints());
      if (!before_.empty()) {
        patch.u_breaks = merged(patch.u_breaks, before_[f].u_breakpoints());
        patch.v_breaks = merged(patch.v_breaks, before_[f].v_breakpoints());
      }
      patches.push_back(std::move(patch));
    }
    slot = std::make_unique<SurfaceProjector>(std::move(patches));
  }
  return *slot;
}

ShapePoint SurfaceShape::project(const Vec3& p, double lambda, const ShapeParameter& hint,
                                 const ParameterRange& range) const {
  if (range.region < 0) {
    const SurfaceParameter start = hint.known() ? SurfaceParameter{hint.face, hint.t, hint.s} : SurfaceParameter{};
    const SurfaceProjection q = stage(lambda).project(p, start);
    return {q.point, q.normal, {q.where.u, q.where.v, q.where.patch}, q.distance};
  }
  // Within a region: its projector's patches are the region's faces in increasing order.
  const int key = region_key(range.region);
  const std::vector<int>* region = nullptr;  // stays put: regions_ only grows, at its end
  {
    const std::shared_lock read(stages_mutex_);
    region = &regions_.at(static_cast<std::size_t>(range.region));
  }
  const std::vector<int>& faces = *region;
  const auto local = std::find(faces.begin(), faces.end(), hint.face);
  const SurfaceParameter start = hint.known() && local != faces.end()
                                     ? SurfaceParameter{static_cast<int>(local - faces.begin()), hint.t, hint.s}
                                     : SurfaceParameter{};
  const SurfaceProjection q = stage(lambda, key).project(p, start);
  return {q.point, q.normal, {q.where.u, q.where.v, faces[static_cast<std::size_t>(q.where.patch)]}, q.distance};
}

int SurfaceShape::crease_region(int face, double min_angle) const {
  if (face < 0 || static_cast<std::size_t>(face) >= faces_.size()) return -1;
  {
    const std::shared_lock read(stages_mutex_);
    const auto it = region_of_face_.find(min_angle);
    if (it != region_of_face_.end()) return it->second[static_cast<std::size_t>(face)];
  }
  // Faces joined through shared edges that are not creases.
  const std::vector<ShapeCrease> cut = creases(min_angle);
  const auto joined = [&](std::size_t a, std::size_t b) {
    return std::none_of(cut.begin(), cut.end(), [&](const ShapeCrease& c) {
      return c.faces == std::array{static_cast<int>(std::min(a, b)), static_cast<int>(std::max(a, b))};
    });
  };
  std::vector<std::vector<std::size_t>> groups = face_groups(neighbours_, joined);
  const std::unique_lock write(stages_mutex_);
  const auto it = region_of_face_.find(min_angle);
  if (it != region_of_face_.end()) return it->second[static_cast<std::size_t>(face)];  // another thread's
  std::vector<int> region(faces_.size());
  for (std::vector<std::size_t>& group : groups) {
    std::sort(group.begin(), group.end());
    const std::vector<int> faces(group.begin(), group.end());
    const auto known = std::find(regions_.begin(), regions_.end(), faces);
    for (const std::size_t f : group) region[f] = static_cast<int>(known - regions_.begin());
    if (known == regions_.end()) regions_.push_back(faces);
  }
  region_of_face_[min_angle] = region;
  return region[static_cast<std::size_t>(face)];
}

ShapePoint SurfaceShape::at(const ShapeParameter& where, double lambda, const Vec3& /*reference*/) const {
  const SurfaceProjection q = stage(lambda).at({where.face, where.t, where.s});
  return {q.point, q.normal, {q.where.u, q.where.v, q.where.patch}, 0.0};
}

ShapePoint SurfaceShape::project_on_face(int face, const Vec3& p, double lambda, const ShapeParameter& hint) const {
  const SurfaceParameter start = hint.known() && hint.face == face ? SurfaceParameter{0, hint.t, hint.s}
                                                                   : SurfaceParameter{};
  const SurfaceProjection q = stage(lambda, face).project(p, start);
  return {q.point, q.normal, {q.where.u, q.where.v, face}, q.distance};
}

/// One face of a wall as a shape of its own (clamped at its shared edges): a node held by the
/// faces on both sides of a crease slides along it (alternating projections meet on the edge).
class FaceOfWall final : public BoundaryShape {
 public:
  FaceOfWall(std::shared_ptr<const SurfaceShape> wall, int face) : wall_(std::move(wall)), face_(face) {}
  ShapePoint project(const Vec3& p, double lambda, const ShapeParameter& hint = kNoHint,
                     const ParameterRange& /*range*/ = {}) const override {
    return wall_->project_on_face(face_, p, lambda, hint);
  }
  ShapePoint at(const ShapeParameter& where, double lambda, const Vec3& reference) const override {
    return wall_->at({where.t, where.s, face_}, lambda, reference);
  }

 private:
  std::shared_ptr<const SurfaceShape> wall_;
  int face_;
};

std::vector<std::shared_ptr<const BoundaryShape>> SurfaceShape::crease_sides(const ShapeParameter& where,
                                                                           double min_angle) const {
  if (!where.known() || where.face < 0 || static_cast<std::size_t>(where.face) >= faces_.size()) return {};
  const auto f = static_cast<std::size_t>(where.face);
  const ParameterRectangle r = faces_[f].surface.domain();
  const double on_t = 1e-9 * (r.u_last - r.u_first), on_s = 1e-9 * (r.v_last - r.v_first);
  const std::array<bool, 4> at_side{std::abs(where.s - r.v_first) <= on_s, std::abs(where.s - r.v_last) <= on_s,
                                    std::abs(where.t - r.u_first) <= on_t, std::abs(where.t - r.u_last) <= on_t};
  const SurfaceDerivatives here = evaluate(f, where.t, where.s, 0.0);
  std::vector<std::shared_ptr<const BoundaryShape>> sides;
  for (std::size_t side = 0; side < 4; ++side) {
    const int other = neighbours_[f][side];
    const int other_side = other >= 0 ? side_shared_with(other, where.face) : -1;
    if (!at_side[side] || other_side < 0) continue;
    const ShapePoint there = project_on_side(static_cast<std::size_t>(other), other_side, here.point, 0.0);
    const SurfaceDerivatives across = evaluate(static_cast<std::size_t>(other), there.parameter.t, there.parameter.s, 0.0);
    if (turn_angle(into_face(here, static_cast<int>(side)), into_face(across, other_side)) < min_angle) continue;
    if (sides.empty()) sides.push_back(std::make_shared<FaceOfWall>(shared_from_this(), where.face));
    sides.push_back(std::make_shared<FaceOfWall>(shared_from_this(), other));
  }
  return sides;
}

int SurfaceShape::side_shared_with(int face, int other) const {
  const auto& sides = neighbours_[static_cast<std::size_t>(face)];
  const auto it = std::find(sides.begin(), sides.end(), other);
  return it == sides.end() ? -1 : static_cast<int>(it - sides.begin());
}

// The side's curve C(f) = S(on_side(f)), f in [0, 1], minimises |C(f) - p|^2: the best of
// uniform samples, then Newton on C'(f).(C(f) - p) = 0, kept on the side.
ShapePoint SurfaceShape::project_on_side(std::size_t face, int side, const Vec3& p, double lambda) const {
  const ParameterRectangle r = faces_[face].surface.domain();
  const bool along_t = side < 2;
  const double span = along_t ? r.u_last - r.u_first : r.v_last - r.v_first;
  const auto curve = [&](double f) {
    const auto [t, s] = on_side(r, side, f);
    return evaluate(face, t, s, lambda);
  };
  constexpr int kSamples = 32;
  double f = 0.0, best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= kSamples; ++k) {
    const double d = distance(curve(static_cast<double>(k) / kSamples).point, p);
    if (d < best) best = d, f = static_cast<double>(k) / kSamples;
  }
  constexpr int kNewtonSteps = 40;
  for (int k = 0; k < kNewtonSteps; ++k) {
    const SurfaceDerivatives c = curve(f);
    const Vec3 d1 = span * (along_t ? c.du : c.dv), d2 = span * span * (along_t ? c.duu : c.dvv), off = c.point - p;
    const double g = dot(d1, off), h = dot(d2, off) + dot(d1, d1);
    const double next = std::clamp(f - g / (h > 0.0 ? h : std::max(dot(d1, d1), 1e-300)), 0.0, 1.0);
    const bool done = std::abs(next - f) <= 1e-14;
    f = next;
    if (done) break;
  }
  const SurfaceDerivatives c = curve(f);
  const Vec3 n = cross(c.du, c.dv);
  const auto [t, s] = on_side(r, side, f);
  return {c.point, n / norm(n), {t, s, static_cast<int>(face)}, distance(c.point, p)};
}

std::vector<ShapeCrease> SurfaceShape::creases(double min_angle) const {
  std::vector<ShapeCrease> found;
  constexpr int kSamples = 8;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    for (int side = 0; side < 4; ++side) {
      const int g = neighbours_[f][static_cast<std::size_t>(side)];
      if (g <= static_cast<int>(f) || side_shared_with(static_cast<int>(f), g) != side) continue;
      const int other_side = side_shared_with(g, static_cast<int>(f));
      if (other_side < 0) continue;
      const ParameterRectangle r = faces_[f].surface.domain();
      ShapeCrease crease{{static_cast<int>(f), g}, 0.0};
      for (const double lambda : {0.0, 1.0}) {
        for (int k = 0; k <= kSamples; ++k) {
          const auto [t, s] = on_side(r, side, static_cast<double>(k) / kSamples);
          const SurfaceDerivatives here = evaluate(f, t, s, lambda);
          const ShapePoint there = project_on_side(static_cast<std::size_t>(g), other_side, here.point, lambda);
          const SurfaceDerivatives across = evaluate(static_cast<std::size_t>(g), there.parameter.t, there.parameter.s, lambda);
          crease.angle = std::max(crease.angle, turn_angle(into_face(here, side), into_face(across, other_side)));
        }
      }
      if (crease.angle >= min_angle) found.push_back(crease);
    }
  }
  return found;
}

CreasePoint SurfaceShape::crease_point(const ShapeCrease& crease, const Vec3& p, double lambda) const {
  const int a = crease.faces[0], b = crease.faces[1];
  const int count = static_cast<int>(faces_.size());
  const int side_a = a >= 0 && a < count && b >= 0 && b < count ? side_shared_with(a, b) : -1;
  const int side_b = side_a >= 0 ? side_shared_with(b, a) : -1;
  if (side_b < 0) throw std::logic_error("SurfaceShape::crease_point: the faces share no edge");
  const ShapePoint on_a = project_on_side(static_cast<std::size_t>(a), side_a, p, lambda);
  const ShapePoint on_b = project_on_side(static_cast<std::size_t>(b), side_b, on_a.point, lambda);
  return {on_a.point, {on_a.normal, on_b.normal}};
}

SurfaceShapeFit make_surface_shape(std::vector<CadFace> faces, const DeflectionSamples& samples,
                                   const ReconstructionOptions& options, const DeflectionSamples* previous) {
  FaceDeflections after = reconstruct_on_faces(faces, samples, options);
  std::vector<BSplineSurface> before;
  if (previous) before = reconstruct_on_faces(faces, *previous, options).fields;
  auto shape = std::make_shared<SurfaceShape>(std::move(faces), std::move(after.fields), std::move(before));
  return {std::move(shape), std::move(after.report)};
}

ScatteredShape::ScatteredShape(ScatteredField after, std::shared_ptr<const ScatteredField> before)
    : after_(std::move(after)), before_(std::move(before)) {}

ShapePoint ScatteredShape::project(const Vec3& p, double /*lambda*/, const ShapeParameter& /*hint*/,
                                   const ParameterRange& /*range*/) const {
  return {p, {}, {}, after_.outside(p)};
}

// x = x0 + before(x0) by fixed-point iteration x0 <- x - before(x0): a contraction wherever the
// deflection's gradient is below 1, as any FEM deflection of a wall is by orders of magnitude.
Vec3 ScatteredShape::material_point(const Vec3& x) const {
  if (!before_) return x;
  constexpr int kMaxIterations = 100;
  const double tolerance = 1e-15 * (1.0 + norm(x));
  Vec3 x0 = x - (*before_)(x);
  for (int k = 0; k < kMaxIterations; ++k) {
    const Vec3 next = x - (*before_)(x0);
    const double step = distance(next, x0);
    x0 = next;
    if (step <= tolerance) break;
  }
  return x0;
}

ShapePoint ScatteredShape::at(const ShapeParameter& where, double lambda, const Vec3& reference) const {
  const Vec3 x0 = material_point(reference);
  const Vec3 start = before_ ? (*before_)(x0) : Vec3{};
  return {x0 + start + lambda * (after_(x0) - start), {}, where, 0.0};
}

}  // namespace hotmesh::geometry
