// hotmesh tests: CAD files built in code with OpenCASCADE's own modelling and writers
// (cylinders, cones, tori, revolved B-spline profiles, rotational B-spline surfaces), and a
// reader of the edges of a file, to test hotmesh's CAD reader and writers against them. The
// header keeps OpenCASCADE out of the test files.
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

/// Points sampled evenly in parameter along every edge of a STEP or IGES file, read in metres.
std::vector<std::vector<Vec3>> edge_points(const std::filesystem::path& path, int samples);

}  // namespace hotmesh::geometry::test
