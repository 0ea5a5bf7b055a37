// hotmesh geometry: the concrete boundaries behind BoundaryShape, the interface the solver in
// deform calls to place sliding nodes:
//   PlanarCurveShape  a (deflected) curve in the x-y plane, for 2D cases;
//   RevolvedShape     a surface of revolution: a (deflected) meridional curve (r, z) and an
//                     axis; points are projected in the meridional plane through them (Fig. 4);
//   PlaneShape        a fixed plane, for slip boundaries: orthogonal projection, constant
//                     normal, the stage lambda is ignored.
// make_revolved_shape / make_planar_shape build them from an undeformed curve and the FEM
// deflection samples (section 4.2, reconstruction.hpp) and report the fit. All three shapes are
// immutable after construction, so project() and at() are safe from any number of threads.
#pragma once

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::geometry {

class PlanarCurveShape final : public BoundaryShape {
 public:
  explicit PlanarCurveShape(DeflectedCurve curve) : projector_(std::move(curve)) {}

  /// Projects (p.x, p.y) onto the curve; the result keeps p.z. Normal as CurveProjection.
  ShapePoint project(const Vec3& p, double lambda, const ShapeParameter& hint = kNoHint,
                     const ParameterRange& range = {}) const override;
  /// The curve point at t, with z of `reference`.
  ShapePoint at(const ShapeParameter& where, double lambda, const Vec3& reference) const override;
  std::vector<ShapeFeature> features(double min_angle) const override;

  const CurveProjector& projector() const { return projector_; }

 private:
  CurveProjector projector_;
};

class RevolvedShape final : public BoundaryShape {
 public:
  /// `meridional` is the curve in (r, z) coordinates about `axis` (Axis::to_cylindrical).
  RevolvedShape(DeflectedCurve meridional, const Axis& axis) : projector_(std::move(meridional)), axis_(axis) {}

  /// Section 4.2, Fig. 4: p = (r, theta, z) about the axis; (r, z) is projected on the
  /// meridional curve and the result keeps theta. The normal is the curve's normal (in (r, z))
  /// turned into the meridional plane through p.
  ShapePoint project(const Vec3& p, double lambda, const ShapeParameter& hint = kNoHint,
                     const ParameterRange& range = {}) const override;
  ShapePoint at(const ShapeParameter& where, double lambda, const Vec3& reference) const override;
  /// The corners of the meridional curve: circles about the axis.
  std::vector<ShapeFeature> features(double min_angle) const override;

  const CurveProjector& projector() const { return projector_; }
  const Axis& axis() const { return axis_; }

 private:
  ShapePoint to_cartesian(const CurveProjection& q, double theta) const;

  CurveProjector projector_;
  Axis axis_;
};

class PlaneShape final : public BoundaryShape {
 public:
  /// Throws std::invalid_argument if the normal has zero length or a value is not finite.
  PlaneShape(const Vec3& origin, const Vec3& normal);

  ShapePoint project(const Vec3& p, double lambda, const ShapeParameter& hint = kNoHint,
                     const ParameterRange& range = {}) const override;
  /// The projection of `reference` (a plane has no curve parameter).
  ShapePoint at(const ShapeParameter& where, double lambda, const Vec3& reference) const override;

  const Vec3& origin() const { return origin_; }
  const Vec3& normal() const { return normal_; }

 private:
  Vec3 origin_;
  Vec3 normal_;
};

struct RevolvedShapeFit {
  RevolvedShape shape;
  ReconstructionReport report;
};

/// The deflected surface of revolution: cartesian or meridional samples taken to (r, z) about
/// `axis` (meridional_samples), eq. (21) on the meridional curve (reconstruct).
RevolvedShapeFit make_revolved_shape(const BSplineCurve2d& meridional, const Axis& axis,
                                     const DeflectionSamples& samples, const ReconstructionOptions& options = {});

struct PlanarShapeFit {
  PlanarCurveShape shape;
  ReconstructionReport report;
};

/// The deflected 2D boundary from a curve in the x-y plane and planar samples.
PlanarShapeFit make_planar_shape(const BSplineCurve2d& curve, const DeflectionSamples& samples,
                                 const ReconstructionOptions& options = {});
/// The deflected 2D boundary without CAD: the planar samples define the curve
/// (reconstruct_from_nodes).
PlanarShapeFit make_planar_shape(const DeflectionSamples& samples, const ReconstructionOptions& options = {});

}  // namespace hotmesh::geometry
