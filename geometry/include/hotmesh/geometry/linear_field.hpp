// hotmesh geometry: a vector field known at the FEM nodes of a wall, interpolated linearly over
// a triangulation of the nodes: the `degree: 1` of a table on a wall without CAD faces (issue
// 49, item 8). Exact at the nodes, and between them a convex combination of the three nodes of
// a triangle, so it never overshoots the table (the smooth interpolation of scattered_field.hpp
// does, next to a kink of a piecewise-linear deflection); it reproduces any field that is
// linear on each triangle, a linear field in particular.
//
// Method: the nodes are projected onto their mean plane (principal axes) and triangulated there
// by Delaunay (CGAL's Delaunay_triangulation_2); a point takes the barycentric coordinates of its
// projection in the triangle holding it. Projection keeps barycentric coordinates, so on the
// triangles through the nodes this is the linear interpolation in 3D. The wall must be a graph
// over that plane: a triangle whose normal turns more than `max_tilt_deg` from the plane's
// (a wall that folds over it, as a cylinder all round does) is refused. Outside the
// triangulation (beyond the table's convex hull) the value is that of the nearest point of the
// nearest triangle.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "hotmesh/core/vec3.hpp"
#include "hotmesh/geometry/wall_field.hpp"

namespace hotmesh::geometry {

struct LinearFieldReport {
  std::size_t samples = 0;            ///< points given
  std::size_t points = 0;             ///< distinct points triangulated
  std::size_t merged_duplicates = 0;  ///< samples - points
  std::size_t triangles = 0;
  double max_tilt_deg = 0.0;          ///< largest angle of a triangle's normal to the plane's
};

class LinearField final : public WallField {
 public:
  /// Throws hotmesh::InputError for a non-finite coordinate or value, duplicates with different
  /// values, fewer than 3 distinct points not on one line, two points over one point of the
  /// plane, or a triangle tilted beyond `max_tilt_deg` (the message says which nodes).
  LinearField(std::vector<Vec3> points, std::vector<Vec3> values, double max_tilt_deg = 80.0);

  Vec3 operator()(const Vec3& x) const override;
  /// How far x (projected onto the plane) lies beyond the triangles by more than the longest
  /// edge of the nearest one: the region the table covers reaches a triangle's size beyond its
  /// nodes, as the smooth field's patches reach beyond theirs (a wall's deflected nodes lie
  /// beyond its cold table by their deflection).
  double outside(const Vec3& x) const override;

  const LinearFieldReport& report() const { return report_; }

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
  LinearFieldReport report_;
};

}  // namespace hotmesh::geometry
