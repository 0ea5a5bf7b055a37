// hotmesh deform: the Newton-Raphson cycle (eqs. 7-8, newton.hpp), and the forcing term of
// inexact Newton.
#include "motion/newton.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hotmesh/deform/linear_algebra.hpp"

namespace hotmesh::deform::detail {
namespace {

/// A Newton residual this many times the initial one means the cycle has blown up: better to
/// split the increment at once than to iterate on. Large transients are normal: the stiffness
/// of the thinnest cells scales with 1/h^2 and follows the geometry, so the ramp case passes
/// through residuals 1e5 times the initial one on its way to converging.
constexpr double kDivergence = 1e10;

}  // namespace

NewtonResult NewtonSolver::solve(NewtonOperator& op, std::span<double> u, std::vector<double> unpredicted,
                                 const StepObserver& observe) {
  const std::size_t dofs = op.size(), d = op.dofs_per_node();
  std::vector<double> reference_residual(unpredicted.empty() ? 0 : dofs);
  r_.assign(dofs, 0.0);
  node_stiffness_.assign(dofs / d, 0.0);
  NewtonResult result;
  double r0 = 0.0, previous = 0.0;
  // Whether this step's element pass assembles the solver's matrix too (amg, direct, icc): not when
  // the residual will likely end the loop (the solve assembles it if not).
  bool matrix_wanted = true;
  linear_.begin_increment();
  Forcing forcing(options_);
  for (int it = 0;; ++it) {
    // K(n) at the current geometry (eq. 8) and R(n) = K(n) u(n) - f (eq. 7; f is K's action on
    // the boundary motion), with only its tangential part F_t at sliding nodes (eq. 17).
    const bool referenced = it == 0 && !unpredicted.empty();
    const ReferenceResidual reference{unpredicted, reference_residual};
    const ConstrainedSystem system =
        op.residual(u, r_, node_stiffness_, referenced ? &reference : nullptr, matrix_wanted);
    const double residual = scaled_residual_norm(r_, node_stiffness_, d);
    // The tolerance is relative to the residual of the increment's start without the
    // predictor, so that a good prediction does not tighten it.
    if (it == 0) {
      r0 = referenced ? scaled_residual_norm(reference_residual, node_stiffness_, d) : residual;
      // Needed no more: given back before the solves (two vectors the mesh's size).
      std::vector<double>().swap(unpredicted);
      std::vector<double>().swap(reference_residual);
    }
    result.steps.push_back({residual, 0, true, 0.0});
    result.residual_reduction = r0 > 0.0 ? residual / r0 : 0.0;
    if (it > 0 && observe) observe(result, it);
    if (stops(result, it, residual, r0)) break;
    // K(n) p = -R(n) on the free degrees of freedom, from p = 0 (eq. 8, section 3); at
    // sliding nodes the projected operator solves eq. (16) and keeps p . n = 0 (eq. 19).
    for (double& value : r_) value = -value;  // the right-hand side, in place: R is not needed again
    // Its tolerance, and whether it stops on this loop's ||D^-1 r|| or the cheaper ||r||: Forcing.
    const auto target = forcing.next(it, residual, r0);
    const std::span<double> p = r_;  // solved in place: p over -R (one vector the mesh's size less)
    const auto solved = linear_.solve(system, r_, p, target, timings_);
    // The next residual, expected from this solve's tolerance and the last step's reduction.
    const double reduction = std::max(target.tolerance, it > 0 && previous > 0.0 ? residual / previous : 0.0);
    matrix_wanted = reduction * residual > options_.newton_tolerance * r0;
    previous = residual;
    auto& step = result.steps.back();
    step.pcg_iterations = solved.iterations;
    step.pcg_converged = solved.converged;
    step.pcg_reduction = solved.reduction;
    step.linear_tolerance = target.tolerance;
    step.linear_newton_norm = target.newton_norm;
    if (solved.breakdown) {
      result.failure = "the linear solver broke down (the stiffness is not positive definite on the free nodes)";
      result.stop = NewtonStop::linear_breakdown;
      break;
    }
    result.max_normal_slip = std::max(result.max_normal_slip, op.normal_slip(p));
    axpy(1.0, p, u);
    // Every sliding node back onto the partial boundary c_b, with its new normal (4.2):
    // IncrementSystem::restore.
    step.max_projection = op.restore(u);
  }
  return result;
}

/// Whether the cycle ends at the residual of step `it`: diverged, converged, or out of
/// iterations.
bool NewtonSolver::stops(NewtonResult& result, int it, double residual, double r0) const {
  if (!std::isfinite(residual) || residual > kDivergence * r0) {
    result.failure = fmt::format("the Newton-Raphson cycle diverged (residual {:.3g} times the initial one)",
                                 residual / r0);
    result.stop = NewtonStop::diverged;
    return true;
  }
  if (residual <= options_.newton_tolerance * r0 || residual <= round_off_) {
    result.stop = NewtonStop::converged;
    return true;
  }
  if (it == options_.max_newton_iterations) {
    result.failure = fmt::format("the Newton-Raphson cycle did not converge in {} iterations (residual reduced "
                                 "to {:.3g}, tolerance {:.3g})",
                                 options_.max_newton_iterations, result.residual_reduction, options_.newton_tolerance);
    result.stop = NewtonStop::stalled;
    return true;
  }
  return false;
}

LinearTarget Forcing::next(int n, double residual, double initial) {
  const double floor = options_.pcg_tolerance;
  double eta = floor;
  constexpr double kSufficientDecrease = 1e-4;  // t
  const bool decreased =
      n == 0 || residual <= (1.0 - kSufficientDecrease * (1.0 - previous_eta_)) * previous_residual_;
  constexpr double kGamma = 0.9, kAlpha = 2.0, kMax = 0.1;
  if (options_.forcing == ForcingTerm::eisenstat_walker && n == 0 && residual > 0.0) {
    // A predicted start already close to the solution: reach the Newton tolerance, no further.
    eta = std::clamp(0.5 * options_.newton_tolerance * initial / residual, floor, std::max(kMax, floor));
  }
  if (options_.forcing == ForcingTerm::eisenstat_walker && n > 0 && previous_residual_ > 0.0 && decreased) {
    const double ratio = residual / previous_residual_;
    eta = kGamma * std::pow(ratio, kAlpha);
    const double safeguard = kGamma * std::pow(previous_eta_, kAlpha);
    if (safeguard > 0.1) eta = std::max(eta, safeguard);
    eta = std::min(eta, kMax);
    // Solving beyond what the Newton tolerance asks of this step is wasted.
    if (residual > 0.0) eta = std::max(eta, 0.5 * options_.newton_tolerance * initial / residual);
    eta = std::clamp(eta, floor, std::max(kMax, floor));
  }
  previous_residual_ = residual;
  previous_eta_ = eta;
  return {eta, n == 0 || !decreased};
}

}  // namespace hotmesh::deform::detail
