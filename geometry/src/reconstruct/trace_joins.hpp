// hotmesh geometry (internal): deflection fields made to agree along edges that cross a face's
// parameter rectangle (issue 23, item 1, trimmed faces).
//
// A trimmed face (a plate with a hole, a casing cut by a strut, a B-spline face split along a
// curve) is bounded by edges that run across its parameter rectangle rather than along its
// sides. No row of poles belongs to such an edge, so the fields cannot be joined by averaging
// rows (field_joins.hpp). Where the edge is a side of the other face (the wall of the hole, the
// strut standing on the casing: the common case), that face follows the trimmed one: its row
// of poles along the side is fitted by least squares to the trimmed face's field there,
//     min sum_k |d_a(x_k) - d_b(t_b(x_k), s_b(x_k))|^2        (x_k: 8 points per knot span),
// with (t_b, s_b)(x) the trimmed face's parameters at the side's point x, and the side's knot
// spans halved where the fields still differ by more than the tolerance (each halving cuts
// the difference about 2^(q+1)-fold), as for uneven sides. An edge that crosses both faces'
// rectangles (both trimmed along it) has no row on either side: both fields are corrected
// towards their mean along it, by the smoothest change of the poles near it
// (join_across_faces).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/geometry/cad_face.hpp"
#include "hotmesh/geometry/surface_projector.hpp"
#include "reconstruct/field_joins.hpp"

namespace hotmesh::geometry::detail {

/// An edge the CAD file says two faces of a wall share, as each face's parameters at its points.
struct TracedEdge {
  std::size_t a = 0;  ///< faces, positions in the wall
  std::size_t b = 0;
  std::vector<std::array<double, 2>> on_a;  ///< (t, s) on face a at each point
  std::vector<std::array<double, 2>> on_b;
  std::vector<Vec3> points;                 ///< the points of the wall
};

/// The edges two of `faces` both name (CadFace::edges) that cross at least one of the two
/// faces' parameter rectangles (edges along a side of both are the side joins' business),
/// with their points projected onto both faces. An edge whose points are not all within
/// `tolerance` of both faces is left out.
std::vector<TracedEdge> crossing_edges(std::span<const CadFace> faces, std::span<const SurfaceProjector> projectors,
                                       double tolerance);

/// The side (0 v first, 1 v last, 2 u first, 3 u last) of the face's rectangle that all the
/// parameters lie on (to 1e-9 of its range), or -1.
int side_holding(const BSplineSurface& face, std::span<const std::array<double, 2>> params);

/// An edge along side `side` of face a that crosses face b's rectangle.
struct SideOnFace {
  std::size_t a = 0;
  int side = 0;
  std::size_t b = 0;
};

/// Fits the row of each a's side to b's field along the edge (above), through the undeformed
/// faces' `projectors` for b's parameters; a's corner poles too, unless a side of a next to it
/// is `frozen` (joined to another face's side). Returns each edge's largest gap |d_a - d_b| at
/// its points after the join.
std::vector<double> join_sides_to_faces(std::vector<BSplineSurface>& fields, std::span<const CadFace> faces,
                                        std::span<const SurfaceProjector> projectors,
                                        std::span<const SideOnFace> edges, std::span<const FaceSide> frozen,
                                        double tolerance);

/// Joins the fields of faces a and b along each edge across both rectangles (a trimming curve
/// of each): both fields corrected towards their mean at points along the edge (b's parameters
/// there through the undeformed faces' `projectors`), by the
/// smoothest change of their poles near it (corrected(), trace_joins.cpp), sides in `frozen`
/// kept; the knot spans the edge crosses where the fields still differ by more than the
/// tolerance halved in both directions (at most kMaxHalvings times, each face at most 16 times
/// its poles, at least 4096) and the correction made again. Returns each edge's largest gap
/// |d_a - d_b| after the join, at its points and its trace's.
std::vector<double> join_across_faces(std::vector<BSplineSurface>& fields, std::span<const CadFace> faces,
                                      std::span<const SurfaceProjector> projectors, std::span<const TracedEdge> edges,
                                      std::span<const FaceSide> frozen, double tolerance);

/// The largest |d_a - d_b| at the points of a traced edge.
double traced_gap(const std::vector<BSplineSurface>& fields, const TracedEdge& edge);

}  // namespace hotmesh::geometry::detail
