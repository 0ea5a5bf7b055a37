// hotmesh geometry: distance from points to B-spline surfaces, for checking a mesh against CAD
// faces that are not surfaces of revolution (planes at an angle, free-form faces), where the
// meridional curve of section 4.2 does not apply. The surfaces are the faces in B-spline form
// (CadModel::face_bspline): each face's surface over its parameter rectangle, so trimming
// curves inside that rectangle are not taken into account.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "hotmesh/geometry/bspline_surface.hpp"

namespace hotmesh::geometry {

class SurfaceDistance {
 public:
  /// Throws std::invalid_argument for an empty list.
  explicit SurfaceDistance(const std::vector<BSplineSurface>& surfaces);
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;
  ~SurfaceDistance();

  struct Result {
    double distance = 0.0;
    Vec3 point;               ///< the closest point
    std::size_t surface = 0;  ///< index of the surface it lies on
  };

  /// The closest point of all the surfaces (within each one's parameter rectangle, its
  /// boundary included). Not thread-safe: it keeps per-surface search caches; use one object
  /// per thread.
  Result nearest(const Vec3& p);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hotmesh::geometry
