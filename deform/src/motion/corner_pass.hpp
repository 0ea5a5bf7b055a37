// hotmesh deform (internal): the corner pass after a successful motion (issue 20, beyond the
// paper): the nodes nearest the corners of the sliding walls move onto them, in a second run of
// the increments (motion.hpp) from the motion's mesh; the quality it costs is repaired
// (quality_repair.hpp), and it is undone if it still costs too much.
#pragma once

#include <span>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"

namespace hotmesh::deform::detail {

/// Whether a sliding wall has corners (or creases) for nodes to hold.
bool has_corners(std::span<const PatchMotion> patches);

/// The corner pass after a successful motion `moved` (issue 20, beyond the paper): each corner
/// of a sliding wall is given the node nearest it, which moves onto it; the other sliding
/// nodes keep to their segments between corners. Run after the motion, not through it, so
/// that nodes still gather where the wall needs them (on a ramp, across its corners): corners
/// held from the start would freeze the number of nodes between them. If the pass fails, the
/// mesh of the motion stands, with a note.
///
/// The pass is an elastic problem of its own whose original mesh is the motion's result, so
/// eq. (35)'s measures |phi_s|, |phi_v| are taken there (`motion_kernel` with new Lamé
/// parameters): the cells the motion sheared stiffen and take less of the corners' moves
/// (ramp: worst cell 0.512 against 0.496 with the measures of the undeformed mesh).
MotionResult hold_corners(const Mesh& mesh, std::span<const PatchMotion> patches,
                          const StiffnessKernel& motion_kernel, const MaterialOptions& material,
                          const SolverOptions& solver, const MotionObservers& observers,
                          const parallel::RankExchange& ranks, MotionResult moved);

}  // namespace hotmesh::deform::detail
