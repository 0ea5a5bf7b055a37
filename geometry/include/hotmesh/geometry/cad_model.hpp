// hotmesh geometry: CAD files (STEP, IGES) read with OpenCASCADE, seen as a list of faces and
// edges, and as the source of the walls' curves: meridional curves of faces (section 4.2: "the
// intersection of a CAD surface with a meridional plane is a B-Spline curve r(t)") and, for 2D
// cases drawn in the plane z = 0, the curve of some edges in that plane.
//
// Faces are numbered 1, 2, ... in the order OpenCASCADE explores the transferred shape, which
// follows the file; a face used by several instances of an assembly appears once per instance.
// Edges are numbered 1, 2, ...: first those of the faces, face by face in face order (the numbers
// a CadFace's edges carry), then those outside any face (the wires and loose edges of a
// drawing), in the order OpenCASCADE explores the shape.
// Coordinates are converted on import to the length unit asked for (metres by default), so
// FEM tables and meshes in that unit match. Surfaces of revolution are recognised from their
// type (revolved curves, cylinders, cones, spheres, tori: the axis is the file's) or, for
// B-spline and other free-form faces, by fitting an axis to their normals and checking that
// every normal meets it (see docs/geometry.md).
//
// OpenCASCADE's readers are not thread-safe; hotmesh serialises them. A CadModel itself is
// meant for one thread at a time.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/bspline_curve.hpp"
#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/geometry/cad_face.hpp"
#include "hotmesh/core/enum_names.hpp"

namespace hotmesh::geometry {

enum class LengthUnit { metre, millimetre, centimetre, micrometre, inch, foot };
/// The abbreviations the case file, the command line and the service use.
inline constexpr EnumNames<LengthUnit, 6> kLengthUnitNames{{{{LengthUnit::metre, "m"},
                                                            {LengthUnit::millimetre, "mm"},
                                                            {LengthUnit::centimetre, "cm"},
                                                            {LengthUnit::micrometre, "um"},
                                                            {LengthUnit::inch, "in"},
                                                            {LengthUnit::foot, "ft"}}}};

const char* to_string(LengthUnit unit);  ///< "m", "mm", "cm", "um", "in", "ft"
/// The unit named by one of those abbreviations; empty if none.
std::optional<LengthUnit> parse_length_unit(std::string_view text);

enum class SurfaceKind { plane, cylinder, cone, sphere, torus, revolution, extrusion, bspline, bezier, offset, other };

const char* to_string(SurfaceKind kind);  ///< "plane", "cylinder", ..., "bspline", ...

/// Where the axis of a face comes from.
enum class AxisSource {
  none,      ///< not a surface of revolution (or no unique axis: planes, free-form spheres)
  analytic,  ///< the file's own definition (revolved curve, cylinder, cone, sphere, torus)
  fitted,    ///< fitted to a free-form (B-spline, ...) face that is rotational within tolerance
};

const char* to_string(AxisSource source);

struct Box3 {
  Vec3 min;
  Vec3 max;
};

/// The kind of curve an edge follows.
enum class EdgeKind { line, circle, ellipse, hyperbola, parabola, bezier, bspline, offset, other, degenerated };

const char* to_string(EdgeKind kind);  ///< "line", "circle", ..., "degenerated" (collapsed to a point)

struct EdgeInfo {
  int id = 0;  ///< 1-based (see the top of this file)
  EdgeKind kind = EdgeKind::other;
  Vec3 start;  ///< the ends of its curve, in the curve's direction
  Vec3 end;
  double length = 0.0;
};

struct FaceInfo {
  int id = 0;        ///< 1-based, file order
  std::string name;  ///< from the file (STEP item name, IGES name or label); empty if none
  SurfaceKind kind = SurfaceKind::other;
  std::optional<Axis> axis;
  AxisSource axis_source = AxisSource::none;
  Box3 bounds;       ///< axis-aligned bounding box
};

struct CadReadOptions {
  LengthUnit unit = LengthUnit::metre;  ///< unit of every coordinate hotmesh gets back
};

struct MeridionalOptions {
  /// The axis of revolution. Without it, the faces' own axes are used (they must agree).
  std::optional<Axis> axis;
  /// Tolerance relative to the size of the faces (their bounding-box diagonal): for axes to
  /// agree, for a face to be rotational about the axis, and for curve ends to meet.
  double relative_tolerance = 1e-4;
};

/// The meridional curve of some faces: (r, z) about `axis`, parameter [0, 1].
struct MeridionalCurve {
  BSplineCurve2d curve;
  Axis axis;
  std::vector<int> faces;           ///< the faces in order along the curve
  std::vector<double> face_breaks;  ///< parameter where each of `faces` starts, then 1
  double tolerance = 0.0;           ///< the absolute tolerance used
};

struct PlanarCurveOptions {
  /// Tolerance relative to the size of the edges (their bounding-box diagonal): for an edge to
  /// lie in the plane z = 0 and for the ends of two edges to meet.
  double relative_tolerance = 1e-4;
};

/// The curve of some edges in the plane z = 0: (x, y), parameter [0, 1].
struct PlanarCurve {
  BSplineCurve2d curve;
  std::vector<int> edges;           ///< the edges in order along the curve
  std::vector<double> edge_breaks;  ///< parameter where each of `edges` starts, then 1
  double tolerance = 0.0;           ///< the absolute tolerance used
};

class CadModel {
 public:
  /// Reads a STEP (.step, .stp) or IGES (.iges, .igs) file. Throws hotmesh::InputError naming
  /// the file if it cannot be read, is empty, is not STEP/IGES, or holds neither faces nor edges
  /// (a drawing of edges alone is read: a 2D case's walls).
  static CadModel read(const std::filesystem::path& path, const CadReadOptions& options = {});

  CadModel(CadModel&&) noexcept;
  CadModel& operator=(CadModel&&) noexcept;
  ~CadModel();

  const std::filesystem::path& path() const;
  LengthUnit unit() const;
  const std::vector<FaceInfo>& faces() const;
  /// Throws hotmesh::InputError if there is no face `id`.
  const FaceInfo& face(int id) const;
  const std::vector<EdgeInfo>& edges() const;
  /// Throws hotmesh::InputError if there is no edge `id`.
  const EdgeInfo& edge(int id) const;

  /// The face's surface as a B-spline, trimmed to the face's parameter bounds.
  BSplineSurface face_bspline(int id) const;
  /// The face as a wall on CAD faces takes it: its B-spline (face_bspline) and the edges that
  /// bound it (cad_face.hpp), numbered as in the whole model.
  CadFace cad_face(int id) const;

  /// Section 4.2, eq. (20): the meridional curve r(t) of the faces, in (r, z) about the axis:
  /// the basis curve for surfaces of revolution (exact, rational where it is), the section by
  /// a meridional plane otherwise (planes and free-form faces, checked to be rotational). The
  /// curves of several faces are joined end to end, ordered along the profile, oriented so that
  /// z (then r) grows from start to end, with a parameter proportional to arc length per face.
  /// Throws hotmesh::InputError naming the faces when there is no common axis, a face is not
  /// rotational about the axis, or the curves do not form one connected profile.
  MeridionalCurve meridional_curve(std::span<const int> face_ids, const MeridionalOptions& options = {}) const;

  /// The meridional curves of faces that may form several separate profiles (a casing on
  /// either side of a blade row): one curve per connected group of faces, each as
  /// meridional_curve gives it, all about the same axis and with the tolerance of the whole
  /// set, in the order of each group's first face in `face_ids`. One curve when the faces form
  /// one profile. Throws as meridional_curve does, except for separate profiles.
  std::vector<MeridionalCurve> meridional_profiles(std::span<const int> face_ids,
                                                   const MeridionalOptions& options = {}) const;

  /// The wall of a 2D case drawn in CAD: the curves of the edges, which must lie in the mesh's
  /// plane z = 0, joined end to end into one curve in (x, y) as meridional_curve joins faces
  /// (C0 at the edges' common vertices, so that the wall's corners are the CAD vertices), ordered
  /// along the chain, oriented so that x (then y) grows from start to end, with a parameter
  /// proportional to arc length per edge. Circles and other conics are exact (rational). Throws
  /// hotmesh::InputError naming the edge when one is off the plane (with its distance), collapsed
  /// to a point or without a curve, or when the edges do not form one chain.
  PlanarCurve planar_curve(std::span<const int> edge_ids, const PlanarCurveOptions& options = {}) const;

 private:
  struct Impl;
  explicit CadModel(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hotmesh::geometry
