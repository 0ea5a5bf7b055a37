// hotmesh geometry: the projector on trimmed patches (surface_projector.hpp): a Newton result
// outside a patch's trimming loops moved onto the nearest binding loop.
#include <algorithm>
#include <cmath>
#include <limits>

#include "hotmesh/geometry/surface_projector.hpp"

namespace hotmesh::geometry {

void SurfaceProjector::sample_rims() {
  rims_.resize(patches_.size());
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    if (!patches_[i].region) continue;
    for (const TrimRegion::Curve& curve : patches_[i].region->curves()) {
      std::vector<Vec3>& rim = rims_[i].emplace_back();
      for (const Vec2& q : curve.points) rim.push_back(evaluate(static_cast<int>(i), q.x, q.y).point);
    }
  }
}

SurfaceProjector::Local SurfaceProjector::newton(const Vec3& p, int patch, double u, double v, RimCache* cache) const {
  const Local local = newton_in_rectangle(p, patch, u, v);
  const SurfacePatch& on = patches_[static_cast<std::size_t>(patch)];
  if (on.region == nullptr || on.region->contains(local.where.u, local.where.v)) return local;
  const double same_u = 1e-9 * (on.domain.u_last - on.domain.u_first);
  const double same_v = 1e-9 * (on.domain.v_last - on.domain.v_first);
  if (cache != nullptr && cache->patch == patch && std::abs(cache->u - local.where.u) <= same_u &&
      std::abs(cache->v - local.where.v) <= same_v) {
    Local again = cache->rim;
    again.iterations = local.iterations;
    return again;
  }
  const Local rim = to_rim(p, local);
  if (cache != nullptr) *cache = {patch, local.where.u, local.where.v, rim};
  return rim;
}

// The nearest chord of the loops' polylines (between their vertices' points on the surface)
// picks the curve and the place along it; a golden-section search over the spans next to it,
// along the curve in (u, v), finds the nearest point of the surface there.
SurfaceProjector::Local SurfaceProjector::to_rim(const Vec3& p, const Local& outside) const {
  const auto k = static_cast<std::size_t>(outside.where.patch);
  const std::vector<TrimRegion::Curve>& curves = patches_[k].region->curves();
  std::size_t best_curve = 0, best_chord = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < rims_[k].size(); ++c) {
    const std::vector<Vec3>& rim = rims_[k][c];
    for (std::size_t i = 0; i + 1 < rim.size(); ++i) {
      const Vec3 chord = rim[i + 1] - rim[i];
      const double length2 = dot(chord, chord);
      const double f = length2 > 0.0 ? std::clamp(dot(p - rim[i], chord) / length2, 0.0, 1.0) : 0.0;
      const Vec3 off = rim[i] + f * chord - p;
      const double d2 = dot(off, off);
      if (d2 < best) best = d2, best_curve = c, best_chord = i;
    }
  }
  if (best == std::numeric_limits<double>::infinity() || !curves[best_curve].binding) return outside;
  const std::vector<Vec2>& q = curves[best_curve].points;
  const double a = best_chord > 0 ? static_cast<double>(best_chord - 1) : 0.0;
  const double b = std::min(static_cast<double>(best_chord + 2), static_cast<double>(q.size() - 1));
  int evaluations = 0;
  const double x = nearest_on_curve(q, a, b, p, [&](const Vec2& uv) {
    ++evaluations;
    return evaluate(outside.where.patch, uv.x, uv.y);
  });
  const Vec2 uv = curve_point(q, x);
  const SurfaceDerivatives value = evaluate(outside.where.patch, uv.x, uv.y);
  return {{outside.where.patch, uv.x, uv.y}, value, distance(value.point, p), outside.iterations + evaluations, true, true};
}

}  // namespace hotmesh::geometry
