// hotmesh geometry: where the CAD faces of a wall on faces meet (surface_shape.hpp): how far the
// wall turns across their shared edges and trimmed edges, the creases and their regions, the
// faces on either side of a crease as shapes of their own, and the nearest point of a crease's
// edge (a side of a face, or a trimming curve).
#include "hotmesh/geometry/surface_shape.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <shared_mutex>
#include <stdexcept>
#include <utility>

#include "reconstruct/cad_face_set.hpp"

namespace hotmesh::geometry {

namespace {

using detail::face_groups;
using detail::on_side;

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

/// The unit direction across an edge (direction `along`) in a face's tangent plane (derivatives
/// `on`), either way.
Vec3 across_edge(const SurfaceDerivatives& on, const Vec3& along) {
  const Vec3 across = cross(cross(on.du, on.dv), along);
  return across / norm(across);
}

/// The direction into face b across an edge that crosses b's rectangle (a side of another face
/// lies on b there: a trimming curve of b): `across` the edge in b's tangent plane, towards the
/// side b's trimming loops keep (`kept`: +1 along `across`, -1 against it). Where they do not
/// tell (0: a face without loops), away from the side the other face leans to: the trimmed face
/// is taken to end where the other leaves it, so the wall turns by the other face's angle to b
/// (its mirror image, leaning the other way, alike).
Vec3 into_trimmed_face(const Vec3& across, const Vec3& into_other, int kept) {
  if (kept != 0) return kept * across;
  return dot(into_other, across) > 0.0 ? -across : across;
}

}  // namespace

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
      return std::minmax(c.faces[0], c.faces[1]) == std::minmax(static_cast<int>(a), static_cast<int>(b));
    });
  };
  std::vector<detail::TracedEdge> trimmed;
  for (const TrimmedEdge& e : trimmed_edges_) trimmed.push_back({e.faces[0], e.faces[1], {}, {}, {}});
  std::vector<std::vector<std::size_t>> groups = face_groups(neighbours_, joined, trimmed);
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
  const auto add = [&](int other) {
    if (sides.empty()) sides.push_back(std::make_shared<FaceOfWall>(shared_from_this(), where.face));
    sides.push_back(std::make_shared<FaceOfWall>(shared_from_this(), other));
  };
  for (std::size_t side = 0; side < 4; ++side) {
    const int other = neighbours_[f][side];
    if (!at_side[side] || other < 0) continue;
    if (turn_into(f, static_cast<int>(side), here, static_cast<std::size_t>(other), 0.0) >= min_angle) add(other);
  }
  // A point of f on a trimming curve: a side of another face that crosses f's rectangle.
  for (std::size_t g = 0; g < faces_.size(); ++g) {
    const int side = side_shared_with(static_cast<int>(g), where.face);
    if (g == f || side < 0 || side_shared_with(where.face, static_cast<int>(g)) >= 0) continue;
    const ShapePoint on_side = project_on_side(g, side, here.point, 0.0);
    if (on_side.distance > 1e-9 * size_) continue;
    const SurfaceDerivatives there = evaluate(g, on_side.parameter.t, on_side.parameter.s, 0.0);
    if (turn_into(g, side, there, f, 0.0) >= min_angle) add(static_cast<int>(g));
  }
  // A point of f on a trimming curve that is also the other face's.
  for (const TrimmedEdge& e : trimmed_edges_) {
    const int k = e.faces[0] == f ? 0 : e.faces[1] == f ? 1 : -1;
    if (k < 0) continue;
    const ShapePoint on = project_on_trim(e, k, here.point, 0.0);
    if (on.distance > 1e-9 * size_) continue;
    const ShapePoint on_first = k == 0 ? on : project_on_trim(e, 0, here.point, 0.0);
    if (turn_across(e, on_first, 0.0) >= min_angle) add(static_cast<int>(e.faces[static_cast<std::size_t>(1 - k)]));
  }
  return sides;
}

double SurfaceShape::turn_into(std::size_t f, int side, const SurfaceDerivatives& here, std::size_t g,
                               double lambda) const {
  const Vec3 into_f = into_face(here, side);
  const int other_side = side_shared_with(static_cast<int>(g), static_cast<int>(f));
  if (other_side >= 0) {
    const ShapePoint there = project_on_side(g, other_side, here.point, lambda);
    return turn_angle(into_f, into_face(evaluate(g, there.parameter.t, there.parameter.s, lambda), other_side));
  }
  const ShapePoint there = project_on_face(static_cast<int>(g), here.point, lambda, kNoHint);
  const SurfaceDerivatives on_g = evaluate(g, there.parameter.t, there.parameter.s, lambda);
  const Vec3 across = across_edge(on_g, side < 2 ? here.du : here.dv);
  return turn_angle(into_f, into_trimmed_face(across, into_f, kept_side(g, there.parameter, on_g, across)));
}

// A step of 1e-4 of the wall's size either way, in (t, s) by least squares on the face's
// derivatives: a hundred times the loops' polyline error, so the loops are not mistaken at it.
int SurfaceShape::kept_side(std::size_t face, const ShapeParameter& at, const SurfaceDerivatives& d,
                            const Vec3& across) const {
  const TrimRegion* region = regions_of_faces_[face].get();
  if (region == nullptr) return 0;
  const double a = dot(d.du, d.du), b = dot(d.du, d.dv), c = dot(d.dv, d.dv);
  const double det = a * c - b * b;
  if (!(det > 0.0)) return 0;
  const Vec3 step = 1e-4 * size_ * across;
  const double g0 = dot(step, d.du), g1 = dot(step, d.dv);
  const double dt = (c * g0 - b * g1) / det, ds = (a * g1 - b * g0) / det;
  const bool ahead = region->contains(at.t + dt, at.s + ds), behind = region->contains(at.t - dt, at.s - ds);
  return ahead == behind ? 0 : ahead ? 1 : -1;
}

// A scan of at most 65 of the curve's vertices finds the span; the golden-section search runs
// over the scan's steps on either side of the nearest.
ShapePoint SurfaceShape::project_on_trim(const TrimmedEdge& e, int k, const Vec3& p, double lambda) const {
  const std::size_t face = e.faces[static_cast<std::size_t>(k)];
  const std::vector<Vec2>& q = curve_of(e, k);
  const std::size_t last = q.size() - 1;
  const std::size_t stride = std::max<std::size_t>(1, last / 64);
  std::size_t nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0;; i = std::min(i + stride, last)) {
    const double d = distance(evaluate(face, q[i].x, q[i].y, lambda).point, p);
    if (d < best) best = d, nearest = i;
    if (i == last) break;
  }
  // The scan's steps on either side of the nearest; on a closed curve (a circle trimming both
  // faces) its first and last points are one, and the nearest point may lie past it: both ends.
  const auto search = [&](std::size_t from, std::size_t to) {
    return curve_point(q, nearest_on_curve(q, static_cast<double>(from), static_cast<double>(to), p,
                                           [&](const Vec2& x) { return evaluate(face, x.x, x.y, lambda); }));
  };
  Vec2 uv = search(nearest >= stride ? nearest - stride : 0, std::min(nearest + stride, last));
  const bool closed = distance(q.front(), q.back()) <= 1e-9 * distance(q.front(), q[last / 2]);
  if (closed && (nearest == 0 || nearest == last)) {
    const Vec2 other = nearest == 0 ? search(last - stride, last) : search(0, stride);
    if (distance(evaluate(face, other.x, other.y, lambda).point, p) < distance(evaluate(face, uv.x, uv.y, lambda).point, p)) {
      uv = other;
    }
  }
  const SurfaceDerivatives d = evaluate(face, uv.x, uv.y, lambda);
  const Vec3 n = cross(d.du, d.dv);
  return {d.point, n / norm(n), {uv.x, uv.y, static_cast<int>(face)}, distance(d.point, p)};
}

// The edge's direction from the first face's derivatives and its curve's tangent there (the
// curve's parameters on either side of the point); across it in each face's tangent plane, the
// way each face's loops keep.
double SurfaceShape::turn_across(const TrimmedEdge& e, const ShapePoint& on_first, double lambda) const {
  const std::size_t a = e.faces[0], b = e.faces[1];
  const std::vector<Vec2>& q = curve_of(e, 0);
  const Vec2 here{on_first.parameter.t, on_first.parameter.s};
  const auto near = std::min_element(q.begin(), q.end(), [&](const Vec2& x, const Vec2& y) {
    return distance(x, here) < distance(y, here);
  });
  const auto i = static_cast<std::size_t>(near - q.begin());
  const Vec2 step = q[std::min(i + 1, q.size() - 1)] - q[i > 0 ? i - 1 : 0];
  const SurfaceDerivatives on_a = evaluate(a, here.x, here.y, lambda);
  const Vec3 along = step.x * on_a.du + step.y * on_a.dv;
  const ShapePoint there = project_on_trim(e, 1, on_first.point, lambda);
  const SurfaceDerivatives on_b = evaluate(b, there.parameter.t, there.parameter.s, lambda);
  const Vec3 across_a = across_edge(on_a, along), across_b = across_edge(on_b, along);
  const int kept_a = kept_side(a, on_first.parameter, on_a, across_a);
  const int kept_b = kept_side(b, there.parameter, on_b, across_b);
  if (kept_a == 0 || kept_b == 0) return 0.0;
  return turn_angle(kept_a * across_a, kept_b * across_b);
}

int SurfaceShape::side_shared_with(int face, int other) const {
  const auto& sides = neighbours_[static_cast<std::size_t>(face)];
  const auto it = std::find(sides.begin(), sides.end(), other);
  return it == sides.end() ? -1 : static_cast<int>(it - sides.begin());
}

// The side's curve C(f) = S(on_side(f)), f in [0, 1], minimises |C(f) - p|^2: the best of
// uniform samples, then Newton on C'(f).(C(f) - p) = 0, kept on the side. A closed side (a
// cylinder's circle, whose ends meet at the face's seam) has no ends: Newton goes on across the
// seam (f modulo 1), so a point just before the seam finds its nearest point there, not the seam.
ShapePoint SurfaceShape::project_on_side(std::size_t face, int side, const Vec3& p, double lambda) const {
  const ParameterRectangle r = faces_[face].surface.domain();
  const bool along_t = side < 2;
  const double span = along_t ? r.u_last - r.u_first : r.v_last - r.v_first;
  const bool closed = closed_sides_[face][static_cast<std::size_t>(side)];
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
    const double step = g / (h > 0.0 ? h : std::max(dot(d1, d1), 1e-300));
    const double next = closed ? f - step - std::floor(f - step) : std::clamp(f - step, 0.0, 1.0);
    const double moved = closed ? next - f - std::round(next - f) : next - f;
    const bool done = std::abs(moved) <= 1e-14;
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
      // Once per edge: from the lower face where the faces share sides, from the face whose
      // side it is where that side crosses the other's rectangle (a trimming curve).
      if (g < 0 || side_shared_with(static_cast<int>(f), g) != side) continue;
      if (side_shared_with(g, static_cast<int>(f)) >= 0 && g <= static_cast<int>(f)) continue;
      const ParameterRectangle r = faces_[f].surface.domain();
      ShapeCrease crease{{static_cast<int>(f), g}, 0.0};
      for (const double lambda : {0.0, 1.0}) {
        for (int k = 0; k <= kSamples; ++k) {
          const auto [t, s] = on_side(r, side, static_cast<double>(k) / kSamples);
          const SurfaceDerivatives here = evaluate(f, t, s, lambda);
          crease.angle = std::max(crease.angle, turn_into(f, side, here, static_cast<std::size_t>(g), lambda));
        }
      }
      if (crease.angle >= min_angle) found.push_back(crease);
    }
  }
  for (const TrimmedEdge& e : trimmed_edges_) {
    ShapeCrease crease{{static_cast<int>(e.faces[0]), static_cast<int>(e.faces[1])}, 0.0};
    const std::vector<Vec2>& q = curve_of(e, 0);
    for (const double lambda : {0.0, 1.0}) {
      for (int k = 0; k <= kSamples; ++k) {  // inside the edge: its ends are corners of loops
        const Vec2 x = curve_point(q, static_cast<double>(q.size() - 1) * (k + 0.5) / (kSamples + 1));
        const ShapePoint on_a{evaluate(e.faces[0], x.x, x.y, lambda).point, {}, {x.x, x.y, crease.faces[0]}, 0.0};
        crease.angle = std::max(crease.angle, turn_across(e, on_a, lambda));
      }
    }
    if (crease.angle >= min_angle) found.push_back(crease);
  }
  return found;
}

CreasePoint SurfaceShape::crease_point(const ShapeCrease& crease, const Vec3& p, double lambda) const {
  const int a = crease.faces[0], b = crease.faces[1];
  const int count = static_cast<int>(faces_.size());
  const int side_a = a >= 0 && a < count && b >= 0 && b < count ? side_shared_with(a, b) : -1;
  const int side_b = side_a >= 0 ? side_shared_with(b, a) : -1;
  if (side_a < 0) return crease_point_on_trims(crease, p, lambda);
  const ShapePoint on_a = project_on_side(static_cast<std::size_t>(a), side_a, p, lambda);
  // b's side along it, or b itself where a's side crosses b's rectangle (a trimming curve).
  const ShapePoint on_b = side_b >= 0 ? project_on_side(static_cast<std::size_t>(b), side_b, on_a.point, lambda)
                                      : project_on_face(b, on_a.point, lambda, kNoHint);
  return {on_a.point, {on_a.normal, on_b.normal}};
}

// The nearest of the trimmed edges between the crease's faces (two faces may share several).
CreasePoint SurfaceShape::crease_point_on_trims(const ShapeCrease& crease, const Vec3& p, double lambda) const {
  std::optional<CreasePoint> best;
  double nearest = std::numeric_limits<double>::infinity();
  for (const TrimmedEdge& e : trimmed_edges_) {
    const int first = static_cast<int>(e.faces[0]), second = static_cast<int>(e.faces[1]);
    if (std::minmax(first, second) != std::minmax(crease.faces[0], crease.faces[1])) continue;
    const int k = crease.faces[0] == first ? 0 : 1;
    const ShapePoint on_a = project_on_trim(e, k, p, lambda);
    if (on_a.distance >= nearest) continue;
    nearest = on_a.distance;
    best = CreasePoint{on_a.point, {on_a.normal, project_on_trim(e, 1 - k, on_a.point, lambda).normal}};
  }
  if (!best) throw std::logic_error("SurfaceShape::crease_point: the faces share no edge");
  return *best;
}

}  // namespace hotmesh::geometry
