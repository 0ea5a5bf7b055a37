// hotmesh geometry: walls of any shape in 3D, beyond surfaces of revolution (issue 23).
//
// Section 4.2 on CAD faces, as the paper describes it for B-spline surfaces S(t, s): every FEM
// node Q_j is projected onto the undeformed faces to get its face and (t_j, s_j); on each face
// the deflection field d(t, s) is a degree-q B-spline surface through the nodes' deflections
// delta_j (surface_fit.hpp: global interpolation where the nodes form a grid in (t, s),
// regularised least squares where they are scattered); the deflected face is
//     S'(t, s) = S(t, s) + d(t, s)                                  (displacement form)
// and the stages of the increments are S + lambda d (section 4.3). A node on an edge shared by
// two faces is a sample of both, so both fields pass near its deflection there; the fields are
// then made to meet along the whole edge (field_joins.hpp): exactly where the two faces
// parametrise the edge affinely to each other (their rows of poles there averaged), to 1e-10
// of the wall's size where they do not (their mean along the edge fitted in each face's
// parameter, the knot spans there halved until the two fits agree), and to the same tolerance
// where the edge is a trimming curve: a side of one face that crosses the other's rectangle
// (that side's row fitted to the trimmed face's field), or a curve across both rectangles (both
// fields corrected smoothly towards their mean, trace_joins.hpp).
//
// SurfaceShape is the BoundaryShape of such a wall: points are projected onto the stage's
// deformed faces (surface_projector.hpp), parameters are (face, t, s); a trimmed face answers
// only inside its trimming loops where the wall goes on across them (trim_region.hpp). A restarted run goes
// from one deflection field to the next: S + d0 + lambda (d1 - d0).
//
// ScatteredShape is the motion of a prescribed wall without CAD faces: the table's deflections
// interpolated over the wall (wall_field.hpp): linearly over a triangulation of the FEM nodes
// (linear_field.hpp, degree 1), or by partition-of-unity radial basis functions
// (scattered_field.hpp, higher degrees: exact at the FEM nodes, linear fields reproduced
// exactly, smooth). It is a field rather than a surface: a point is its own closest point, and
// at() moves the material point at `reference`.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
#include <map>
#include <memory>
#include <shared_mutex>
#include <span>
#include <utility>
#include <vector>

#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/geometry/cad_face.hpp"
#include "hotmesh/geometry/deflection_samples.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/geometry/scattered_field.hpp"
#include "hotmesh/geometry/surface_fit.hpp"
#include "hotmesh/geometry/surface_projector.hpp"
#include "hotmesh/geometry/trim_region.hpp"
#include "hotmesh/geometry/wall_field.hpp"

namespace hotmesh::geometry {

/// How the field of one face was fitted.
struct FaceFitReport {
  int face = 0;               ///< CAD face number
  std::size_t nodes = 0;      ///< FEM nodes on the face (those on a shared edge count on both)
  SurfaceFitReport fit;
};

struct SurfaceReconstructionReport {
  std::size_t nodes = 0;       ///< FEM nodes given
  std::size_t used_nodes = 0;  ///< nodes within the tolerance of a face
  int degree = 1;
  double tolerance = 0.0;      ///< the distance tolerance used
  double max_node_distance_to_cad = 0.0;
  /// max |d(t_j, s_j) - delta_j| over the nodes used and the faces each lies on: the
  /// interpolation's round-off on grids, the fit's error elsewhere.
  double max_node_residual = 0.0;
  /// Largest difference between the deflections of two faces along the edges they share
  /// (sampled): how far apart the deflected faces are there. Round-off on affine joined edges,
  /// at most 1e-10 of the wall's size on the others that are joined.
  double max_edge_gap = 0.0;
  std::size_t shared_edges = 0;  ///< edges two faces share
  /// Shared edges along which the fields were made to meet: exactly where the two faces
  /// parametrise the edge affinely to each other (equal fractions along both sides, or
  /// reversed), to 1e-10 of the wall's size elsewhere (uneven edges, and sides of one face
  /// across the other's rectangle, that the refinement brought within it; not edges across
  /// both faces' rectangles).
  std::size_t joined_edges = 0;
  std::vector<NodeDistance> rejected_nodes;  ///< dropped for distance (FarNodePolicy::drop)
  std::vector<FaceFitReport> faces;
};

/// Where one FEM node used lies on one face: a node within the tolerance of several faces (on
/// the edge they share) has a placement on each.
struct NodePlacement {
  std::size_t node = 0;   ///< 0-based position in the samples
  std::size_t face = 0;   ///< position in `faces`
  double t = 0.0;         ///< the face parameters of its closest point
  double s = 0.0;
  double distance = 0.0;  ///< |Q_j - S(t, s)|
};

/// The deflection field of every face, in the order of `faces`.
struct FaceDeflections {
  std::vector<BSplineSurface> fields;
  SurfaceReconstructionReport report;
  std::vector<NodePlacement> placements;  ///< by node, then by face
};

/// Section 4.2 on CAD faces: FEM nodes (cartesian samples) projected onto the faces, d(t, s)
/// fitted on each (options.degree; options.form is not used: surfaces take the displacement
/// form). Throws hotmesh::InputError naming the table for samples that are not cartesian,
/// nodes farther than the tolerance from every face (policy reject), a face without enough
/// nodes for the degree (naming the face), or options out of range.
FaceDeflections reconstruct_on_faces(std::span<const CadFace> faces, const DeflectionSamples& samples,
                                     const ReconstructionOptions& options = {});

class SurfaceShape final : public BoundaryShape, public std::enable_shared_from_this<SurfaceShape> {
 public:
  /// Stage lambda is S + before + lambda (after - before), face by face; `before` empty means
  /// zero (a run from the cold geometry). Throws std::invalid_argument if the counts or the
  /// fields' parameter rectangles differ from the faces'.
  SurfaceShape(std::vector<CadFace> faces, std::vector<BSplineSurface> after, std::vector<BSplineSurface> before = {});

  /// The closest point of the stage-lambda faces; parameter (t, s, face index). The normal is
  /// S_t x S_s of that face, unit (its sign is the face's parametrisation's).
  ShapePoint project(const Vec3& p, double lambda, const ShapeParameter& hint = kNoHint,
                     const ParameterRange& range = {}) const override;
  ShapePoint at(const ShapeParameter& where, double lambda, const Vec3& reference) const override;
  /// At a point of an edge where two faces meet turning by at least `min_angle` (radians; pi
  /// minus the angle between the directions into each face across the edge, so a face folding
  /// back onto the other turns by nearly pi): each face as a shape of its own, the point's face
  /// first (three where it is a corner of three faces).
  /// The shape must be owned by a shared_ptr.
  std::vector<std::shared_ptr<const BoundaryShape>> crease_sides(const ShapeParameter& where,
                                                                 double min_angle) const override;
  /// The edges two faces share where they meet turning by at least `min_angle`: the largest
  /// turn (as for crease_sides) at points along the edge, undeformed or fully deflected. An
  /// edge where a side of one face crosses the other's rectangle (a trimming curve of the
  /// other) counts, the face whose side it is first; the trimmed face goes on to the side its
  /// trimming loops keep, or, for a face without loops, away from the side the other leans to.
  /// So does an edge the CAD file names on both faces that crosses both rectangles, where both
  /// faces' loops tell which way they go on, the lower face first.
  std::vector<ShapeCrease> creases(double min_angle) const override;
  /// The point of the crease's edge nearest p on the stage-lambda faces: the closest point of
  /// faces[0]'s side along it (or of its trimming curve, where the edge crosses both
  /// rectangles), and each face's normal there (faces[1]'s at its own side's or trimming
  /// curve's closest point, or its closest point where the edge crosses its rectangle: the same
  /// edge of the deflected wall, since the faces' fields agree there).
  CreasePoint crease_point(const ShapeCrease& crease, const Vec3& p, double lambda) const override;
  /// Regions are numbered as they are first asked for; project() with a range of that region
  /// searches only its faces (clamped where they meet the others).
  int crease_region(int face, double min_angle) const override;
  /// The closest point of one face at stage lambda (clamped at its shared edges).
  ShapePoint project_on_face(int face, const Vec3& p, double lambda, const ShapeParameter& hint) const;

  /// Whether (t, s) is a point of face `face`: inside its trimming loops (any of them, binding
  /// or free), anywhere on a face that is its whole rectangle.
  bool holds(std::size_t face, double t, double s) const {
    const TrimRegion* region = regions_of_faces_[face].get();
    return region == nullptr || region->contains(t, s);
  }
  std::size_t face_count() const { return faces_.size(); }
  const CadFace& face(std::size_t i) const { return faces_[i]; }

 private:
  /// The projector of stage lambda onto every face (`faces` kAllFaces), one face (its index)
  /// or a crease region (region_key), built on first use (one per increment's stage) and kept.
  /// Its patches are `faces`' faces in increasing order.
  const SurfaceProjector& stage(double lambda, int faces = kAllFaces) const;
  static constexpr int kAllFaces = -1;
  static int region_key(int region) { return -2 - region; }
  /// The faces of a stage key, increasing.
  std::vector<int> faces_of(int key) const;
  SurfaceDerivatives evaluate(std::size_t face, double t, double s, double lambda) const;
  /// The side (s first, s last, t first, t last) of `face` shared with `other`, or -1.
  int side_shared_with(int face, int other) const;
  /// The closest point to p of side `side` of `face` at stage lambda, and the face's unit normal.
  ShapePoint project_on_side(std::size_t face, int side, const Vec3& p, double lambda) const;
  /// How far the wall turns at `here`, a point of side `side` of face f, into face g: g's side
  /// along it, or g itself where f's side crosses g's rectangle (a trimming curve of g).
  double turn_into(std::size_t f, int side, const SurfaceDerivatives& here, std::size_t g, double lambda) const;
  /// An edge two faces of the wall name that crosses both their rectangles (a trimming curve of
  /// each): the faces (lower first) and the edge's curve among each one's trims.
  struct TrimmedEdge {
    std::array<std::size_t, 2> faces;
    std::array<std::size_t, 2> curves;
  };
  const std::vector<Vec2>& curve_of(const TrimmedEdge& e, int k) const {
    return faces_[e.faces[static_cast<std::size_t>(k)]].trims[e.curves[static_cast<std::size_t>(k)]].points;
  }
  /// The point of trimmed edge e nearest p on its face k (0 or 1) at stage lambda: a scan of
  /// its curve, then a golden-section search along it.
  ShapePoint project_on_trim(const TrimmedEdge& e, int k, const Vec3& p, double lambda) const;
  /// crease_point for a crease along trimmed edges.
  CreasePoint crease_point_on_trims(const ShapeCrease& crease, const Vec3& p, double lambda) const;
  /// How far the wall turns across trimmed edge e at `on_first`, a point of it on its first face
  /// (0 where either face's loops do not tell which way the face goes on).
  double turn_across(const TrimmedEdge& e, const ShapePoint& on_first, double lambda) const;
  /// Which way across an edge at `at` (derivatives `d`) the face's trimming loops keep: +1 along
  /// `across`, -1 against it, 0 where they do not tell (no loops; both sides in, or out).
  int kept_side(std::size_t face, const ShapeParameter& at, const SurfaceDerivatives& d, const Vec3& across) const;

  std::vector<CadFace> faces_;
  std::vector<BSplineSurface> after_;
  std::vector<BSplineSurface> before_;
  std::vector<ParameterRectangle> reach_;  ///< each face's rectangle, beyond its free edges
  /// Each face's trimming loops, those along edges another face of the wall names binding;
  /// nullptr for a face that is its whole rectangle.
  std::vector<std::shared_ptr<const TrimRegion>> regions_of_faces_;
  std::vector<TrimmedEdge> trimmed_edges_;
  /// Per face and side of its rectangle (s first, s last, t first, t last), the face sharing it,
  /// or -1.
  std::vector<std::array<int, 4>> neighbours_;
  /// Per face and side: whether the side is a closed curve (its ends meet at the face's seam,
  /// as a cylinder's circle), which project_on_side follows across the seam.
  std::vector<std::array<bool, 4>> closed_sides_;
  double size_ = 0.0;  ///< the faces' size (FaceSet::size)
  mutable std::shared_mutex stages_mutex_;
  /// The crease regions asked for: each one's faces (increasing), and per angle asked for,
  /// each face's region (guarded by stages_mutex_).
  mutable std::deque<std::vector<int>> regions_;  ///< a deque: its elements stay where they are
  mutable std::map<double, std::vector<int>> region_of_face_;
  mutable std::map<std::pair<double, int>, std::unique_ptr<SurfaceProjector>> stages_;
};

struct SurfaceShapeFit {
  std::shared_ptr<SurfaceShape> shape;
  SurfaceReconstructionReport report;
};

/// The deflected wall on `faces` through the samples (reconstruct_on_faces), from the cold
/// geometry; with `previous` samples, from their deflected wall to the new one (a restart,
/// section 4.3).
SurfaceShapeFit make_surface_shape(std::vector<CadFace> faces, const DeflectionSamples& samples,
                                   const ReconstructionOptions& options = {},
                                   const DeflectionSamples* previous = nullptr);

/// The faces themselves at every stage (zero deflection fields): the undeformed wall, for
/// checking a mesh against its CAD faces as the motion sees them.
std::shared_ptr<SurfaceShape> undeformed_surface_shape(std::vector<CadFace> faces);

class ScatteredShape final : public BoundaryShape {
 public:
  /// Stage lambda moves the material point x0 to x0 + before(x0) + lambda (after(x0) -
  /// before(x0)); without `before`, to x0 + lambda after(x0).
  explicit ScatteredShape(std::shared_ptr<const WallField> after, std::shared_ptr<const WallField> before = nullptr);

  /// p itself; `distance` is how far p lies outside the region the table covers (0 within).
  ShapePoint project(const Vec3& p, double lambda, const ShapeParameter& hint = kNoHint,
                     const ParameterRange& range = {}) const override;
  /// The stage-lambda position of the material point that stage 0 has at `reference`.
  ShapePoint at(const ShapeParameter& where, double lambda, const Vec3& reference) const override;

  const WallField& field() const { return *after_; }

 private:
  /// The cold position x0 with x0 + before(x0) = x (x itself without `before`).
  Vec3 material_point(const Vec3& x) const;

  std::shared_ptr<const WallField> after_;
  std::shared_ptr<const WallField> before_;
};

}  // namespace hotmesh::geometry
