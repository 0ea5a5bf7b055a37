// hotmesh deform (internal): the Newton-Raphson cycle of the paper (eqs. 7-8) as a solver of its
// own, as MFEM's NewtonSolver is: it takes any operator that gives the residual and the linear
// system of a step (NewtonOperator) and any linear solver (LinearSolver,
// storage/linear_solver.hpp), and iterates
//     R(n) = K(n) u(n) - f,      K(n) p = -R(n),      u(n+1) = u(n) + p,
// until ||D^-1 R|| <= tol ||D^-1 R0|| (the Newton norm, scaled_residual_norm), each inner solve
// to the tolerance of inexact Newton (Forcing). The mesh motion's operator is the system of one
// increment (increment_system.hpp); the increment scheduler (motion.hpp) runs the solver once
// per attempt at an increment.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/deform/solver_options.hpp"
#include "storage/linear_solver.hpp"

namespace hotmesh::deform::detail {

/// An increment's displacements before the predictor (predictor.cpp) and, filled by
/// NewtonOperator::residual, their residual K(n) u_start with the stiffness of the predicted
/// first step, folded and projected as R is.
struct ReferenceResidual {
  std::span<const double> u_start;
  std::span<double> r_start;
};

/// What the Newton solver iterates on (as MFEM's Operator with its gradient): the residual at
/// u, the linear system of the step from there, and what u must satisfy after each step.
class NewtonOperator {
 public:
  virtual ~NewtonOperator() = default;
  /// The unknowns: dofs_per_node() a node.
  virtual std::size_t size() const = 0;
  virtual std::size_t dofs_per_node() const = 0;
  /// R(u) into `r` and each node's stiffness D, the weight of the Newton norm, into
  /// `node_stiffness`; with a `reference`, also the residual of reference->u_start with the
  /// same K. Without `matrix_wanted` a linear solver that assembles its own matrix may leave it
  /// for the solve (ElementAssembler). Returns the system K(u) p = -R(u) of the step (its
  /// constraints and node stiffness), valid until the next call.
  virtual ConstrainedSystem residual(std::span<const double> u, std::span<double> r, std::span<double> node_stiffness,
                                     const ReferenceResidual* reference, bool matrix_wanted) = 0;
  /// The largest |p . n| of a step p along the directions nodes may not move in (eq. 19).
  virtual double normal_slip(std::span<const double> p) const = 0;
  /// After u += p: puts u back where the constraints want it; returns the largest move that
  /// took (NewtonStep::max_projection).
  virtual double restore(std::span<double> u) = 0;
};

/// How a Newton solve ended.
enum class NewtonStop { converged, diverged, stalled, linear_breakdown };

struct NewtonResult {
  NewtonStop stop = NewtonStop::stalled;
  std::vector<NewtonStep> steps;    ///< one per residual (IncrementRecord::newton)
  double residual_reduction = 0.0;  ///< the last ||D^-1 R|| / ||D^-1 R0||
  double max_normal_slip = 0.0;     ///< the largest NewtonOperator::normal_slip of its steps
  std::string failure;              ///< why it stopped, unless it converged
};

class NewtonSolver {
 public:
  /// After each step n = 1, 2, ...: the result so far.
  using StepObserver = std::function<void(const NewtonResult& so_far, int n)>;

  /// `options`: newton_tolerance, max_newton_iterations and the forcing of the inner solves.
  /// `round_off`: a residual ||D^-1 R|| this small has converged whatever ||D^-1 R0||.
  /// Adds the solves' times to `timings`.
  NewtonSolver(const SolverOptions& options, LinearSolver& linear, MotionTimings& timings, double round_off)
      : options_(options), linear_(linear), timings_(timings), round_off_(round_off) {}

  /// Solves R(u) = 0 for u, from u. With `unpredicted` (u before a prediction; else empty)
  /// the tolerance is relative to its residual with the first step's K.
  NewtonResult solve(NewtonOperator& op, std::span<double> u, std::vector<double> unpredicted,
                     const StepObserver& observe);

  /// The residual R and node stiffness D of the last step (where a failed solve stood).
  std::span<const double> residual() const { return r_; }
  std::span<const double> node_stiffness() const { return node_stiffness_; }

 private:
  bool stops(NewtonResult& result, int it, double residual, double r0) const;

  SolverOptions options_;
  LinearSolver& linear_;
  MotionTimings& timings_;
  double round_off_;
  std::vector<double> r_;
  std::vector<double> node_stiffness_;
};

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
