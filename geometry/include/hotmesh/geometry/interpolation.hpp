// hotmesh geometry: global B-spline interpolation, the linear system of the paper's eq. (21),
//     values_j = sum_i N_i^q(t_j) T_i,   j = 1..k,
// with averaged knots (Piegl & Tiller, The NURBS Book, eq. 9.8), solved by a banded LU
// decomposition. Data ordered by t make the collocation matrix banded (bandwidth q on each
// side) and, with averaged knots, totally positive, so no pivoting is needed.
#pragma once

#include <span>
#include <vector>

#include "hotmesh/geometry/bspline_curve.hpp"
#include "hotmesh/core/vec2.hpp"

namespace hotmesh::geometry {

/// Flat knot vector of degree `degree` for interpolation at `parameters` (strictly increasing,
/// at least degree + 1): clamped at the first and last parameter, interior knots the averages
/// of `degree` consecutive parameters (eq. 9.8). Throws std::invalid_argument otherwise.
std::vector<double> averaged_knots(std::span<const double> parameters, int degree);

/// The degree-`degree` B-spline c with c(parameters[j]) = values[j] for every j (eq. 21).
/// Throws std::invalid_argument if the parameters are not strictly increasing, there are
/// fewer than degree + 1 of them, or the sizes differ.
BSplineCurve2d interpolate(std::span<const double> parameters, std::span<const Vec2> values, int degree);

}  // namespace hotmesh::geometry
