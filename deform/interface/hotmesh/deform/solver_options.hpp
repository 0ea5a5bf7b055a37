// hotmesh deform: options of the elastic mesh-motion solve, with their defaults. The case
// file (io) fills them; the solver reads them. One struct per concern, no global settings.
#pragma once

#include <cstddef>
#include <string_view>

#include "hotmesh/core/enum_names.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::deform {

/// How each Newton step's linear system K(n) p = -R(n) is solved (docs/method.md).
enum class LinearSolverKind {
  automatic,   ///< the fastest for the case, by choose_linear_solver()
  jacobi_pcg,  ///< the paper's PCG with nodal Jacobi (section 3), projected for sliding (eq. 16), K in node blocks
  amg,         ///< assembled in nodal frames (PETSc), CG preconditioned by algebraic multigrid
  direct,      ///< assembled in nodal frames (PETSc), sparse Cholesky of every Newton step's matrix
  icc,         ///< assembled in nodal frames (PETSc), CG preconditioned by its incomplete Cholesky factors
};

/// The algebraic multigrid of the `amg` solver.
enum class AmgPackage {
  gamg,   ///< PETSc's smoothed-aggregation PCGAMG with the rigid-body near-null space
  hypre,  ///< hypre's BoomerAMG (classical AMG, nodal coarsening)
};

/// What the amg solver keeps of a Newton step's multigrid for later steps. K changes little
/// between them; all but `adaptive` build anew at the first step of each increment.
enum class AmgReuse {
  automatic,       ///< gamg: `adaptive` from kAdaptiveReuseCells cells, `preconditioner` below; hypre: `none`
  adaptive,        ///< the whole hierarchy, across increments too, rebuilt when CG slows (kAmgSlowdown)
  preconditioner,  ///< the whole hierarchy, operators included (KSPSetReusePreconditioner), within an increment
  interpolation,   ///< gamg's aggregates and prolongators within an increment; the Galerkin operators are recomputed
  none,            ///< rebuilt every Newton step
};

/// `amg_reuse: adaptive` rebuilds the hierarchy once the first solve of an increment takes more
/// than this many times the CG iterations of the first solve with a fresh hierarchy (those
/// solves all stop at pcg_tolerance in the Newton norm, so their counts compare).
inline constexpr double kAmgSlowdown = 1.5;

/// `amg_reuse: auto` with gamg keeps hierarchies across increments (`adaptive`) from this many
/// cells on, where a set-up costs seconds (48 s of a 263 s run of the 200 000-cell sector on two
/// ranks, 16 set-ups); below, each increment builds its own (`preconditioner`), so that a resumed
/// run repeats the uninterrupted one to the bit.
inline constexpr std::size_t kAdaptiveReuseCells = 100000;

/// The tolerance of each inner linear solve.
enum class ForcingTerm {
  fixed,            ///< pcg_tolerance every time
  eisenstat_walker, ///< adaptive (inexact Newton), from the observed Newton rate, never below pcg_tolerance
};

/// The names the case file and report.json use.
inline constexpr EnumNames<LinearSolverKind, 5> kLinearSolverNames{{{{LinearSolverKind::automatic, "auto"},
                                                                  {LinearSolverKind::jacobi_pcg, "jacobi-pcg"},
                                                                  {LinearSolverKind::amg, "amg"},
                                                                  {LinearSolverKind::direct, "direct"},
                                                                  {LinearSolverKind::icc, "icc"}}}};
inline constexpr EnumNames<AmgPackage, 2> kAmgPackageNames{{{{AmgPackage::gamg, "gamg"}, {AmgPackage::hypre, "hypre"}}}};
inline constexpr EnumNames<AmgReuse, 5> kAmgReuseNames{{{{AmgReuse::automatic, "auto"},
                                                        {AmgReuse::adaptive, "adaptive"},
                                                        {AmgReuse::preconditioner, "preconditioner"},
                                                        {AmgReuse::interpolation, "interpolation"},
                                                        {AmgReuse::none, "none"}}}};
inline constexpr EnumNames<ForcingTerm, 2> kForcingTermNames{
    {{{ForcingTerm::fixed, "fixed"}, {ForcingTerm::eisenstat_walker, "eisenstat-walker"}}}};
constexpr std::string_view to_string(LinearSolverKind k) { return kLinearSolverNames.name(k); }
constexpr std::string_view to_string(AmgPackage p) { return kAmgPackageNames.name(p); }
constexpr std::string_view to_string(ForcingTerm f) { return kForcingTermNames.name(f); }

/// The linear solver `linear: auto` runs, and why, from what docs/performance.md measured on
/// whole motions ("AMG against Jacobi-PCG", "Stator-well solve at growing sizes"):
///  - amg with several processes: jacobi-pcg runs in one;
///  - icc for a 2D mesh of at most kIccCells cells, sliding or not: its factors, in the mesh's
///    node order, hold the strong coupling across the thin cells of a boundary layer that
///    nodal Jacobi misses (3 to 6 CG iterations a Newton step on the 2D samples against 90 to
///    400 for Jacobi-PCG). The sliding ramp took 0.38 s against direct's 1.40 s, amg's 1.88 s
///    and Jacobi-PCG's 2.46 s; refined twice (9 120 cells) 2.5 s against 13.9 s (direct) and
///    19.9 s (amg); refined four times (36 480 cells) 35 s against direct's 156 s. Without
///    sliding, the ramp took 0.30 s against Jacobi-PCG's 0.54 s; the shear, without a boundary
///    layer, 0.06 s against 0.04 s. Beyond the sizes measured: amg with a sliding wall (the
///    factorization of `direct` grows as N^1.5 or faster), jacobi-pcg without;
///  - in 3D, jacobi-pcg up to kJacobiPcgCells cells, amg beyond: on the sliding stator-well
///    sector Jacobi-PCG was faster at 18 000, 50 000 and 200 000 cells (336 s against 388 s
///    there, with 40 % less memory), but its time grows faster (N^1.15 against N^1.02 from
///    50 000 to 200 000 cells): the two cross near 600 000 cells. At 18 000 cells direct took
///    3 to 8 times Jacobi-PCG's time (the factors of a 3D mesh grow as N^4/3), icc 1.7 to 1.9
///    times.
inline constexpr std::size_t kJacobiPcgCells = 500000;
inline constexpr std::size_t kIccCells = 40000;
struct LinearSolverChoice {
  LinearSolverKind kind = LinearSolverKind::jacobi_pcg;
  std::string_view reason;
};
constexpr LinearSolverChoice choose_linear_solver(int dimension, std::size_t cells, bool sliding, int processes) {
  if (processes > 1) return {LinearSolverKind::amg, "several processes"};
  if (dimension == 2) {
    if (cells <= kIccCells) return {LinearSolverKind::icc, "a 2D mesh of at most 40 000 cells"};
    return sliding ? LinearSolverChoice{LinearSolverKind::amg, "a 2D mesh with a sliding wall, more than 40 000 cells"}
                   : LinearSolverChoice{LinearSolverKind::jacobi_pcg, "a 2D mesh without sliding walls, more than 40 000 cells"};
  }
  return cells > kJacobiPcgCells ? LinearSolverChoice{LinearSolverKind::amg, "a 3D mesh of more than 500 000 cells"}
                                 : LinearSolverChoice{LinearSolverKind::jacobi_pcg, "a 3D mesh of at most 500 000 cells"};
}

/// Limits on the cells that every accepted increment keeps (the case file's `quality:`; 0: a
/// limit not set). An increment whose mesh breaks one is retried in halves, as one that
/// inverts a cell; a cell whose scaled Jacobian is at most 0 is always refused.
struct QualityLimits {
  double min_scaled_jacobian = 0.0;
  double max_non_orthogonality = 0.0;  ///< degrees, as mesh::solver_quality measures it
  double max_skewness = 0.0;
  /// What a 2D mesh's cells stand for in the flow solver (io::LoadedMesh::layer), for the
  /// non-orthogonality and skewness.
  mesh::Extrusion layer;
  /// The quality step after each increment: the nodes around the faces a flow solver finds
  /// worst moved to lower their non-orthogonality and skewness (deform/src/motion/quality_step.hpp).
  bool smoothing = false;
  bool solver_measures() const { return max_non_orthogonality > 0.0 || max_skewness > 0.0; }
};

/// Increments, Newton-Raphson (eqs. 7-8) and the inner PCG solves (section 3).
struct SolverOptions {
  int increments = 16;              ///< N: the prescribed motion is applied in N steps
  double newton_tolerance = 1e-4;   ///< stop at ||D^-1 R|| <= tol * ||D^-1 R0|| (the paper's value, there for ||R||)
  int max_newton_iterations = 30;
  double pcg_tolerance = 1e-3;      ///< relative residual of each inner linear solve
  int max_pcg_iterations = 5000;
  /// An increment that inverts a cell or whose Newton iteration fails is retried as two
  /// half increments, recursively, at most this many times in a row (0: never).
  int max_increment_splits = 4;
  /// jacobi-pcg for callers of the library, as the paper solves; a case file's default is
  /// `auto` (io::Case), resolved by move_mesh through choose_linear_solver().
  LinearSolverKind linear = LinearSolverKind::jacobi_pcg;
  AmgPackage amg = AmgPackage::gamg;
  AmgReuse amg_reuse = AmgReuse::automatic;
  ForcingTerm forcing = ForcingTerm::fixed;
  /// Start each increment after the first along the secant of the last accepted step, carried
  /// on to its stage, instead of from the boundary's move alone (deform/src/motion/predictor.cpp,
  /// docs/method.md "Predictor"). Off for callers of the library, as the paper starts; a case
  /// file's default is on (io::Case).
  bool predictor = false;
  QualityLimits quality;
};

/// How the pseudo-material's Lamé parameters vary from element to element.
enum class StiffnessLaw {
  shape_volume,    ///< eq. (35): 2G = alpha_s |phi_s|, lambda + 2G/3 = alpha_v |phi_v| (the paper)
  uniform,         ///< 2G = alpha_s, lambda + 2G/3 = alpha_v everywhere
  inverse_volume,  ///< both moduli scaled by V_median / V_e (stiff small cells)
};
/// The names the case file uses.
inline constexpr EnumNames<StiffnessLaw, 3> kStiffnessLawNames{{{{StiffnessLaw::shape_volume, "shape_volume"},
                                                                {StiffnessLaw::uniform, "uniform"},
                                                                {StiffnessLaw::inverse_volume, "inverse_volume"}}}};

/// Pseudo-material of the elastic medium (the paper's appendix).
struct MaterialOptions {
  StiffnessLaw law = StiffnessLaw::shape_volume;
  double alpha_s = 1.0;   ///< weight of shape (deviatoric) stiffness
  double alpha_v = 0.01;  ///< weight of volume stiffness; the paper keeps it 1-3 orders lower
  /// Integrate K_e without the Jacobian determinant (Stein et al.), which makes small
  /// elements stiffer. The paper does; standard finite elements (and the patch test) don't.
  bool drop_jacobian = true;
  /// p > 0: both moduli of a cell also times (D / d)^p, d the distance from its centre to the
  /// nearest node of a prescribed or sliding wall and D the mesh's bounding diagonal (d at
  /// least 1e-6 D), so that the cells near the walls that move follow them nearly rigidly and
  /// the far ones take the deformation (beyond the paper: OpenFOAM's inverseDistance
  /// diffusivity; docs/method.md). 0: the paper's eq. (35) alone.
  double wall_distance_exponent = 0.0;
};

}  // namespace hotmesh::deform
