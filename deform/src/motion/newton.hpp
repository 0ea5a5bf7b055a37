// hotmesh deform (internal): the Newton-Raphson loop's own parts (eqs. 7-8), which move_mesh.cpp
// runs: the residual R(n) = K(n) u(n) - f of each step, from the element matrices of K(n) at
// the current geometry, and the tolerance of each inner linear solve (inexact Newton).
#pragma once

#include <cstddef>
#include <span>

#include "hotmesh/deform/solver_options.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"
#include "storage/linear_solver.hpp"

namespace hotmesh::deform::detail {

/// An increment's displacements before the predictor (move_mesh.cpp) and, filled by
/// newton_residual, their residual K(n) u_start with the stiffness of the predicted first step,
/// folded and projected as R is.
struct ReferenceResidual {
  std::span<const double> u_start;
  std::span<double> r_start;
};

/// The residual of a Newton step, R(n) = P T^T K(n) u(n) of eq. (7), at s.points: folded onto
/// periodic masters, only its tangential part F_t at sliding nodes (eq. 17); and each node's
/// stiffness D, which scales its norm (scaled_residual_norm). K(n) comes from the node blocks
/// of `k`, updated here at s.points (R = K u by its product); without them from the element
/// pass of the solver's `assembler`, which computes each K_e once for its matrix and for R,
/// each rank its cells, summed over `ranks`. Adds the element work to timings.assembly.
/// With a `reference`, also its residual from the same K(n). Without `matrix_wanted` the
/// assembler computes the residual alone (ElementAssembler).
void newton_residual(const ConstrainedSystem& s, StiffnessOperator* k, ElementAssembler* assembler,
                     const parallel::RankExchange& ranks, std::span<const double> u, std::span<double> r,
                     std::span<double> node_stiffness, MotionTimings& timings, const ReferenceResidual* reference = nullptr,
                     bool matrix_wanted = true);

/// Inexact Newton: the tolerance of each inner solve. `fixed` gives pcg_tolerance every time.
/// `eisenstat_walker` is Eisenstat and Walker's choice 2 (SIAM J. Sci. Comput. 17, 1996),
///     eta_n = gamma (||R_n|| / ||R_n-1||)^alpha,   gamma = 0.9, alpha = 2,
/// safeguarded by gamma eta_n-1^alpha when that exceeds 0.1, capped at eta_max = 0.1, never
/// below pcg_tolerance, and not tighter than the Newton tolerance needs:
/// eta_n >= 0.5 newton_tolerance ||R_0|| / ||R_n||. The first solve of an increment uses
/// pcg_tolerance, and so does the solve after any step that failed the inexact Newton
/// condition of sufficient decrease (Eisenstat and Walker, SIAM J. Optim. 4, 1994),
///     ||R_n|| <= (1 - t (1 - eta_n-1)) ||R_n-1||,   t = 1e-4:
/// choice 2 alone keeps eta near its cap while Newton stalls, and the loose solves then make
/// no progress (the 2.7-million-cell stator well, the history of docs/performance.md).
/// The norm the solve stops on: the plain ||r|| costs a fraction of the CG iterations of
/// ||D^-1 r||, but the stiffest cells dominate it and a solve can meet it leaving ||D^-1 R|| as
/// it was. So the first solve of an increment, which sets the course of the increment, and the
/// solve after a step that failed the condition of sufficient decrease (with either forcing)
/// stop on ||D^-1 r||; the others on ||r|| (docs/method.md, inexact Newton).
class Forcing {
 public:
  explicit Forcing(const SolverOptions& options) : options_(options) {}
  /// The target of the solve that follows the residual ||R_n|| (n = 0, 1, ... in an increment).
  LinearTarget next(int n, double residual, double initial);

 private:
  SolverOptions options_;
  double previous_residual_ = 0.0;
  double previous_eta_ = 0.0;
};

}  // namespace hotmesh::deform::detail
