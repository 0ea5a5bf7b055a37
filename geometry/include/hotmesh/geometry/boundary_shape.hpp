// hotmesh geometry: a boundary the mesh follows, as seen by the solver in deform.
//
// One interface for every kind of boundary (a curve in the x-y plane for 2D cases, a surface
// of revolution described by its meridional curve, CAD faces of any kind, a plane). A shape
// has stages lambda in [0, 1]: the undeformed boundary r(t) at lambda = 0, the fully deflected
// boundary c(t) at lambda = 1, and between them the partial shapes of the increments,
//     c_lambda(t) = r(t) + lambda (c(t) - r(t)),                                (section 4.3)
// (on faces, S_lambda(t, s) = S(t, s) + lambda d(t, s)). Points with the same parameter on
// different stages are the same material point of the boundary, so a prescribed node at
// parameter t moves by at(t, lambda) - at(t, 0).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

/// Where a point lies on a boundary shape: on a curve (2D, or the meridional curve of a surface
/// of revolution) its parameter t; on a surface made of faces, the face and (t, s) on it.
/// A parameter whose t is NaN is unknown (kNoHint).
struct ShapeParameter {
  double t = 0.0;
  double s = 0.0;
  int face = 0;  ///< 0-based index among the shape's faces
  bool known() const { return t == t; }
  friend bool operator==(const ShapeParameter&, const ShapeParameter&) = default;
};

/// No earlier projection to start from: the search is global.
inline constexpr ShapeParameter kNoHint{std::numeric_limits<double>::quiet_NaN(), 0.0, 0};

/// A point on a boundary shape with its unit normal and parameter.
struct ShapePoint {
  Vec3 point;
  /// Unit normal to the boundary at `point`: in the x-y plane for 2D shapes, in the meridional
  /// plane through the point for axisymmetric ones. Its sign is the shape's convention
  /// (consistent along the shape; for curves, to the left of increasing t; at a corner, the
  /// bisector of the two sides); users that need "outward" orient it themselves.
  Vec3 normal;
  ShapeParameter parameter;  ///< for planes, t = 0
  double distance = 0.0;   ///< distance from the point that was projected (0 for at())
};

/// A parameter interval [first, last] of a shape: the part of it between two of its features,
/// which a sliding node may not leave (it would slide across a corner). The default is the
/// whole shape. On a shape of faces, `region` is instead the part between its creases
/// (BoundaryShape::crease_region; -1: the whole shape).
struct ParameterRange {
  double first = -std::numeric_limits<double>::infinity();
  double last = std::numeric_limits<double>::infinity();
  int region = -1;
  bool contains(double t) const { return first <= t && t <= last; }
};

/// A corner of the shape that every stage keeps at one parameter: a C0 point of the deflected
/// curve (a kink of the FEM table, a CAD vertex where edges meet at an angle, a knot of full
/// multiplicity). For a surface of revolution it is a circle about the axis.
struct ShapeFeature {
  double parameter = 0.0;
  /// The largest angle (radians) by which the undeformed or the fully deflected shape turns
  /// there, between the tangents on either side.
  double angle = 0.0;
  /// The angle (radians) by which the undeformed shape turns there: a corner of the wall as
  /// drawn (a CAD vertex, a kink of the cold FEM wall), where a mesh made from CAD has a node,
  /// rather than one the deflection makes.
  double undeformed_angle = 0.0;
};
/// An edge where two faces of a shape meet turning by an angle: the faces' indices (increasing)
/// and the largest angle (radians) between their normals along the edge, undeformed or fully
/// deflected.
struct ShapeCrease {
  std::array<int, 2> faces{-1, -1};
  double angle = 0.0;
};

/// The point of a crease nearest a given point, with each face's unit normal there.
struct CreasePoint {
  Vec3 point;
  std::array<Vec3, 2> normals;  ///< of faces[0] and faces[1]
};

class BoundaryShape {
 public:
  virtual ~BoundaryShape() = default;

  /// The closest point to p on the stage-lambda shape. Axisymmetric shapes project in the
  /// meridional plane through p (keeping its angle theta). `hint` is the parameter of an
  /// earlier projection of a nearby point (a warm start); with kNoHint the search is global.
  /// Even with a hint the result is the global closest point, except where a point moved by
  /// much more than its distance to a near branch of the curve since the hint was computed.
  /// Const and thread-safe: called from parallel loops over nodes.
  /// `range` restricts the search to a part of a curve's parameter t, or to a region of a
  /// shape of faces (other shapes ignore it).
  virtual ShapePoint project(const Vec3& p, double lambda, const ShapeParameter& hint = kNoHint,
                             const ParameterRange& range = {}) const = 0;

  /// The point of the stage-lambda shape at `where`. For axisymmetric shapes it lies in the
  /// meridional plane through `reference` (any point off the axis).
  virtual ShapePoint at(const ShapeParameter& where, double lambda, const Vec3& reference) const = 0;

  /// The shape's corners that turn by at least `min_angle` (radians) on the undeformed or the
  /// fully deflected stage, in increasing parameter; none for smooth shapes and planes.
  virtual std::vector<ShapeFeature> features(double /*min_angle*/) const { return {}; }

  /// Where the shape is made of faces that meet at an edge turning by at least `min_angle`
  /// (radians), at the point `where` of such an edge: the faces on either side as shapes of
  /// their own, so that a node held by all of them slides along the edge (or, at a corner of
  /// three faces, stays on it). Empty elsewhere and for shapes without faces.
  virtual std::vector<std::shared_ptr<const BoundaryShape>> crease_sides(const ShapeParameter& /*where*/,
                                                                         double /*min_angle*/) const {
    return {};
  }

  /// The shape's creases turning by at least `min_angle` (radians); none for shapes without
  /// faces. Unlike crease_sides they need no mesh node on them: a wall whose mesh lines miss
  /// a crease is given nodes for it (deform's corner pass).
  virtual std::vector<ShapeCrease> creases(double /*min_angle*/) const { return {}; }
  /// The point of the stage-lambda crease nearest p (one of creases()). Throws
  /// std::logic_error for shapes without creases.
  virtual CreasePoint crease_point(const ShapeCrease& crease, const Vec3& p, double lambda) const;
  /// The region of `face` between the creases of at least `min_angle`: the faces joined to it
  /// through edges that are not such creases, as the `region` of a ParameterRange, so that a
  /// node projected within it never crosses a crease. -1 for shapes without faces.
  virtual int crease_region(int /*face*/, double /*min_angle*/) const { return -1; }
};

}  // namespace hotmesh::geometry
