// hotmesh geometry: what every kind of parametric surface S(u, v) hands to the algorithms that
// work on it (closest points, normals, sliding): its point and first and second partial
// derivatives at (u, v), and its parameter rectangle. B-spline faces, deformed faces
// S(u, v) + d(u, v) and any analytic surface give the same struct, so one projector serves all.
#pragma once

#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

/// S and its partial derivatives S_u, S_v, S_uu, S_uv, S_vv at one (u, v).
struct SurfaceDerivatives {
  Vec3 point;
  Vec3 du;
  Vec3 dv;
  Vec3 duu;
  Vec3 duv;
  Vec3 dvv;
};

/// Sum of two surfaces' derivatives: (S + d) and its derivatives, term by term.
constexpr SurfaceDerivatives operator+(const SurfaceDerivatives& a, const SurfaceDerivatives& b) {
  return {a.point + b.point, a.du + b.du, a.dv + b.dv, a.duu + b.duu, a.duv + b.duv, a.dvv + b.dvv};
}
/// All six vectors scaled by s (a displacement field at a stage lambda of the deformation).
constexpr SurfaceDerivatives operator*(double s, const SurfaceDerivatives& a) {
  return {s * a.point, s * a.du, s * a.dv, s * a.duu, s * a.duv, s * a.dvv};
}

/// The parameter rectangle [u_first, u_last] x [v_first, v_last] of a surface.
struct ParameterRectangle {
  double u_first = 0.0;
  double u_last = 1.0;
  double v_first = 0.0;
  double v_last = 1.0;
};

}  // namespace hotmesh::geometry
