// hotmesh geometry: the deformed face S'(t, s) = S(t, s) + d(t, s) of section 4.2 (displacement
// form, surface_shape.hpp) as one B-spline surface, so that CAD systems can read it (STEP, IGES:
// cad_export.hpp) in the face's own parameters.
//
// For a polynomial face the sum is exact: S and d are brought to a common degree (degree
// elevation) and common knots (knot insertion), which changes neither, and their poles are
// added. A rational face (weights) cannot be summed so: S + d = (w S + w d) / w, and w d is not a
// B-spline with S's weights. There S + d is interpolated on a tensor grid of its own (t, s)
// (Greville abscissae of S's and d's knots joined, each span subdivided until the interpolant
// lies within the tolerance of S + d at check points between the grid lines, or the spans run
// out). The grid's spline space holds d exactly, so what deviation there is comes from S's
// weights alone. Either way the result reports the largest deviation it measured.
#pragma once

#include <cstddef>

#include "hotmesh/geometry/bspline_surface.hpp"

namespace hotmesh::geometry {

struct DeformedFaceOptions {
  /// Rational faces: the interpolant is refined until it lies within this distance of S + d at
  /// every check point, relative to the face's size (the diagonal of its poles' box).
  double relative_tolerance = 1e-9;
  /// Rational faces: knot spans per direction the refinement stops at, tolerance met or not.
  std::size_t max_spans = 256;
};

struct DeformedFace {
  BSplineSurface surface;      ///< S + d on S's parameter rectangle
  bool exact = true;           ///< S + d itself (poles added); false: interpolated (rational S)
  double max_deviation = 0.0;  ///< max |surface - (S + d)| over the check points
  std::size_t check_points = 0;
};

/// S + d for the face `face` (S) and the displacement field `displacement` (d, poles are
/// displacement vectors) on the same parameter rectangle. A face whose weights are all equal is
/// polynomial and summed exactly. Throws std::invalid_argument if the rectangles differ or the
/// options are out of range.
DeformedFace deformed_face(const BSplineSurface& face, const BSplineSurface& displacement,
                           const DeformedFaceOptions& options = {});

}  // namespace hotmesh::geometry
