// hotmesh deform: fixed and prescribed nodes: where each prescribed node lies on its shape, and
// where it is at a stage (prescribed_position).
#include <cstddef>
#include <vector>

#include "constraints/boundary_builder.hpp"
#include "constraints/boundary_conditions.hpp"

namespace hotmesh::deform::detail {

Vec3 prescribed_position(const PrescribedNode& p, const Vec3& original, double lambda) {
  const Vec3 moved = p.shape->at(p.parameter, lambda, original).point;
  const Vec3 start = p.shape->at(p.parameter, 0.0, original).point;
  if (p.reaches_shape) return moved + (1.0 - lambda) * (original - start);
  return original + (moved - start);
}

/// Fixed and prescribed nodes.
void BoundaryBuilder::constrain_fixed_and_prescribed_nodes() {
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    const Patch& patch = mesh_.patches[p];
    const PatchMotion& m = *motion_of_[p];
    if (patch.nodes.empty()) continue;
    if (m.role == BoundaryRole::fixed) {
      for (NodeId n : patch.nodes) {
        if (!is_slave(n)) setup_.constraints.fix(n);
      }
    } else if (m.role == BoundaryRole::prescribed) {
      std::vector<NodeId> nodes;
      for (NodeId n : patch.nodes) {
        if (owner_[static_cast<std::size_t>(n)] == static_cast<int>(p) && !is_slave(n)) nodes.push_back(n);
      }
      const Located located = locate(mesh_, x0_, patch, m, nodes);
      setup_.wall_gaps.push_back(located.gap);
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        setup_.prescribed.push_back({nodes[k], located.parameters[k], m.shape.get()});
        setup_.constraints.fix(nodes[k]);
      }
    }
  }
}

}  // namespace hotmesh::deform::detail
