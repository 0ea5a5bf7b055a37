// hotmesh sample duct3d: how far a (deformed) mesh's floor is from the exact deflected floor
// X(t, s) = S(t, s) + delta(t, s) of a load (duct_floor.hpp), for the results page and tests.
//
// The mesh's floor is its patch's quads, each the bilinear patch through its four nodes. Three
// measures:
//   nodes          max over the patch's nodes of the distance to X (closest point by
//                  Gauss-Newton on (t, s), started at the node's x and y): the nodes on the wall;
//   mesh_to_floor  max over points of the quads (each sampled on a (k+1) x (k+1) grid of its
//                  bilinear parameters) of the distance to X: the faces off the wall (faceting,
//                  a cell's sagitta, plus the nodes' error);
//   floor_to_mesh  max over points of X (a grid in (t, s) about k times finer than the quads) of
//                  the distance to the nearest quad (closest point of each candidate bilinear
//                  patch, candidates pruned by their bounding boxes): the wall off the faces.
// The two-sided (Hausdorff) distance is the larger of the last two. With the undeformed mesh
// too, material_point_error: max over the nodes of |x_i - X(t_i, s_i)|, (t_i, s_i) the node's
// parameters in the undeformed mesh: how far each node is from where the FEM field carries its
// material point (0 for a prescribed wall that follows the field exactly; a sliding wall's nodes
// may slide away from it while staying on the wall).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

#include "duct_floor.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::samples::duct3d {

/// Where a largest distance is reached: the point, the nearest point of the other side.
struct WorstPoint {
  double distance = 0.0;
  Vec3 point;
  Vec3 nearest;
  std::int64_t node = 0;  ///< the mesh node's id, for node measures (0 otherwise)
};

struct FloorDistance {
  std::size_t nodes = 0;
  std::size_t faces = 0;
  WorstPoint node;           ///< nodes to X
  WorstPoint mesh_to_floor;  ///< quads to X
  WorstPoint floor_to_mesh;  ///< X to the quads
  std::optional<WorstPoint> material_point;  ///< with an undeformed mesh: x_i to X(t_i, s_i)
  double hausdorff() const { return std::max(mesh_to_floor.distance, floor_to_mesh.distance); }
};

struct FloorDistanceOptions {
  std::string patch = "floor";
  int samples = 4;  ///< k: subdivisions per quad (both ways) on either side
};

/// The measures above for `mesh`'s patch against `floor`; `undeformed` (the same mesh before
/// the motion, same node order) adds material_point. Throws std::invalid_argument for a patch
/// that the mesh lacks, that has faces other than quads, or meshes whose node counts differ.
FloorDistance floor_distance(const mesh::Mesh& mesh, const DeflectedFloor& floor, const FloorDistanceOptions& options = {},
                             const mesh::Mesh* undeformed = nullptr);

/// The measures as a JSON object (mm, and over h), for duct_wall_distance.
std::string to_json(const FloorDistance& d);

}  // namespace hotmesh::samples::duct3d
