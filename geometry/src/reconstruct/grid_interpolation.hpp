// hotmesh geometry (internal): global interpolation of values on a tensor grid of parameters by
// a B-spline surface on given knots (The NURBS Book, section 9.2.5). Shared by the deflection
// field through FEM nodes on a grid (surface_fit.cpp) and the deformed face S + d of a rational
// face in B-spline form (deformed_face.cpp).
#pragma once

#include <span>
#include <vector>

#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry::detail {

/// The poles (u-major, as BSplineSurface) of the surface of degrees (p, q) on the flat knots
/// `u_knots`, `v_knots` whose value at (u[i], v[j]) is values[i * v.size() + j]. There must be
/// one parameter per pole in each direction, each inside the support of its basis function
/// (Schoenberg-Whitney: averaged knots or Greville abscissae satisfy it). Throws
/// std::logic_error if the collocation matrices are singular all the same.
std::vector<Vec3> interpolate_on_grid(std::span<const double> u_knots, int p, std::span<const double> u,
                                      std::span<const double> v_knots, int q, std::span<const double> v,
                                      std::span<const Vec3> values);

}  // namespace hotmesh::geometry::detail
