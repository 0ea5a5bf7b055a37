// hotmesh geometry: a vector field over a wall without CAD faces, known at the FEM nodes of a
// table and interpolated between them: the smooth partition-of-unity RBF (scattered_field.hpp)
// or the linear interpolation over a triangulation of the nodes (linear_field.hpp). A
// prescribed wall moves by one (ScatteredShape, surface_shape.hpp).
#pragma once

#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

class WallField {
 public:
  virtual ~WallField() = default;
  /// The interpolated value at x. Const and thread-safe.
  virtual Vec3 operator()(const Vec3& x) const = 0;
  /// How far x lies outside the region the table covers (0 within).
  virtual double outside(const Vec3& x) const = 0;
};

}  // namespace hotmesh::geometry
