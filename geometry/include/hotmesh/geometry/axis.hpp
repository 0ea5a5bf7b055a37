// hotmesh geometry: an axis of revolution and cylindrical coordinates (r, theta, z) about it.
// Axisymmetric patches (the paper's §4.2, Fig. 4) are handled in the meridional plane (r, z).
#pragma once

#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

struct Cylindrical {
  double r = 0.0;
  double theta = 0.0;  ///< radians, in (-pi, pi]
  double z = 0.0;      ///< signed distance along the axis from its origin
};

class Axis {
 public:
  /// Throws std::invalid_argument if direction has zero length or is not finite.
  Axis(const Vec3& origin, const Vec3& direction);
  Axis() : Axis({0, 0, 0}, {0, 0, 1}) {}

  const Vec3& origin() const { return origin_; }
  const Vec3& direction() const { return e3_; }  ///< unit length

  Cylindrical to_cylindrical(const Vec3& p) const;
  Vec3 to_cartesian(const Cylindrical& c) const;
  /// A vector given by its (radial, axial) components at angle theta, in Cartesian form.
  Vec3 meridional_vector(double theta, double dr, double dz) const;

 private:
  Vec3 origin_;
  Vec3 e1_, e2_, e3_;  // right-handed frame: theta = 0 along e1, axis along e3
};

}  // namespace hotmesh::geometry
