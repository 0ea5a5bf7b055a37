// hotmesh tests: CAD files built in code with OpenCASCADE's own modelling and writers
// (cylinders, cones, tori, revolved B-spline profiles, rotational B-spline surfaces, a part
// without an axis, the plane drawing of a 2D channel's wall), and a reader of the edges of a
// file, to test hotmesh's CAD reader and writers, and the commands, against them. The header
// keeps OpenCASCADE out of the test files.
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

/// The lower wall of a 2D channel with a forward-facing step, drawn in the plane z = 0 (mm):
/// a line along the floor y = 0 from x = 0 to the step's sharp foot at x = 10, up the step's
/// face to y = 3, a quarter circle of radius 2 about (12, 3) (the fillet on the shoulder,
/// tangent to the face and the top), and a line along the top y = 5 to x = 25.
struct StepWall {
  static constexpr double kFootX = 10.0, kStepHeight = 5.0, kFilletRadius = 2.0, kLength = 25.0;
  static constexpr double kChannelHeight = 10.0;
  static Vec2 fillet_centre() { return {kFootX + kFilletRadius, kStepHeight - kFilletRadius}; }
  /// The wall's vertices in order along it: the floor's start, the foot, the fillet's ends, the end.
  static std::vector<Vec2> vertices() {
    return {{0, 0}, {kFootX, 0}, {kFootX, kStepHeight - kFilletRadius}, {kFootX + kFilletRadius, kStepHeight},
            {kLength, kStepHeight}};
  }
};

enum class StepWallDrawing {
  face,   ///< the channel above the wall as one planar face (top y = 10, inlet x = 0, outlet x = 25)
  edges,  ///< the wall's four edges alone (a wire), no face
  lifted, ///< the wall's edges with the fillet moved 0.5 out of the plane, to z = 0.5
  gap,    ///< the wall's edges with the top line starting 0.5 beyond the fillet's end
};

/// Writes the step wall as a STEP file, millimetres, with OpenCASCADE's writer.
void write_step_wall(const std::filesystem::path& path, StepWallDrawing drawing);

/// Writes a STEP file holding one vertex and nothing else.
void write_lone_vertex(const std::filesystem::path& path);

/// Points sampled evenly in parameter along every edge of a STEP or IGES file, read in metres.
std::vector<std::vector<Vec3>> edge_points(const std::filesystem::path& path, int samples);

}  // namespace hotmesh::geometry::test
