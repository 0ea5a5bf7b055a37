// hotmesh deform: preconditioned conjugate gradients (the paper's section 3), as a free
// function over operators. Non-convergence is a result, not an exception.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "hotmesh/deform/linear_algebra.hpp"

namespace hotmesh::deform {

struct PcgOptions {
  double relative_tolerance = 1e-3;  ///< stop at ||r|| <= tol * ||r0||, in the norm below
  int max_iterations = 5000;
  bool record_history = true;
  /// Applied to the initial residual and to every preconditioned residual; the sliding and
  /// slip constraints use it to keep iterates in their subspace against round-off.
  std::function<void(std::span<double>)> project;
  /// The norm of the residual that the stopping test and the history measure; empty: the
  /// Euclidean norm. The Newton loop passes its own (scaled_residual_norm), so that a solve
  /// to tolerance eta reduces the residual Newton measures by eta.
  std::function<double(std::span<const double>)> norm;
  /// Sums a value over the processes that each hold some rows of the system: the dot products
  /// of the iteration and the Euclidean norm. Empty: one process holds every row. A `norm`
  /// given above sums over the processes itself.
  std::function<double(double)> sum;
};

struct PcgResult {
  int iterations = 0;
  bool converged = false;
  bool breakdown = false;            ///< d^T A d <= 0 or r^T z <= 0: A or M not SPD on the subspace
  double initial_residual = 0.0;     ///< ||r0|| (in PcgOptions::norm)
  double final_residual = 0.0;       ///< ||r|| at exit (recursively updated)
  std::vector<double> history;       ///< ||r_k|| / ||r0||, k = 0..iterations
};

/// Solves A x = b from the initial guess in x, with M approximating A^-1.
PcgResult pcg(const LinearOperator& a, const LinearOperator& m, std::span<const double> b, std::span<double> x,
              const PcgOptions& options = {});

}  // namespace hotmesh::deform
