// hotmesh api: the two-sided distance between a mesh patch's faces and its wall (issue 20,
// item 4), as `hotmesh check` and report.json give it. The node distances of a patch do not
// see a corner cut by an edge between two nodes; this measures the faces themselves
// (geometry::wall_deviation: against a curve in the x-y plane in 2D or in the meridional plane
// about the axis in 3D, naming the worst location with the nodes of its edge; against CAD
// faces of any shape, naming the mesh face and the CAD face's (t, s)). A wall without a
// surface (the table interpolated over a wall without CAD faces) is reported as not measured,
// saying why.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/geometry/wall_deviation.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::api {

/// One side of the two-sided distance, with node numbers of the mesh file.
struct WallSide {
  double distance = 0.0;
  geometry::Vec3 point;    ///< where it is reached: on the mesh's faces, or on the shape
  geometry::Vec3 nearest;  ///< the nearest point of the other side
  double parameter = 0.0;  ///< curve parameter (on faces: t) of whichever of the two lies on the shape
  std::array<std::int64_t, 2> edge_nodes{0, 0};  ///< curves: the face edge holding the mesh's point
  std::vector<std::int64_t> face_nodes;          ///< faces: the mesh face holding the mesh's point
  double parameter_s = 0.0;                      ///< faces: s of the point on the shape
  int cad_face = 0;                              ///< faces: the CAD face it lies on (its number)
};

/// The two-sided distance of a patch (or part of one) to its shape.
struct WallCheck {
  /// What the shape is: "curve", "faces" or "scattered" (setup::WallKind's names), or "other".
  std::string shape = "curve";
  /// Why the faces were not measured (a wall without a surface); empty: measured.
  std::string not_measured;
  std::size_t edges = 0;   ///< curves: distinct face edges measured
  std::size_t faces = 0;   ///< faces: mesh faces measured
  std::size_t shape_samples = 0;      ///< faces: samples of the CAD faces
  std::size_t uncovered_samples = 0;  ///< faces: of those, left out beyond the patch's rim
  WallSide mesh_to_shape;  ///< the faces off the shape (e.g. a chord's sagitta)
  WallSide shape_to_mesh;  ///< the shape off the faces (e.g. a corner cut by an edge)
  double hausdorff = 0.0;
  std::string worst;       ///< "mesh_to_shape" or "shape_to_mesh"
  std::array<double, 2> parameter_range{0.0, 0.0};  ///< curves: the part of the curve the faces cover
  bool passed = true;      ///< hausdorff within the wall tolerance (true without one, or not measured)

  bool measured() const { return not_measured.empty(); }
  const WallSide& worst_side() const { return worst == "shape_to_mesh" ? shape_to_mesh : mesh_to_shape; }
};

/// The faces of `patch` (or those with `selected[f]`, when given) as a geometry::WallFaces.
geometry::WallFaces wall_faces(const mesh::Patch& patch, std::span<const std::uint8_t> selected = {});

/// The two-sided distance between `faces` (corners into `points`) and stage `lambda` of
/// `shape`: for curve shapes (a planar curve, or a surface of revolution through its
/// meridional curve) and walls on CAD faces (geometry::SurfaceShape); for other shapes (the
/// table interpolated over a wall, geometry::ScatteredShape) a check not measured, saying why.
WallCheck measure_wall(const geometry::BoundaryShape& shape, double lambda, const mesh::Mesh& mesh,
                       std::span<const geometry::Vec3> points, const geometry::WallFaces& faces);

/// Where a side's point lies on the mesh, for messages: "face edge of nodes 4-5" (curves) or
/// "mesh face of nodes 4-5-9-8" (faces).
std::string mesh_location(const WallSide& side);

/// The JSON object of a wall check; `length_scale` > 0 adds a `…_relative` twin to every length.
nlohmann::json wall_json(const WallCheck& wall, double length_scale = 0.0);

/// One line for people: "two-sided distance 2.5e-02 (shape_to_mesh: the shape at (…) is …)", or
/// "not measured: …".
std::string wall_text(const WallCheck& wall);

/// report.json's `wall_deviations`: for every prescribed and sliding patch of the case, the
/// two-sided distance between its faces at `points` (the final mesh) and its shape at stage
/// `lambda` (1: the deflected shape; the stage reached for a failed run), or why it was not
/// measured.
nlohmann::json wall_deviations_json(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                                    const setup::CaseSetup& setup, double lambda, double length_scale);

}  // namespace hotmesh::api
