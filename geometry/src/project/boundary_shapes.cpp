// hotmesh geometry: planar curves, surfaces of revolution (projection in the meridional
// plane, Fig. 4) and planes behind the BoundaryShape interface.
#include "hotmesh/geometry/boundary_shapes.hpp"

#include <cmath>
#include <stdexcept>

namespace hotmesh::geometry {

CreasePoint BoundaryShape::crease_point(const ShapeCrease& /*crease*/, const Vec3& /*p*/, double /*lambda*/) const {
  throw std::logic_error("BoundaryShape::crease_point: the shape has no creases");
}

ShapePoint PlanarCurveShape::project(const Vec3& p, double lambda, const ShapeParameter& hint,
                                     const ParameterRange& range) const {
  const CurveProjection q = projector_.project({p.x, p.y}, lambda, hint.t, range);
  return {{q.point.x, q.point.y, p.z}, {q.normal.x, q.normal.y, 0.0}, {.t = q.parameter}, q.distance};
}

ShapePoint PlanarCurveShape::at(const ShapeParameter& where, double lambda, const Vec3& reference) const {
  const CurveProjection q = projector_.at(where.t, lambda);
  return {{q.point.x, q.point.y, reference.z}, {q.normal.x, q.normal.y, 0.0}, {.t = q.parameter}, 0.0};
}

std::vector<ShapeFeature> PlanarCurveShape::features(double min_angle) const {
  return projector_.curve().corners(min_angle);
}

ShapePoint RevolvedShape::to_cartesian(const CurveProjection& q, double theta) const {
  return {axis_.to_cartesian({q.point.x, theta, q.point.y}), axis_.meridional_vector(theta, q.normal.x, q.normal.y),
          {.t = q.parameter}, q.distance};
}

// Fig. 4-b: P' = (r + dr, theta + dtheta, z + dz) is projected in its meridional plane onto the
// meridional curve, giving (r_F, z_F); P_F = (r_F, theta + dtheta, z_F).
ShapePoint RevolvedShape::project(const Vec3& p, double lambda, const ShapeParameter& hint,
                                     const ParameterRange& range) const {
  const Cylindrical c = axis_.to_cylindrical(p);
  return to_cartesian(projector_.project({c.r, c.z}, lambda, hint.t, range), c.theta);
}

ShapePoint RevolvedShape::at(const ShapeParameter& where, double lambda, const Vec3& reference) const {
  return to_cartesian(projector_.at(where.t, lambda), axis_.to_cylindrical(reference).theta);
}

std::vector<ShapeFeature> RevolvedShape::features(double min_angle) const {
  return projector_.curve().corners(min_angle);
}

PlaneShape::PlaneShape(const Vec3& origin, const Vec3& normal) : origin_(origin) {
  const double length = norm(normal);
  if (!is_finite(origin) || !std::isfinite(length) || length == 0.0) {
    throw std::invalid_argument("plane needs a finite origin and a non-zero normal");
  }
  normal_ = normal / length;
}

ShapePoint PlaneShape::project(const Vec3& p, double /*lambda*/, const ShapeParameter& /*hint*/,
                               const ParameterRange& /*range*/) const {
  const double height = dot(p - origin_, normal_);
  return {p - height * normal_, normal_, {}, std::abs(height)};
}

ShapePoint PlaneShape::at(const ShapeParameter& /*where*/, double lambda, const Vec3& reference) const {
  ShapePoint q = project(reference, lambda);
  q.distance = 0.0;
  return q;
}

RevolvedShapeFit make_revolved_shape(const BSplineCurve2d& meridional, const Axis& axis,
                                     const DeflectionSamples& samples, const ReconstructionOptions& options) {
  Reconstruction fit = fit_curve(curve_samples(samples, &axis), &meridional, options);
  return {RevolvedShape(std::move(fit.curve), axis), std::move(fit.report)};
}

PlanarShapeFit make_planar_shape(const BSplineCurve2d& curve, const DeflectionSamples& samples,
                                 const ReconstructionOptions& options) {
  Reconstruction fit = fit_curve(curve_samples(samples, nullptr), &curve, options);
  return {PlanarCurveShape(std::move(fit.curve)), std::move(fit.report)};
}

PlanarShapeFit make_planar_shape(const DeflectionSamples& samples, const ReconstructionOptions& options) {
  Reconstruction fit = fit_curve(curve_samples(samples, nullptr), nullptr, options);
  return {PlanarCurveShape(std::move(fit.curve)), std::move(fit.report)};
}

}  // namespace hotmesh::geometry
