// hotmesh deform (internal): from patch roles to what each node does. Every node takes the
// strongest role of the patches it lies on: fixed > prescribed > slip > interior, so a node
// is never moved twice. Slip nodes collect the normals of all their slip patches.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "hotmesh/deform/constraints.hpp"
#include "hotmesh/deform/mesh_motion.hpp"

namespace hotmesh::deform::detail {

/// A node that follows a deflected shape: x(lambda) = x0 + at(t, lambda) - at(t, 0).
struct PrescribedNode {
  NodeId node = 0;
  double parameter = 0.0;
  const geometry::BoundaryShape* shape = nullptr;
};

struct BoundarySetup {
  NodeConstraints constraints;
  std::vector<PrescribedNode> prescribed;
  std::vector<NodeRoleCode> roles;
  std::vector<std::string> notes;
};

/// Throws hotmesh::InputError for set-ups the solver cannot take.
BoundarySetup set_up_boundaries(const Mesh& mesh, std::span<const PatchMotion> patches);

/// Position of a prescribed node at stage lambda.
Vec3 prescribed_position(const PrescribedNode& p, const Vec3& original, double lambda);

}  // namespace hotmesh::deform::detail
