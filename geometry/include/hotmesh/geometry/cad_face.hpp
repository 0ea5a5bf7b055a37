// hotmesh geometry: a CAD face as a wall on CAD faces (surface_shape.hpp) sees it: its surface in
// B-spline form over the face's parameter bounds and, from a CAD file, the edges that bound it
// there, trimming curves included. Two faces of a wall that name the same edge share it, along
// the whole edge, whether it runs along the sides of their parameter rectangles or across them.
#pragma once

#include <vector>

#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/core/vec2.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

/// An edge of a face's boundary, as points of the wall.
struct FaceEdge {
  int edge = 0;              ///< its number among the CAD model's edges: the same on every face it bounds
  std::vector<Vec3> points;  ///< kFaceEdgePoints points, evenly spaced in the edge's parameter, end to end
};

/// Points on each FaceEdge: enough to tell which side of a face's rectangle the edge runs along
/// (if any) and to measure the gap between two faces' deflections along it.
inline constexpr int kFaceEdgePoints = 65;

/// An edge's curve on a face (its pcurve) in the parameters (t, s) of the face's B-spline form:
/// together, a face's curves close the loops that trim its rectangle (trim_region.hpp).
struct TrimCurve {
  int edge = 0;              ///< as FaceEdge::edge; 0 for a seam or an edge collapsed to a point
  std::vector<Vec2> points;  ///< a polyline within 1e-6 of the rectangle's size of the curve
};

/// A CAD face in B-spline form (CadModel::cad_face) with its number in the CAD file.
struct CadFace {
  int id = 0;
  BSplineSurface surface;
  /// The edges that bound it in the CAD file, seams and edges collapsed to a point left out;
  /// empty for a face given without its CAD file, whose shared edges are then the sides of its
  /// parameter rectangle that lie on another face.
  std::vector<FaceEdge> edges;
  /// Every edge of its boundary in (t, s), seams (both sides) and poles included; empty for a
  /// face given without its CAD file, which is its whole rectangle.
  std::vector<TrimCurve> trims;
};

}  // namespace hotmesh::geometry
