// hotmesh deform (internal): from patch roles to what each node does. Every node takes the
// strongest role of the patches it lies on,
//     fixed > prescribed > sliding > passive > slip > periodic > interior (BoundaryRoleTraits),
// so a node is never moved twice. A sliding node keeps the shapes of all its sliding patches
// (two or three where sliding walls meet: it then moves along their intersection, or stays
// put where they meet in a point), the planes of its slip patches and, on the rim of a passive
// surface that crosses its wall, the plane tangent to that surface's undeformed shape there:
// it slides along the line where wall and surface meet, and the surface, solved from its rim,
// follows it. The slave node of a periodic pair has no motion of its own: it follows its
// master (periodic.hpp).
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "constraints/passive.hpp"
#include "constraints/periodic.hpp"
#include "constraints/sliding.hpp"
#include "constraints/wall_features.hpp"
#include "hotmesh/deform/constraints.hpp"
#include "hotmesh/deform/mesh_motion.hpp"

namespace hotmesh::deform::detail {

/// A node that follows a deflected shape: x(lambda) = x0 + at(t, lambda) - at(t, 0). A node
/// that holds a corner of a sliding wall reaches it: its offset from the corner at stage 0
/// fades over the increments, x(lambda) = at(t, lambda) + (1 - lambda) (x0 - at(t, 0)).
struct PrescribedNode {
  NodeId node = 0;
  geometry::ShapeParameter parameter;
  const geometry::BoundaryShape* shape = nullptr;
  bool reaches_shape = false;
};

/// A node of a passive surface: moves by `displacement` times the stage (unless its surface
/// follows a sliding rim: then `displacement` is its place at the rim's targets).
struct PassiveNode {
  NodeId node = 0;
  Vec3 displacement;
};

/// A passive surface with sliding nodes on its rim (directly or through passive surfaces
/// solved before it): where its rim will end is not known beforehand, so it is solved again
/// from the rim's positions every time the rim moves (follow_sliding_rims).
struct FollowingSurface {
  PassiveSurface surface;
  std::vector<std::pair<std::size_t, NodeId>> nodes;  ///< the nodes it moves: index in the patch, node
};

/// A corner of a sliding wall with the nodes that hold it (wall_features.hpp).
struct WallCorner {
  std::string patch;
  const geometry::BoundaryShape* shape = nullptr;
  Vec3 reference;  ///< a node of the wall: its meridional plane is where the corner is reported
  HeldFeature held;
};

/// An edge where faces of a sliding wall meet at an angle, and the nodes sliding along it
/// (or, where three faces meet, staying at their corner).
struct WallCrease {
  std::string patch;
  std::vector<int> faces;  ///< the wall's face indices that meet there, increasing
  double angle = 0.0;      ///< radians between their normals, the largest at its nodes, undeformed or deflected
  std::vector<NodeId> nodes;  ///< the nodes on it from the start, then those given it
  std::vector<const geometry::BoundaryShape*> sides;  ///< the faces as shapes (in corner_paths)
  /// Where the mesh's lines miss the crease (the corner pass): the wall and the crease, the
  /// farthest of the nodes given it (the last of `nodes`) from it before the pass, and the
  /// wall edges across it left without a node on it.
  const geometry::BoundaryShape* wall = nullptr;
  geometry::ShapeCrease line;
  double largest_offset = 0.0;
  std::size_t unheld_edges = 0;
};

struct BoundarySetup {
  /// Positions the shapes' stage 0 refers to: the mesh's, or those a restarted run starts from
  /// (MotionStart::points). Not copied: both outlive the set-up (move_mesh's arguments).
  std::span<const Vec3> reference;
  NodeConstraints constraints;
  std::vector<PrescribedNode> prescribed;
  std::vector<SlidingNode> sliding;
  std::vector<PassiveNode> passive;
  std::vector<FollowingSurface> following;  ///< in the order they are solved
  /// Those of slip patches, then the planes tangent to passive surfaces that hold the sliding
  /// nodes of their rims.
  std::vector<SlipPlane> slip_planes;
  PeriodicCoupling periodic;
  std::vector<WallCorner> corners;
  std::vector<WallCrease> creases;
  /// The paths of the nodes that slide along corner lines, and the faces of the nodes that
  /// slide along creases of walls made of faces (SlidingNode::shapes point to them).
  std::vector<std::shared_ptr<const geometry::BoundaryShape>> corner_paths;
  std::vector<NodeRoleCode> roles;
  std::vector<std::string> notes;
  std::vector<WallGap> wall_gaps;  ///< how far each moving patch's nodes lay from its undeformed wall
};

/// Throws hotmesh::InputError for set-ups the solver cannot take.
BoundarySetup set_up_boundaries(const Mesh& mesh, std::span<const PatchMotion> patches, const MotionStart* start);

/// Position of a prescribed node at stage lambda.
Vec3 prescribed_position(const PrescribedNode& p, const Vec3& original, double lambda);

}  // namespace hotmesh::deform::detail
