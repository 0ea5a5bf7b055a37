// hotmesh geometry: an axis of revolution and cylindrical coordinates (r, theta, z) about it
// (axis.hpp): the frame of the meridional plane in which axisymmetric walls are projected (Fig. 4).
#include "hotmesh/geometry/axis.hpp"

#include <cmath>
#include <stdexcept>

namespace hotmesh::geometry {

Axis::Axis(const Vec3& origin, const Vec3& direction) : origin_(origin) {
  const double length = norm(direction);
  if (!is_finite(origin) || !std::isfinite(length) || length == 0.0) {
    throw std::invalid_argument("axis direction must be a finite, non-zero vector");
  }
  e3_ = direction / length;
  // theta = 0 along the coordinate direction least aligned with the axis, made orthogonal.
  const Vec3 ax{std::abs(e3_.x), std::abs(e3_.y), std::abs(e3_.z)};
  const Vec3 seed = (ax.x <= ax.y && ax.x <= ax.z) ? Vec3{1, 0, 0}
                    : (ax.y <= ax.z)               ? Vec3{0, 1, 0}
                                                   : Vec3{0, 0, 1};
  e1_ = seed - dot(seed, e3_) * e3_;
  e1_ = e1_ / norm(e1_);
  e2_ = cross(e3_, e1_);
}

Cylindrical Axis::to_cylindrical(const Vec3& p) const {
  const Vec3 d = p - origin_;
  const double a = dot(d, e1_);
  const double b = dot(d, e2_);
  return {std::hypot(a, b), std::atan2(b, a), dot(d, e3_)};
}

Vec3 Axis::to_cartesian(const Cylindrical& c) const {
  return origin_ + meridional_vector(c.theta, c.r, c.z);
}

Vec3 Axis::meridional_vector(double theta, double dr, double dz) const {
  return dr * (std::cos(theta) * e1_ + std::sin(theta) * e2_) + dz * e3_;
}

}  // namespace hotmesh::geometry
