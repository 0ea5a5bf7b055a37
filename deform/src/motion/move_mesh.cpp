// hotmesh deform: move_mesh (hotmesh/deform/move_mesh.hpp): the element kernel of the run
// (eq. 35 on the undeformed mesh), the motion (motion.hpp), then the corner pass
// (corner_pass.hpp); and the linear solver `auto` picks.
#include "hotmesh/deform/move_mesh.hpp"

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "motion/corner_pass.hpp"
#include "motion/motion.hpp"
#include "hotmesh/core/clock.hpp"

namespace hotmesh::deform {

namespace detail {

std::vector<NodeId> moving_wall_nodes(const Mesh& mesh, std::span<const PatchMotion> patches) {
  std::vector<NodeId> nodes;
  for (const PatchMotion& m : patches) {
    if (!follows_shape(m.role)) continue;
    if (const mesh::Patch* patch = mesh.find_patch(m.patch)) nodes.insert(nodes.end(), patch->nodes.begin(), patch->nodes.end());
  }
  return nodes;
}

}  // namespace detail


LinearSolverChoice choose_linear_solver(const Mesh& mesh, std::span<const PatchMotion> patches, int processes) {
  const bool sliding = std::any_of(patches.begin(), patches.end(), [](const PatchMotion& m) { return m.role == BoundaryRole::sliding; });
  return choose_linear_solver(mesh.dimension, mesh.cell_count(), sliding, processes);
}

MotionResult move_mesh(const Mesh& mesh, std::span<const PatchMotion> patches, const MaterialOptions& material,
                       const SolverOptions& options, const MotionObservers& observers, const MotionStart* start,
                       const MotionCheckpoint* resume, const parallel::RankExchange& ranks) {
  const auto begin = Clock::now();
  SolverOptions solver = options;
  if (solver.linear == LinearSolverKind::automatic) solver.linear = choose_linear_solver(mesh, patches, ranks.ranks()).kind;
  require_motion_cells(mesh);  // before eq. (35), which would measure the other cell types
  const bool corners = detail::has_corners(patches);
  std::vector<PatchMotion> sliding_freely(patches.begin(), patches.end());
  for (PatchMotion& m : sliding_freely) m.features.enabled = false;  // corners and creases on nodes stay held
  auto kernel = std::make_shared<const StiffnessKernel>(
      mesh, element_lame(mesh, material, detail::moving_wall_nodes(mesh, patches)), material.drop_jacobian);
  detail::Motion motion(mesh, sliding_freely, kernel, solver, observers, start, ranks);
  motion.set_setup_time(seconds_since(begin));
  MotionResult result = motion.run(resume);
  if (!corners || !result.success) return result;
  return detail::hold_corners(mesh, patches, *kernel, material, solver, observers, ranks, std::move(result));
}

}  // namespace hotmesh::deform
