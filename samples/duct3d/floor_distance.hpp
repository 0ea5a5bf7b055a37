// hotmesh sample duct3d: how far a (deformed) mesh's floor is from the exact deflected floor
// X(t, s) = S(t, s) + delta(t, s) of a load (duct_floor.hpp), for the results page and tests.
//
// The mesh's floor is its patch's faces: each quad the bilinear patch through its four nodes,
// each triangle (a hybrid mesh's floor) the flat triangle through its three. Three measures:
//   nodes          max over the patch's nodes of the distance to X (closest point by
//                  Gauss-Newton on (t, s), started at the node's x and y): the nodes on the wall;
//   mesh_to_floor  max over points of the faces (each quad sampled on a (k+1) x (k+1) grid of
//                  its bilinear parameters, each triangle on the (k+1)(k+2)/2 points of its
//                  barycentric grid) of the distance to X: the faces off the wall (faceting, a
//                  cell's sagitta, plus the nodes' error);
//   floor_to_mesh  max over points of X (a grid in (t, s) about k times finer than the quads) of
//                  the distance to the nearest face (closest point of each candidate bilinear
//                  patch or triangle, candidates pruned by their bounding boxes): the wall off
//                  the faces.
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
#include <vector>

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
/// that the mesh lacks, that has faces other than quads and triangles, or meshes whose node
/// counts differ.
FloorDistance floor_distance(const mesh::Mesh& mesh, const DeflectedFloor& floor, const FloorDistanceOptions& options = {},
                             const mesh::Mesh* undeformed = nullptr);

/// How far apart two meshes of the same nodes end (two runs that should agree, e.g. a restarted
/// run and a straight one): the largest distance between a node of `a` and the same node of
/// `b`, over every node and over the nodes of `patch` (point: in a; nearest: in b). Throws
/// std::invalid_argument for meshes whose node counts differ or a patch that `a` lacks.
struct NodesApart {
  WorstPoint all;
  WorstPoint patch;
};
NodesApart nodes_apart(const mesh::Mesh& a, const mesh::Mesh& b, const std::string& patch = "floor");
/// As a JSON object {"all": ..., "<patch>": ...} (mm, and over h).
std::string to_json(const NodesApart& apart, const std::string& patch = "floor");

/// Where the plane x = value (axis 0) or y = value (axis 1) cuts the exact floor: n + 1 points
/// of X, at parameters evenly spaced over the other coordinate's range (for each, Newton on the
/// parameter of the plane's coordinate, t for x and s for y, from value). For pictures of a mesh
/// cut by the same plane. Throws std::invalid_argument for another axis or n < 1.
std::vector<Vec3> floor_section(const DeflectedFloor& floor, int axis, double value, int n);

/// The measures as a JSON object (mm, and over h), for duct_wall_distance.
std::string to_json(const FloorDistance& d);

}  // namespace hotmesh::samples::duct3d
