// hotmesh deform: moving a mesh to follow its boundaries — the whole method of the paper
// (what it takes and gives: hotmesh/deform/mesh_motion.hpp).
//
// The prescribed motion is applied in N increments (stages lambda_k = k/N). Each increment
// starts from the geometry reached by the previous one and solves the elastic-medium
// analogy with geometric nonlinearity by the paper's Newton-Raphson cycle (eqs. 7-8):
//     R(u) = K(x + u) u - f,      K(n) p = -R(n),      u(n+1) = u(n) + p,
// K rebuilt at the current geometry every iteration, until ||R|| <= tol ||R0||. Each linear
// system is solved by preconditioned CG on the free degrees of freedom, with nodal Jacobi
// (the paper's, K in node blocks) or assembled in nodal frames with algebraic multigrid
// (SolverOptions::linear). After every
// increment the cells are checked; an increment that inverts a cell or whose Newton cycle
// fails is retried as two half increments (recursively, up to a limit). If it still fails,
// the run stops with the last valid mesh and a message naming the cell and increment.
// Observers see every Newton step and every attempt; after each accepted step the run hands
// out its state (MotionCheckpoint), from which a run that was killed later resumes and makes
// the same moves to the last bit.
#pragma once

#include <span>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"

namespace hotmesh::deform {

/// Moves `mesh` (validated) as its patches prescribe. Every mesh patch needs an entry in
/// `patches`. Throws hotmesh::InputError for a set-up the solver cannot take (unknown patch,
/// missing shape, patch nodes off their shape, a slip patch that is not planar, cells other
/// than quad4/hex8) and FreeRigidMotion for roles that leave a rigid-body motion free; a
/// failure of the motion itself is reported in the result.
/// With `start`, the run continues from a previous one (see MotionStart): the patch shapes
/// must then start (stage 0) where the previous run ended.
/// With `resume`, the run picks up an interrupted run of the same set-up (same mesh, patches,
/// options and `start`) where its checkpoint left it; its result is the uninterrupted run's
/// (records and timings include those of the interrupted run). Throws hotmesh::InputError if
/// the checkpoint does not fit the set-up (node counts, sliding nodes, increments).
/// With `ranks` the processes of a job (each with the same mesh and set-up) share the work of
/// the run (hotmesh/parallel/processes.hpp) and all end with the same result.
/// What `linear: auto` picks for a motion of `mesh` with `patches` on `processes` processes:
/// choose_linear_solver() with the mesh's dimension and cells and whether a patch slides.
/// move_mesh resolves SolverOptions::linear = automatic with it.
LinearSolverChoice choose_linear_solver(const Mesh& mesh, std::span<const PatchMotion> patches, int processes);

MotionResult move_mesh(const Mesh& mesh, std::span<const PatchMotion> patches, const MaterialOptions& material,
                       const SolverOptions& solver, const MotionObservers& observers = {},
                       const MotionStart* start = nullptr, const MotionCheckpoint* resume = nullptr,
                       const parallel::RankExchange& ranks = parallel::one_process());

}  // namespace hotmesh::deform
