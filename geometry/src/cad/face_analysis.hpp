// hotmesh geometry (internal): what a CAD face is: its surface kind, bounding box, axis of
// revolution (analytic or fitted) and sample points with normals.
#pragma once

#include <TopoDS_Face.hxx>

#include <vector>

#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::geometry::detail {

/// Largest angle between a normal and its meridional plane for a free-form face to count as a
/// surface of revolution (radians; about the relative distance error of the shape).
inline constexpr double kRotationAngleTolerance = 1e-4;

SurfaceKind surface_kind(const TopoDS_Face& face);
Box3 face_bounds(const TopoDS_Face& face);
double diagonal(const Box3& box);

struct FaceAxis {
  std::optional<Axis> axis;
  AxisSource source = AxisSource::none;
};
FaceAxis face_axis(const TopoDS_Face& face, SurfaceKind kind);

struct SurfaceSamples {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;  ///< unit; same size as points
};
/// Points on an n x n grid of the face's parameter bounds (cell centres), with their normals
/// where defined; with inside_only, only points inside the face's boundary.
SurfaceSamples sample_face(const TopoDS_Face& face, int n, bool inside_only);

}  // namespace hotmesh::geometry::detail
