// hotmesh deform (internal): the assembled linear solvers (SolverOptions::linear = amg, direct
// or icc). The system in nodal frames (nodal_frames.hpp) is assembled into a PETSc matrix with
// block size d, preallocated once from the node graph, and solved by CG with algebraic
// multigrid (PCGAMG with the rigid-body near-null space, or hypre's BoomerAMG), with its
// sparse Cholesky factors (CHOLMOD, MUMPS) or with its incomplete Cholesky factors (PCICC). PETSc and MPI types stay in
// petsc_solver.cpp, petsc_preconditioner.* (the preconditioners), frame_matrix.hpp (the matrix)
// and petsc_probes.cpp (the test hooks below); PETSc is initialised on first use, once
// per process (hotmesh/parallel/processes.hpp), and finalised at exit.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "constraints/nodal_frames.hpp"
#include "storage/linear_solver.hpp"

namespace hotmesh::deform::detail {

/// With several processes in `ranks`, the matrix and the element work are distributed among them.
/// K(n) is computed in its element pass (ElementAssembler).
std::unique_ptr<LinearSolver> make_assembled_solver(const SolverOptions& options, const parallel::RankExchange& ranks);

/// For tests: K~ of the system in `frames` (updated by the caller), assembled into a PETSc
/// matrix exactly as the amg solver does it, applied to x~ (MatMult). With `twice`, assembled
/// a second time into the same matrix, as every Newton step after the first does.
std::vector<double> assembled_frame_product(const ConstrainedSystem& system, const NodalFrames& frames,
                                            std::span<const double> x, bool twice = false);

/// For tests: the near-null space the amg solver gives PCGAMG for the matrix of `cells` in
/// `frames` (set_near_null_space), each mode as a vector of d entries per node (zero at nodes
/// without unknowns).
std::vector<std::vector<double>> assembled_near_null_space(const ElementList& cells, const NodalFrames& frames);

}  // namespace hotmesh::deform::detail
