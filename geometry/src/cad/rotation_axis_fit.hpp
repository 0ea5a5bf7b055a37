// hotmesh geometry (internal): the axis of a surface of revolution from sampled points and
// normals. Every normal line of a surface of revolution meets its axis; in Plücker
// coordinates (a, c) of the axis (direction a, moment c = O x a) that is the linear condition
//     a . (P x n) + c . n = 0
// for each sample (P, n) (Pottmann & Randrup, "Rotational and helical surface approximation
// for reverse engineering", 1998). The smallest eigenvector of the 6x6 normal matrix solves it
// in the least-squares sense; the fit is accepted only if every normal then lies in its
// meridional plane within the angle tolerance. Spheres and planes, whose normals meet many
// lines, have no unique axis and give none.
#pragma once

#include <optional>
#include <span>

#include "hotmesh/geometry/axis.hpp"

namespace hotmesh::geometry::detail {

/// normals are unit vectors. Returns the axis with its origin the point of the axis nearest to
/// the samples' centroid, its direction's largest component positive.
std::optional<Axis> fit_rotation_axis(std::span<const Vec3> points, std::span<const Vec3> normals,
                                      double angle_tolerance);

/// Largest angle (radians) between a sample's normal and the plane through it and the axis,
/// over samples farther than min_radius from the axis.
double max_meridional_angle(const Axis& axis, std::span<const Vec3> points, std::span<const Vec3> normals,
                            double min_radius);

}  // namespace hotmesh::geometry::detail
