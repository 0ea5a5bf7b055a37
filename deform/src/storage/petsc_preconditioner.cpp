// hotmesh deform: the preconditioners of the assembled solver's CG (petsc_preconditioner.hpp):
// PETSc's algebraic multigrid (GAMG or hypre's BoomerAMG) with hotmesh's defaults, or
// Cholesky (CHOLMOD, MUMPS) or incomplete Cholesky factors of K~.
#include "storage/petsc_preconditioner.hpp"

#include <string>

#include "storage/frame_matrix.hpp"

namespace hotmesh::deform::detail {
namespace {

/// `icc`: the levels of fill of the incomplete factors, by the mesh's dimension. The sliding
/// ramp refined twice took 1 170, 818 and 618 CG iterations with 1, 2 and 3 levels, in 3.3, 2.8
/// and 2.9 s. A hex's node couples to 26 others, a quad's to 8, and the fill grows with them:
/// the 18 000-cell stator-well sector took 10, 20 and 51 s with 0, 1 and 2 levels (its
/// factorizations 2, 14 and 43 s of them).
constexpr PetscInt icc_levels(int dimension) { return dimension == 2 ? 2 : 0; }

bool option_given(const char* name) {
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
  return set == PETSC_TRUE;
}

/// Whether the user chose GAMG's smoother in PETSC_OPTIONS: asked once per process, before
/// the first solver sets hotmesh's defaults into the same options database.
bool user_chose_smoother() {
  static const bool chosen = option_given("-hotmesh_mg_levels_ksp_type") || option_given("-hotmesh_mg_levels_pc_type");
  return chosen;
}

/// Sets the option unless the user gave it (PETSC_OPTIONS); a null value sets a flag.
void default_option(const char* name, const char* value) {
  if (!option_given(name)) check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
}

}  // namespace

Preconditioner preconditioner_of(LinearSolverKind linear) {
  switch (linear) {
    case LinearSolverKind::direct: return Preconditioner::cholesky;
    case LinearSolverKind::icc: return Preconditioner::incomplete_cholesky;
    default: return Preconditioner::multigrid;
  }
}

MultigridDefaults set_multigrid_defaults(AmgPackage amg) {
  MultigridDefaults defaults;
  if (amg == AmgPackage::gamg) {
    // Gauss-Seidel smoothing on every level: in 3D one forward sweep before the coarse-grid
    // correction and one backward sweep after it, which keeps the V-cycle symmetric for CG
    // (2D: AssembledSolver::create()).
    // A symmetric sweep on both sides (PETSc's SOR default) took as many CG iterations and
    // twice the smoothing time. With several ranks each sweeps its own rows (hybrid
    // Gauss-Seidel), and the one-sided sweeps can make the V-cycle indefinite where ranks
    // couple strongly (a hybrid sector on two ranks): CG then breaks down, and the solver
    // goes over to symmetric sweeps for the rest of the run (AssembledSolver::solve()). The default
    // Chebyshev/Jacobi smoother made the preconditioner indefinite on the ramp: its
    // eigenvalue estimates miss the top of the spectrum of these boundary-layer matrices.
    const bool smoother_given = user_chose_smoother();
    defaults.one_sided_sweeps = !smoother_given;
    defaults.smoother_given = smoother_given;
    default_option("-hotmesh_mg_levels_ksp_type", "richardson");
    default_option("-hotmesh_mg_levels_pc_type", "sor");
    if (!smoother_given) {
      default_option("-hotmesh_mg_levels_pc_sor_local_forward", nullptr);
      default_option("-hotmesh_pc_mg_distinct_smoothup", nullptr);
      default_option("-hotmesh_mg_levels_up_ksp_type", "richardson");
      default_option("-hotmesh_mg_levels_up_pc_type", "sor");
      default_option("-hotmesh_mg_levels_up_pc_sor_local_backward", nullptr);
    }
  } else {
    // BoomerAMG for elasticity: the d components of a node coarsened together.
    default_option("-hotmesh_pc_hypre_boomeramg_nodal_coarsen", "6");
    default_option("-hotmesh_pc_hypre_boomeramg_strong_threshold", "0.5");
  }
  return defaults;
}

PC create_preconditioner(Mat a, Preconditioner preconditioner, AmgPackage amg, int ranks, int dimension) {
  PC pc = nullptr;
  check(PCCreate(PetscObjectComm(reinterpret_cast<PetscObject>(a)), &pc), "PCCreate");
  check(PCSetOptionsPrefix(pc, "hotmesh_"), "PCSetOptionsPrefix");
  if (preconditioner == Preconditioner::cholesky) {
    check(PCSetType(pc, PCCHOLESKY), "PCSetType");
    check(PCFactorSetMatSolverType(pc, ranks > 1 ? MATSOLVERMUMPS : MATSOLVERCHOLMOD), "PCFactorSetMatSolverType");
  } else if (preconditioner == Preconditioner::incomplete_cholesky && ranks > 1) {
    check(PCSetType(pc, PCBJACOBI), "PCSetType");  // one block per rank, each ICC in its rows' order
    default_option("-hotmesh_sub_pc_type", "icc");
    default_option("-hotmesh_sub_pc_factor_levels", std::to_string(icc_levels(dimension)).c_str());
    default_option("-hotmesh_sub_pc_factor_mat_ordering_type", MATORDERINGNATURAL);
  } else if (preconditioner == Preconditioner::incomplete_cholesky) {
    check(PCSetType(pc, PCICC), "PCSetType");
    check(PCFactorSetLevels(pc, icc_levels(dimension)), "PCFactorSetLevels");
    check(PCFactorSetMatOrderingType(pc, MATORDERINGNATURAL), "PCFactorSetMatOrderingType");
  } else if (amg == AmgPackage::gamg) {
    check(PCSetType(pc, PCGAMG), "PCSetType");
    check(PCGAMGSetType(pc, PCGAMGAGG), "PCGAMGSetType");
    check(PCGAMGSetNSmooths(pc, 1), "PCGAMGSetNSmooths");  // smoothed aggregation
    PetscReal threshold[] = {0.02};
    check(PCGAMGSetThreshold(pc, threshold, 1), "PCGAMGSetThreshold");
  } else {
    check(PCSetType(pc, PCHYPRE), "PCSetType");
    check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
  }
  check(PCSetFromOptions(pc), "PCSetFromOptions");
  return pc;
}

bool factorize_here(PC pc) {
  check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
  const PetscErrorCode code = PCSetUp(pc);
  check(PetscPopErrorHandler(), "PetscPopErrorHandler");
  if (code != 0 && code != PETSC_ERR_MAT_CH_ZRPVT && code != PETSC_ERR_MAT_LU_ZRPVT) check(code, "PCSetUp");
  PCFailedReason reason = PC_NOERROR;
  if (code == 0) check(PCGetFailedReason(pc, &reason), "PCGetFailedReason");
  return code == 0 && reason == PC_NOERROR;
}

void make_sweeps_symmetric(PC pc) {
  PetscInt levels = 0;
  check(PCMGGetLevels(pc, &levels), "PCMGGetLevels");
  for (PetscInt level = 1; level < levels; ++level) {  // level 0 is the coarse solve
    for (const bool up : {false, true}) {
      KSP smoother = nullptr;
      check(up ? PCMGGetSmootherUp(pc, level, &smoother) : PCMGGetSmootherDown(pc, level, &smoother), "PCMGGetSmoother");
      PC sweep = nullptr;
      check(KSPGetPC(smoother, &sweep), "KSPGetPC");
      PetscBool sor = PETSC_FALSE;
      check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(sweep), PCSOR, &sor), "PetscObjectTypeCompare");
      if (sor) check(PCSORSetSymmetric(sweep, SOR_LOCAL_SYMMETRIC_SWEEP), "PCSORSetSymmetric");
    }
  }
}

}  // namespace hotmesh::deform::detail
