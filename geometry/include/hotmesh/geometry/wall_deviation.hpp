// hotmesh geometry: how far a discrete wall is from the boundary it should follow, both ways
// (issue 20, item 4: checks that see cut corners): from a curve (2D walls, surfaces of
// revolution in the meridional plane), and from CAD faces of any shape (issue 23; the second
// overload of wall_deviation, described at its end).
//
// A mesh patch holds its wall nodes on the deflected curve c_lambda (sections 4.2-4.3), but its
// wall is the faces between the nodes: where no node lands on a corner of the curve, the
// wall's edges cut the corner, and the distance of the nodes alone (round-off) does not show
// it. This measures the wall itself, as the two one-sided distances and their maximum, the
// Hausdorff distance between the discrete wall W and the part C of the curve the wall covers:
//   mesh_to_shape = max over w in W of dist(w, c_lambda)   (the wall bulging off the curve:
//                   a chord's sagitta, h^2 / 8R on an arc of radius R);
//   shape_to_mesh = max over c in C of dist(c, W)          (the curve the wall misses: a corner
//                   cut by a chord, the deeper of the two at a corner);
//   hausdorff     = max(mesh_to_shape, shape_to_mesh).
// C is c_lambda over [t_lo, t_hi], the smallest and largest parameter of the projections of the
// wall's nodes, so that a curve reaching beyond the patch (a table longer than the wall) is not
// counted against it.
//
// Where it is measured. In 2D the faces are edges (segments) in the x-y plane. In 3D the wall
// is a surface of revolution and is measured in the meridional plane: every face edge is taken
// to the segment between its end nodes' (r, z) about the axis, and the faces are represented by
// their edges. So the circumferential faceting of a sector mesh (a face's chord across theta,
// which lies inside the cylinder r = const) is not counted: it is a property of the mesh's
// resolution in theta, the same for every wall, not of how the wall follows its meridional
// curve. The locations reported are put back in space, in the meridional plane of the wall
// edge they belong to.
//
// How (both sides sampled, then refined; the distance to any set is 1-Lipschitz, so between
// two samples a distance can exceed the larger of them by at most half their spacing):
//   mesh_to_shape: every distinct edge sampled at its ends and `edge_samples` interior points,
//     each projected globally on c_lambda (CurveProjector, cold start: a warm start could stay
//     on the wrong side of a corner, exactly where the maximum is). Between nodes the distance
//     from a chord is one bump per arc or corner under it (a parabola-like sagitta, or a tent
//     whose top is where the chord is equally far from both sides of a corner), so each local
//     maximum of the samples is refined by golden-section search in its bracket of two
//     spacings. A local maximum is skipped when even the Lipschitz bound (its value plus half a
//     spacing) cannot beat the largest value found, or when its samples lie on the curve up to
//     round-off (an edge on the curve there: a narrow notch of the curve between them would be
//     seen by shape_to_mesh).
//   shape_to_mesh: c_lambda sampled over [t_lo, t_hi] at every piece end of the curve (its
//     knots and the ends of the FEM range: the C0 corners, where the maximum is, are always
//     among them) and in between at most `curve_spacing` median wall edges apart along the
//     curve; each sample's nearest wall edge is found through a uniform grid of the edges'
//     boxes (O(1) per query for walls with edges of similar length), and local maxima are
//     refined in the curve parameter as above.
// The cost is O((edges + curve samples) * projection), each projection a cold CurveProjector
// search (about 2 us), so some 20 to 60 projections per edge.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

class SurfaceShape;

/// The faces of a discrete wall, as lists of corner indices into a point array: 2 corners for
/// an edge (2D meshes), 3 or more for a polygon (its edges join consecutive corners, last to
/// first).
class WallFaces {
 public:
  void add(std::span<const std::int32_t> corners);
  std::size_t size() const { return offsets_.size() - 1; }
  bool empty() const { return size() == 0; }
  std::span<const std::int32_t> corners(std::size_t face) const {
    return {corners_.data() + offsets_[face], corners_.data() + offsets_[face + 1]};
  }

 private:
  std::vector<std::int32_t> corners_;
  std::vector<std::size_t> offsets_{0};
};

struct WallDeviationOptions {
  double lambda = 1.0;        ///< the stage of the curve (1: fully deflected)
  std::optional<Axis> axis;   ///< 3D: measure in the meridional plane about it; none: the x-y plane
  int edge_samples = 15;      ///< interior points sampled on each edge before refining (>= 1)
  double curve_spacing = 0.125;  ///< curve samples at most this many median edge lengths apart
};

/// One side's largest distance and where it is reached.
struct WallDeviationPoint {
  double distance = 0.0;
  /// Where it is reached: on the discrete wall (mesh_to_shape) or on the curve (shape_to_mesh).
  Vec3 point;
  /// The nearest point of the other side: on the curve (mesh_to_shape) or on the wall.
  Vec3 nearest;
  /// The curve parameter t of whichever of the two lies on the curve; on faces, its t.
  double parameter = 0.0;
  /// On faces: the s of that point, and the index of its face among the shape's (-1: a curve).
  double parameter_s = 0.0;
  int shape_face = -1;
  /// Curves: the wall edge holding the wall's point, as its two corner indices (-1: none
  /// measured; on faces too).
  std::array<std::int32_t, 2> edge{-1, -1};
  /// Faces: the wall face holding the wall's point, an index of the WallFaces measured (-1:
  /// none measured; on curves too).
  std::int32_t face = -1;
};

enum class WallDirection {
  mesh_to_shape,  ///< the wall off the curve
  shape_to_mesh,  ///< the curve off the wall
};
const char* to_string(WallDirection direction);

struct WallDeviation {
  WallDeviationPoint mesh_to_shape;
  WallDeviationPoint shape_to_mesh;
  double hausdorff = 0.0;  ///< max of the two
  WallDirection worst = WallDirection::mesh_to_shape;
  double first_parameter = 0.0;  ///< curves: t_lo, the part of the curve the wall covers
  double last_parameter = 0.0;   ///< curves: t_hi
  std::size_t edges = 0;          ///< curves: distinct edges measured (0: no faces, nothing measured)
  std::size_t faces = 0;          ///< faces: wall faces measured (0: none, nothing measured)
  std::size_t shape_samples = 0;  ///< samples of the curve or the faces, before refinement
  /// Faces: shape samples left out as not covered by the wall (their nearest point of the wall
  /// is on its rim) or not on their face (beyond its trimming loops); counted in shape_samples.
  std::size_t uncovered_samples = 0;

  const WallDeviationPoint& worst_point() const {
    return worst == WallDirection::mesh_to_shape ? mesh_to_shape : shape_to_mesh;
  }
  /// `worst` and `hausdorff` from the two directions' distances (NaN if either is).
  void take_worst_direction();
};

/// The two-sided distance between the wall made of `faces` (corners indexing `points`) and the
/// stage options.lambda of `curve`, in the x-y plane or, with options.axis, in the meridional
/// plane. No faces: a result with edges == 0 and zero distances. Throws std::invalid_argument
/// for a corner index outside `points` or options out of range.
WallDeviation wall_deviation(const CurveProjector& curve, std::span<const Vec3> points, const WallFaces& faces,
                             const WallDeviationOptions& options = {});

// Walls on CAD faces (SurfaceShape: the faces S + lambda d(t, s) of issue 23). The wall W is a
// mesh patch's faces in 3D, triangles and quads, each quad the bilinear patch through its four
// corners (a polygon of more corners: a fan of triangles from its first); C is the part of the
// stage-lambda faces the wall covers. Both sides are sampled, then refined:
//   mesh_to_shape: each wall face on a grid of `face_samples` intervals per direction of its
//     parameters (bilinear (a, b) of a quad, (a, b) on a triangle's barycentric grid), each point
//     projected onto the stage (SurfaceShape::project, a warm start from the previous point;
//     the projection reaches beyond free edges as the solver's does).
//   shape_to_mesh: each CAD face over the part of its parameter rectangle (t, s) that the
//     projections of the wall's samples span (as the curve's [t_lo, t_hi]), on a grid at most
//     `shape_spacing` median wall edges apart, each point's nearest wall face found in a box
//     tree of the faces (median splits, O(N log N) to build, O(log N) a query near the wall).
//     Restriction to the part the wall covers: a sample whose nearest point of the wall lies on
//     the wall's rim (an edge of one face only, or a node at an end of such an edge) is beyond
//     the wall's edge, not under it: it is left out (counted in uncovered_samples), as is a
//     sample beyond its face's trimming loops (SurfaceShape::holds), not on the face. So a CAD
//     face reaching beyond the patch, or a patch covering part of a face, is measured where the
//     patch covers it; a patch that stops short of its face's edge is not caught on this side.
//   Refinement: the best sample of each wall face, and each local maximum of a CAD face's
//     grid, is a candidate, bounded by its value plus half the largest difference to its grid
//     neighbours (how much higher a tent, a kink of the distance, can rise between the samples;
//     a smooth bump, a parabola, half as much); from the highest bound down, as long as the bound
//     beats the largest value found, a pattern search (8 directions, the step from half the
//     sample spacing halved down to 1e-4 of it) climbs to the local maximum. A feature narrower
//     than the samples' spacing on both sides (a spike of the wall between a face's samples and
//     a dimple of the face between its samples) can be missed.
// The cost is (face_samples + 1)^2 projections per wall face (25 by default) and about
// 1 / shape_spacing^2 nearest-face queries per wall face (16), plus about 100 evaluations per
// refined candidate: measured, about 0.1 ms per wall face on one thread (10^5 quads on a wavy
// bicubic face: 10.6 s, 3% of the faces refined). Memory: the tree, and one CAD face's sample
// grid at a time (8 bytes a sample, at most 2^24 samples a face).

/// Options of the measure against CAD faces.
struct SurfaceWallOptions {
  double lambda = 1.0;          ///< the stage of the faces (1: fully deflected)
  int face_samples = 4;         ///< intervals per direction of each wall face's sample grid (>= 1)
  double shape_spacing = 0.25;  ///< CAD face samples at most this many median wall edges apart
};

/// The two-sided distance between the wall made of `faces` (3 or more corners each, indexing
/// `points`) and the stage options.lambda of `shape`'s faces. No faces: a result with faces == 0
/// and zero distances. Throws std::invalid_argument for a corner index outside `points`, a face
/// of fewer than 3 corners, or options out of range.
WallDeviation wall_deviation(const SurfaceShape& shape, std::span<const Vec3> points, const WallFaces& faces,
                             const SurfaceWallOptions& options = {});

}  // namespace hotmesh::geometry
