// hotmesh geometry (internal): B-spline basis functions and their derivatives on a flat knot
// vector (Piegl & Tiller, The NURBS Book, section 2.3). Shared by curve and surface
// evaluation; fixed-size stack storage, no allocation.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "hotmesh/geometry/bspline_curve.hpp"

namespace hotmesh::geometry::detail {

inline constexpr std::size_t kMaxOrder = static_cast<std::size_t>(kMaxBSplineDegree) + 1;

/// ders[k][j]: k-th derivative (k = 0, 1, 2) of N_{span - degree + j}(t), j = 0..degree.
using BasisDerivatives = std::array<std::array<double, kMaxOrder>, 3>;

/// The span i (degree <= i < pole_count) with knots[i] <= t < knots[i+1]; the last span for
/// t at or beyond the end, the first for t before the start.
std::size_t find_span(std::span<const double> knots, int degree, std::size_t pole_count, double t);

/// Basis functions of `degree` at t on knot span `span` and their derivatives up to `order`
/// (0..2); derivatives above the degree are zero. knots[span] < knots[span + 1] is required.
void basis_derivatives(std::span<const double> knots, int degree, std::size_t span, double t, int order,
                       BasisDerivatives& ders);

}  // namespace hotmesh::geometry::detail
