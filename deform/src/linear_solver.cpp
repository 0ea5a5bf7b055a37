// hotmesh deform: the choice of linear solver, and the forcing term of inexact Newton.
#include "linear_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "petsc_solver.hpp"

namespace hotmesh::deform::detail {

std::unique_ptr<LinearSolver> make_jacobi_pcg_solver(const SolverOptions& options);  // jacobi_pcg.cpp

std::unique_ptr<LinearSolver> make_linear_solver(const SolverOptions& options, const parallel::RankExchange& ranks) {
  switch (options.linear) {
    case LinearSolverKind::jacobi_pcg: return make_jacobi_pcg_solver(options);
    case LinearSolverKind::amg: return make_amg_solver(options, ranks);
  }
  return make_jacobi_pcg_solver(options);
}

bool stores_element_matrices(const SolverOptions& options) { return options.linear != LinearSolverKind::amg; }

void add_node_stiffness(std::span<const NodeId> nodes, std::span<const double> ke, std::size_t d,
                        std::span<double> node_stiffness) {
  const std::size_t n = nodes.size() * d;
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    double trace = 0.0;
    for (std::size_t i = 0; i < d; ++i) trace += ke[(a * d + i) * n + a * d + i];
    node_stiffness[static_cast<std::size_t>(nodes[a])] += trace / static_cast<double>(d);
  }
}

double scaled_residual_norm(std::span<const double> r, std::span<const double> node_stiffness, std::size_t d) {
  double sum = 0.0;
  for (std::size_t node = 0; node < node_stiffness.size(); ++node) {
    if (!(node_stiffness[node] > 0.0)) continue;
    for (std::size_t c = 0; c < d; ++c) {
      const double scaled = r[node * d + c] / node_stiffness[node];
      sum += scaled * scaled;
    }
  }
  return std::sqrt(sum);
}

void LinearSolver::update(StiffnessOperator& k, const ConstrainedSystem& s, std::span<const double> u, std::span<double> r,
                          std::span<double> node_stiffness, MotionTimings& timings) {
  const auto start = std::chrono::steady_clock::now();
  k.update(s.points);
  timings.assembly += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fill(node_stiffness.begin(), node_stiffness.end(), 0.0);
  const auto d = static_cast<std::size_t>(k.dofs_per_node());
  const ElementList& cells = k.cells();
  for (std::size_t c = 0; c < cells.size(); ++c) {  // in cell order: deterministic, cheap next to a product
    add_node_stiffness(cells.nodes(c), k.element_matrix(static_cast<CellId>(c)), d, node_stiffness);
  }
  s.periodic.fold_nodal(node_stiffness);
  k.apply(u, r);
  s.periodic.fold(r);
  s.constraints.project(r);
}

LinearTarget Forcing::next(int n, double residual, double initial) {
  const double floor = options_.pcg_tolerance;
  double eta = floor;
  constexpr double kSufficientDecrease = 1e-4;  // t
  const bool decreased =
      n == 0 || residual <= (1.0 - kSufficientDecrease * (1.0 - previous_eta_)) * previous_residual_;
  if (options_.forcing == ForcingTerm::eisenstat_walker && n > 0 && previous_residual_ > 0.0 && decreased) {
    constexpr double kGamma = 0.9, kAlpha = 2.0, kMax = 0.1;
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
