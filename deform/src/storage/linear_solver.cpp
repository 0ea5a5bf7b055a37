// hotmesh deform: the choice of linear solver, the Newton norm its solves may stop on, and the
// Newton residual's part of an element pass (ResidualPass).
#include "storage/linear_solver.hpp"

#include <cmath>
#include <stdexcept>

#include "hotmesh/deform/element_stiffness.hpp"
#include "storage/petsc_solver.hpp"

namespace hotmesh::deform::detail {

void ResidualPass::add(std::span<const NodeId> nodes, std::span<const double> ke) const {
  add_element_product(nodes, ke, d, u, r);
  if (!u_start.empty()) add_element_product(nodes, ke, d, u_start, r_start);
  add_node_stiffness(nodes, ke, d, node_stiffness);
}

std::unique_ptr<LinearSolver> make_jacobi_pcg_solver(const SolverOptions& options,
                                                     const StiffnessOperator& k);  // jacobi_pcg.cpp

std::unique_ptr<LinearSolver> make_linear_solver(const SolverOptions& options, const parallel::RankExchange& ranks,
                                                 const StiffnessOperator* k) {
  if (!solves_with_node_blocks(options)) return make_assembled_solver(options, ranks);
  if (!k) throw std::invalid_argument("make_linear_solver: jacobi-pcg needs K in node blocks");
  return make_jacobi_pcg_solver(options, *k);
}

bool solves_with_node_blocks(const SolverOptions& options) {
  return options.linear == LinearSolverKind::jacobi_pcg || options.linear == LinearSolverKind::automatic;
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

}  // namespace hotmesh::deform::detail
