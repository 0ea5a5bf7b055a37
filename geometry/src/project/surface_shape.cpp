// hotmesh geometry: a wall on CAD faces deflected by their fields d(t, s) as a BoundaryShape
// (surface_shape.hpp): the faces reaching beyond their free edges, their trimming loops, the
// projector of each stage S + lambda d (section 4.3) and projection onto every face, a crease
// region or one face (the reconstruction is face_reconstruction.cpp, the creases where faces
// meet surface_creases.cpp, the scattered-data wall scattered_shape.cpp).
#include "hotmesh/geometry/surface_shape.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <stdexcept>
#include <utility>

#include "reconstruct/cad_face_set.hpp"

namespace hotmesh::geometry {

namespace {

using detail::FaceSet;
using detail::on_side;

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

}  // namespace

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
  size_ = set.size;
  std::vector<double> deflection(faces_.size());
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    deflection[f] = std::max(largest_pole(after_[f]), before_.empty() ? 0.0 : largest_pole(before_[f]));
  }
  reach_ = reaches(faces_, set, deflection);
  // Sides whose ends meet (on the CAD face), though they are not points: closed curves.
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const ParameterRectangle r = faces_[f].surface.domain();
    std::array<bool, 4> closed{};
    for (int side = 0; side < 4; ++side) {
      const auto end_point = [&](double at) {
        const auto [t, u] = on_side(r, side, at);
        return faces_[f].surface.point(t, u);
      };
      closed[static_cast<std::size_t>(side)] = !set.collapsed[f][static_cast<std::size_t>(side)] &&
                                               distance(end_point(0.0), end_point(1.0)) <= 1e-9 * size_;
    }
    closed_sides_.push_back(closed);
  }
  // A trimming curve binds where the wall goes on across it: another face of the wall names its
  // edge (faces from separate surfaces too: the reader sews them).
  std::map<int, int> faces_naming;  // CAD edge -> how many faces of the wall name it
  for (const CadFace& face : faces_) {
    for (const FaceEdge& e : face.edges) ++faces_naming[e.edge];
  }
  for (const CadFace& face : faces_) {
    regions_of_faces_.push_back(trim_region(face, [&](int edge) { return faces_naming[edge] > 1; }));
  }
  // Edges across both faces' rectangles: each face's curve of the edge runs inside it.
  const auto across = [&](std::size_t f, int edge) -> std::optional<std::size_t> {
    const std::vector<TrimCurve>& trims = faces_[f].trims;
    for (std::size_t c = 0; c < trims.size(); ++c) {
      if (trims[c].edge == edge && trims[c].points.size() >= 2 &&
          !along_rectangle_side(trims[c].points, faces_[f].surface.domain())) {
        return c;
      }
    }
    return std::nullopt;
  };
  for (std::size_t a = 0; a < faces_.size(); ++a) {
    for (const FaceEdge& e : faces_[a].edges) {
      const auto on_a = across(a, e.edge);
      if (!on_a) continue;
      for (std::size_t b = a + 1; b < faces_.size(); ++b) {
        if (const auto on_b = across(b, e.edge)) trimmed_edges_.push_back({{a, b}, {*on_a, *on_b}});
      }
    }
  }
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
      patch.region = regions_of_faces_[f];
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

SurfaceShapeFit make_surface_shape(std::vector<CadFace> faces, const DeflectionSamples& samples,
                                   const ReconstructionOptions& options, const DeflectionSamples* previous) {
  FaceDeflections after = reconstruct_on_faces(faces, samples, options);
  std::vector<BSplineSurface> before;
  if (previous) before = reconstruct_on_faces(faces, *previous, options).fields;
  auto shape = std::make_shared<SurfaceShape>(std::move(faces), std::move(after.fields), std::move(before));
  return {std::move(shape), std::move(after.report)};
}

std::shared_ptr<SurfaceShape> undeformed_surface_shape(std::vector<CadFace> faces) {
  std::vector<BSplineSurface> zero;
  for (const CadFace& f : faces) {
    const ParameterRectangle r = f.surface.domain();
    zero.emplace_back(1, 1, std::vector<double>{r.u_first, r.u_first, r.u_last, r.u_last},
                      std::vector<double>{r.v_first, r.v_first, r.v_last, r.v_last}, std::vector<Vec3>(4));
  }
  return std::make_shared<SurfaceShape>(std::move(faces), std::move(zero));
}

}  // namespace hotmesh::geometry
