// hotmesh deform (internal): the preconditioners of the assembled solver's CG (petsc_solver.cpp):
// PETSc's algebraic multigrid, or Cholesky or incomplete Cholesky factors of K~, made on the
// matrix of frame_matrix.hpp. PETSc types: include only where PETSc is used.
#pragma once

#include <petscksp.h>

#include "hotmesh/deform/solver_options.hpp"

namespace hotmesh::deform::detail {

/// `icc` goes over to `direct` after a solve not converged in this many CG iterations: 3 to 6
/// a solve on the 2D samples, 30 on average on the sliding ramp refined four times (36 480
/// cells, where a factorization costs about 100 ICC iterations); 100 to 800 where the
/// numbering does not follow the boundary layer (the ramp's hybrid mesh in reverse
/// Cuthill-McKee order).
constexpr int kIccMostIterations = 100;

/// What preconditions the assembled solver's CG.
enum class Preconditioner { multigrid, cholesky, incomplete_cholesky };

Preconditioner preconditioner_of(LinearSolverKind linear);

/// What set_multigrid_defaults found: whether GAMG smooths with one-sided sweeps (hotmesh's
/// default) and whether the user chose the smoother in PETSC_OPTIONS.
struct MultigridDefaults {
  bool one_sided_sweeps = false;
  bool smoother_given = false;
};
/// hotmesh's defaults for the multigrid of `amg` in PETSc's options database (prefix hotmesh_),
/// each unless the user gave it in PETSC_OPTIONS.
MultigridDefaults set_multigrid_defaults(AmgPackage amg);

/// The multigrid preconditioner or the Cholesky factorization of `a`, options from PETSC_OPTIONS
/// (prefix hotmesh_), on the communicator of `a`, for a job of `ranks` processes on a mesh of
/// `dimension`.
PC create_preconditioner(Mat a, Preconditioner preconditioner, AmgPackage amg, int ranks, int dimension);

/// PCSetUp of the Cholesky factorization on this rank; false if it failed (a pivot that is not
/// positive: K~ is not positive definite). CHOLMOD reports that as error
/// PETSC_ERR_MAT_CH_ZRPVT in 3D (without printing PETSc's traceback here) and as the PC's
/// failed reason in 2D, MUMPS as the failed reason; other errors throw as ever.
bool factorize_here(PC pc);

/// A symmetric Gauss-Seidel sweep (forward and backward, each rank on its rows) before and
/// after the coarse-grid correction on every level of the built hierarchy, as PETSc's SOR
/// does by default.
void make_sweeps_symmetric(PC pc);

}  // namespace hotmesh::deform::detail
