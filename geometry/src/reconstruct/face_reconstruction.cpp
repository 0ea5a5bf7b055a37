// hotmesh geometry: section 4.2 on CAD faces, the reconstruction (surface_shape.hpp): FEM nodes
// to (face, t, s), a deflection field d(t, s) fitted on each face (surface_fit.hpp), the fields
// joined along the edges the faces share (field_joins.hpp), and the faces that cannot carry a
// field refused.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/surface_shape.hpp"
#include "reconstruct/cad_face_set.hpp"
#include "reconstruct/field_joins.hpp"
#include "reconstruct/node_list.hpp"

namespace hotmesh::geometry {
namespace {

using detail::Box;
using detail::FaceSet;
using detail::format;
using detail::on_side;

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

/// The edges the faces share side to side with parameters that correspond affinely (equal
/// fractions along both sides, or reversed), which join_fields makes the fields meet on
/// exactly; those whose parameters do not (uneven), which it makes meet to a tolerance; and
/// the corners those sides end at, grouped by the point of the wall they lie at.
struct EdgeJoins {
  std::vector<detail::SharedSide> sides;
  std::vector<detail::UnevenSide> uneven;
  std::vector<detail::SideOnFace> on_faces;  ///< a side of one face across the other's rectangle (trace_joins.hpp)
  std::vector<detail::TracedEdge> across;    ///< edges across both faces' rectangles (trace_joins.hpp)
  std::vector<std::vector<detail::FaceCorner>> corners;
  std::size_t shared = 0;  ///< shared sides, each counted once, joinable or not
};

/// The parameter along side `side` of a face (u along sides 0 and 1, v along 2 and 3) of the
/// point of that side nearest p: Newton on |C(y) - p|^2 for the side's curve C, from `start`.
double nearest_on_side(const BSplineSurface& s, int side, const Vec3& p, double start) {
  const ParameterRectangle r = s.domain();
  const bool u = side < 2;
  const double lo = u ? r.u_first : r.v_first, hi = u ? r.u_last : r.v_last;
  double y = std::clamp(start, lo, hi);
  for (int iteration = 0; iteration < 20; ++iteration) {
    const auto [su, sv] = on_side(r, side, (y - lo) / (hi - lo));
    const SurfaceDerivatives d = s.derivatives(su, sv);
    const Vec3 c1 = u ? d.du : d.dv, c2 = u ? d.duu : d.dvv, off = d.point - p;
    const double slope = dot(off, c1), curvature = dot(c1, c1) + dot(off, c2);
    if (!(curvature > 0.0)) break;
    const double next = std::clamp(y - slope / curvature, lo, hi);
    const bool settled = std::abs(next - y) <= 1e-15 * (hi - lo);
    y = next;
    if (settled) break;
  }
  return y;
}

/// The uneven edge where side `side_a` of face a lies on face b: the side of b it lies on
/// (found from 5 points of a's side projected onto b), and the maps between the two sides'
/// parameters through the points of the wall (valid while `faces` and `set` are); none if the
/// points are not on one side of b.
std::optional<detail::UnevenSide> uneven_side(std::span<const CadFace> faces, const FaceSet& set, std::size_t a,
                                              int side_a, std::size_t b) {
  const ParameterRectangle ra = faces[a].surface.domain(), rb = faces[b].surface.domain();
  const auto range = [](const ParameterRectangle& r, int side) {
    return side < 2 ? std::pair(r.u_first, r.u_last) : std::pair(r.v_first, r.v_last);
  };
  const auto across = [](const ParameterRectangle& r, int side) {  // the fixed parameter, its range
    return side < 2 ? std::array{side == 0 ? r.v_first : r.v_last, r.v_last - r.v_first}
                    : std::array{side == 2 ? r.u_first : r.u_last, r.u_last - r.u_first};
  };
  std::vector<SurfaceParameter> on_b;
  for (int k = 0; k < 5; ++k) {
    const auto [u, v] = on_side(ra, side_a, (k + 0.5) / 5.0);
    on_b.push_back(set.projectors[b].project(faces[a].surface.point(u, v)).where);
  }
  for (int side_b = 0; side_b < 4; ++side_b) {
    const std::array<double, 2> line = across(rb, side_b);  // no structured binding: lambdas capture it
    const double fixed = line[0], extent = line[1];
    const bool on = std::all_of(on_b.begin(), on_b.end(), [&](const SurfaceParameter& w) {
      return std::abs((side_b < 2 ? w.v : w.u) - fixed) <= 1e-7 * extent;
    });
    if (!on) continue;
    const auto point = [faces, range](std::size_t f, int side, double y) {  // the point at y along a side
      const auto [lo, hi] = range(faces[f].surface.domain(), side);
      const auto [u, v] = on_side(faces[f].surface.domain(), side, (y - lo) / (hi - lo));
      return faces[f].surface.point(u, v);
    };
    // From x along one side to the parameter of the other side's point nearest the point at x:
    // the other face's projector, then Newton along its side.
    const auto map = [faces, &set, point](std::size_t from, int side_from, std::size_t to, int side_to) {
      return [faces, &set, point, from, side_from, to, side_to](double x) {
        const Vec3 p = point(from, side_from, x);
        const SurfaceParameter w = set.projectors[to].project(p).where;
        return nearest_on_side(faces[to].surface, side_to, p, side_to < 2 ? w.u : w.v);
      };
    };
    return detail::UnevenSide{{a, side_a}, {b, side_b}, map(a, side_a, b, side_b), map(b, side_b, a, side_a)};
  }
  return std::nullopt;
}

/// Phase 1: the sides that lie on another face (FaceSet::neighbours), each counted once:
/// matched side to side affinely (`sides`), unevenly (`uneven`), or lying inside the other's
/// rectangle where the CAD file names no edge for it (`on_faces`).
void add_shared_sides(std::span<const CadFace> faces, const FaceSet& set, double tolerance, EdgeJoins& out) {
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
      if (found) continue;
      const bool counted_from_b = b < a && std::find(set.neighbours[b].begin(), set.neighbours[b].end(), static_cast<int>(a)) !=
                                               set.neighbours[b].end();
      if (counted_from_b) continue;
      if (auto s = uneven_side(faces, set, a, side_a, b)) {
        ++out.shared;
        out.uneven.push_back(std::move(*s));
      } else if (!set.crossed(a, b)) {  // inside b's rectangle, and the CAD file has no edge for it
        ++out.shared;
        out.on_faces.push_back({a, side_a, b});
      }
    }
  }
}

/// Phase 2: the edges the CAD file names that cross a rectangle: along a side of one face
/// (`on_faces`), or across both (`across`).
void add_crossing_edges(std::span<const CadFace> faces, const FaceSet& set, EdgeJoins& out) {
  out.shared += set.crossing.size();
  for (const detail::TracedEdge& e : set.crossing) {
    if (const int side = detail::side_holding(faces[e.a].surface, e.on_a); side >= 0) {
      out.on_faces.push_back({e.a, side, e.b});
    } else if (const int side_b = detail::side_holding(faces[e.b].surface, e.on_b); side_b >= 0) {
      out.on_faces.push_back({e.b, side_b, e.a});
    } else {
      out.across.push_back(e);
    }
  }
}

/// Phase 3: the corners that end a side joined side to side, grouped by the point of the wall
/// they lie at (within `tolerance`).
std::vector<std::vector<detail::FaceCorner>> corner_groups(std::span<const CadFace> faces, const EdgeJoins& joins,
                                                           double tolerance) {
  // Corner c of a rectangle: (u first | u last) + 2 (v first | v last); the ends of side k.
  constexpr std::array<std::array<int, 2>, 4> kEnds{{{0, 1}, {2, 3}, {0, 2}, {1, 3}}};
  std::vector<std::pair<detail::FaceCorner, Vec3>> ends;
  std::vector<detail::FaceSide> ending;
  for (const detail::SharedSide& s : joins.sides) ending.insert(ending.end(), {s.a, s.b});
  for (const detail::UnevenSide& s : joins.uneven) ending.insert(ending.end(), {s.a, s.b});
  for (const detail::FaceSide& fs : ending) {
    for (const int c : kEnds[static_cast<std::size_t>(fs.side)]) {
      const bool seen = std::any_of(ends.begin(), ends.end(), [&](const auto& e) { return e.first.face == fs.face && e.first.corner == c; });
      if (seen) continue;
      const ParameterRectangle r = faces[fs.face].surface.domain();
      ends.push_back({{fs.face, c}, faces[fs.face].surface.point(c % 2 == 0 ? r.u_first : r.u_last, c < 2 ? r.v_first : r.v_last)});
    }
  }
  std::vector<std::vector<detail::FaceCorner>> groups;
  std::vector<bool> grouped(ends.size(), false);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    if (grouped[i]) continue;
    groups.emplace_back();
    for (std::size_t j = i; j < ends.size(); ++j) {
      if (!grouped[j] && distance(ends[i].second, ends[j].second) <= tolerance) {
        grouped[j] = true;
        groups.back().push_back(ends[j].first);
      }
    }
  }
  return groups;
}

EdgeJoins edge_joins(std::span<const CadFace> faces, const FaceSet& set) {
  const double tolerance = 1e-7 * set.size;
  EdgeJoins out;
  add_shared_sides(faces, set, tolerance, out);
  add_crossing_edges(faces, set, out);
  out.corners = corner_groups(faces, out, tolerance);
  return out;
}

/// The sides joined to other faces' sides, which the joins across rectangles leave as they are.
std::vector<detail::FaceSide> joined_sides(const EdgeJoins& joins) {
  std::vector<detail::FaceSide> sides;
  for (const detail::SharedSide& s : joins.sides) sides.insert(sides.end(), {s.a, s.b});
  for (const detail::UnevenSide& s : joins.uneven) sides.insert(sides.end(), {s.a, s.b});
  return sides;
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

// Every Q_j onto every face near it: a node within the tolerance of several faces (on the
// edge they share) is a sample of each, so their fields agree there. Nodes near no face are
// reported in the rejected nodes.
PlacedSamples place_nodes(std::span<const CadFace> faces, const FaceSet& set, const DeflectionSamples& samples,
                          SurfaceReconstructionReport& report, std::vector<NodePlacement>& placements) {
  const std::vector<SurfaceProjector>& projectors = set.projectors;
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
      placements.push_back({j, f, p.where.u, p.where.v, p.distance});
    }
  }
  return placed;
}

/// Under FarNodePolicy::reject, nodes farther than the tolerance from every face are an error.
void refuse_far_nodes(const DeflectionSamples& samples, const ReconstructionOptions& options,
                      const SurfaceReconstructionReport& report, double size) {
  if (!report.rejected_nodes.empty() && options.far_nodes == FarNodePolicy::reject) {
    const std::string how = options.tolerance > 0.0 ? "the given tolerance"
                                                    : "the default tolerance, " + format(options.relative_tolerance) +
                                                          " of the faces' size " + format(size);
    throw InputError::in(samples.source, std::to_string(report.rejected_nodes.size()) + " of " +
                                             std::to_string(samples.size()) + " FEM nodes are farther than " +
                                             format(report.tolerance) + " (" + how + ") from the CAD faces: " +
                                             detail::list_nodes(report.rejected_nodes));
  }
}

// d(t, s) on each face through its nodes.
std::vector<BSplineSurface> fit_fields(std::span<const CadFace> faces, const PlacedSamples& placed,
                                       const DeflectionSamples& samples, const ReconstructionOptions& options,
                                       SurfaceReconstructionReport& report) {
  std::vector<BSplineSurface> fields;
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
      fields.push_back(std::move(fit.field));
    } catch (const InputError& e) {
      throw InputError::in(samples.source, "CAD face " + std::to_string(id) + ": " + e.what());
    }
  }
  return fields;
}

// The fields made to meet along the edges the faces share (field_joins.hpp); returns the
// largest gap left along edges that cross a face's rectangle.
double join_along_edges(std::span<const CadFace> faces, const FaceSet& set, std::vector<BSplineSurface>& fields,
                        SurfaceReconstructionReport& report) {
  const EdgeJoins joins = edge_joins(faces, set);
  report.shared_edges = joins.shared;
  // Uneven edges, and edges across a face's rectangle, count as joined where their fields
  // meet to 1e-10 of the wall's size. The rows joined along sides stay as they are.
  const double join_tolerance = 1e-10 * set.size;
  report.joined_edges = detail::join_fields(fields, joins.sides, joins.uneven, joins.corners, join_tolerance).joined;
  double crossing_gap = 0.0;
  for (const double gap : detail::join_sides_to_faces(fields, faces, set.projectors, joins.on_faces,
                                                      joined_sides(joins), join_tolerance)) {
    crossing_gap = std::max(crossing_gap, gap);
    if (gap <= join_tolerance) ++report.joined_edges;
  }
  std::vector<detail::FaceSide> kept = joined_sides(joins);
  for (const detail::SideOnFace& e : joins.on_faces) kept.push_back({e.a, e.side});
  for (const double gap : detail::join_across_faces(fields, faces, set.projectors, joins.across, kept, join_tolerance)) {
    crossing_gap = std::max(crossing_gap, gap);
    if (gap <= join_tolerance) ++report.joined_edges;
  }
  return crossing_gap;
}

// The fit's residuals measured again on the joined fields.
void measure_residuals(const PlacedSamples& placed, const std::vector<BSplineSurface>& fields,
                       SurfaceReconstructionReport& report) {
  report.max_node_residual = 0.0;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    SurfaceFitReport& fit = report.faces[f].fit;
    fit.u_poles = fields[f].u_count();  // knots inserted along joined edges add poles
    fit.v_poles = fields[f].v_count();
    fit.max_residual = 0.0;
    double squares = 0.0;
    for (const FieldSample& sample : placed.on_face[f]) {
      const double r = distance(fields[f].point(sample.u, sample.v), sample.value);
      fit.max_residual = std::max(fit.max_residual, r);
      squares += r * r;
    }
    fit.rms_residual = std::sqrt(squares / static_cast<double>(placed.on_face[f].size()));
    report.max_node_residual = std::max(report.max_node_residual, fit.max_residual);
  }
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
  const double size = set.size;
  report.tolerance = options.tolerance > 0.0 ? options.tolerance : options.relative_tolerance * size;

  const PlacedSamples placed = place_nodes(faces, set, samples, report, out.placements);
  refuse_far_nodes(samples, options, report, size);
  out.fields = fit_fields(faces, placed, samples, options, report);
  const double crossing_gap = join_along_edges(faces, set, out.fields, report);
  measure_residuals(placed, out.fields, report);
  report.max_edge_gap = std::max(edge_gap(faces, set.projectors, out.fields, 1e-6 * size), crossing_gap);
  return out;
}

}  // namespace hotmesh::geometry
