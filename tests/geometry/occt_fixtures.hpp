// hotmesh tests: CAD files built in code with OpenCASCADE's own modelling and writers
// (cylinders, cones, tori, revolved B-spline profiles, rotational B-spline surfaces, a part
// without an axis), and a reader of the edges of a file, to test hotmesh's CAD reader and
// writers, and the commands, against them. The header keeps OpenCASCADE out of the test files.
#pragma once

#include <filesystem>
#include <vector>

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/bspline_curve.hpp"

namespace hotmesh::geometry::test {

enum class Primitive {
  cylinder,          ///< radius 2, height 5 from the axis origin
  cone,              ///< radii 3 (at the origin) and 1, height 4
  torus,             ///< major radius 5, minor 1
  revolved_profile,  ///< profile() revolved by 360 degrees (a surface of revolution)
  bspline_revolved,  ///< the same surface converted to a (rational) B-spline surface
  /// A plate 10 x 10 x 2 (x, y in [-5, 5] in the axis's frame, 0 to 2 along the axis) with a hole
  /// of radius 2 through it on the axis: its flat faces are planes trimmed by the hole's circles.
  plate_with_hole,
};

/// The meridional profile of the revolved primitives: (r, z) about the axis, cubic.
BSplineCurve2d profile();

/// Writes the primitive, placed on `axis`, as a STEP or IGES file (by extension) with
/// OpenCASCADE's writer, coordinates in millimetres.
void write_primitive(const std::filesystem::path& path, Primitive primitive, const Axis& axis);

/// A forward-facing step, a part without an axis of revolution (issue 45), over 0 < z < 4:
/// face 1 the floor y = 0 for 0 < x < 10; face 2 a concave fillet of radius 1, the cylinder about
/// the line x = 10, y = 1 along z, from (10, 0) to (11, 1); face 3 the riser x = 11 for
/// 1 < y < 3; face 4 the top y = 3 for 11 < x < 20. Sewn into one shell and written as STEP with
/// OpenCASCADE's writer, coordinates in millimetres.
void write_forward_facing_step(const std::filesystem::path& path);

/// Points sampled evenly in parameter along every edge of a STEP or IGES file, read in metres.
std::vector<std::vector<Vec3>> edge_points(const std::filesystem::path& path, int samples);

}  // namespace hotmesh::geometry::test
