// hotmesh geometry: the deflection field d(t, s) of one CAD face, fitted to the deflections of
// the FEM nodes projected onto the face at (t, s). This is the paper's section 4.2 for faces of
// any shape ("a B-Spline of the deformed boundary is constructed by global interpolation of the
// deflection data, performed in the parametric space (t, s)"), the surface analogue of eq. (21)
// in displacement form: the deformed face is S'(t, s) = S(t, s) + d(t, s).
//
// Nodes that form a tensor grid in (t, s) are interpolated exactly (global interpolation);
// scattered nodes, through which tensor-product interpolation is not defined, get a regularised
// least-squares B-spline. Both reproduce fields that are polynomials of degree <= q in t and in
// s to round-off. The field is a BSplineSurface whose poles are deflection vectors, not points.
// In this header u and v are the face's parameters t and s.
#pragma once

#include <cstddef>
#include <span>

#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/geometry/parametric_surface.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

/// One FEM node on a face: its parameters (u, v) = (t, s) and its deflection.
struct FieldSample {
  double u = 0.0;
  double v = 0.0;
  Vec3 value;
};

enum class SurfaceFitMethod {
  interpolation,  ///< the nodes form a tensor grid: exact at every node
  least_squares,  ///< scattered nodes: regularised least squares
};

struct SurfaceFitOptions {
  /// q in u and in v, 1..kMaxReconstructionDegree; 1 matches linear FEM elements.
  int degree = 1;
  /// Least squares only: weight of the smoothness penalty against the data term,
  /// dimensionless (the penalty is scaled by the ratio of the two terms' traces). Fields that
  /// are polynomials of degree <= q are reproduced whatever its value; larger values smooth
  /// more and cost accuracy, smaller ones leave knot spans far from nodes less constrained.
  double smoothing = 1e-2;
  /// Least squares only: the length on the face of its u range over that of its v range. The
  /// control net's knot spans are then about as long as they are wide on the face. The default
  /// 1 takes the parameter rectangle, scaled to a unit square, as the face's shape.
  double aspect = 1.0;
};

struct SurfaceFitReport {
  SurfaceFitMethod method = SurfaceFitMethod::interpolation;
  int degree = 1;
  std::size_t samples = 0;
  std::size_t u_poles = 0;
  std::size_t v_poles = 0;
  double max_residual = 0.0;  ///< max |d(u_j, v_j) - value_j| over the samples
  double rms_residual = 0.0;  ///< root mean square of the same
};

struct SurfaceFit {
  BSplineSurface field;  ///< d(u, v) on `domain`; poles are deflections
  SurfaceFitReport report;
};

/// A face's length along u over its length along v (their means over 5 x 5 samples of S_u and
/// S_v, times the parameter ranges), within [1e-6, 1e6]; 1 for a degenerate face: how its
/// parameters are stretched on it (SurfaceFitOptions::aspect, and its proportions in pictures).
double face_aspect(const BSplineSurface& face);

/// d(u, v) over `domain` from `samples` (section 4.2). Samples whose (u, v) form a tensor grid
/// (within 1e-7 of the domain's extent, at least q + 1 values each way, every pair present
/// once) are interpolated; any others are fitted by least squares. Between the nodes and the
/// domain's edges the field is extrapolated: the grid's end polynomial pieces continued, or
/// the smoothest continuation the least-squares penalty allows. `domain` is the face's
/// parameter rectangle or, for a face much larger than the region its FEM nodes cover (a full
/// cylinder under a sector model), that region with a margin.
///
/// Throws hotmesh::InputError (its message speaks of "this face"; the caller names the face)
/// for options out of range, deflections that are not finite, and nodes that cannot determine
/// a degree-q field: fewer than (q + 1)^2, fewer than q + 1 distinct values of u or of v, all
/// on one line or curve of the parameter plane, or on too small a part of the domain. Throws
/// std::invalid_argument for an empty or non-finite domain, or a sample outside it.
SurfaceFit fit_surface_field(std::span<const FieldSample> samples, const ParameterRectangle& domain,
                             const SurfaceFitOptions& options = {});

}  // namespace hotmesh::geometry
