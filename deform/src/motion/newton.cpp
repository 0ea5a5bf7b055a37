// hotmesh deform: the Newton loop's residual, and the forcing term of inexact Newton.
#include "motion/newton.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "support/seconds_since.hpp"

namespace hotmesh::deform::detail {

void newton_residual(const ConstrainedSystem& s, StiffnessOperator* k, ElementAssembler* assembler,
                     const parallel::RankExchange& ranks, std::span<const double> u, std::span<double> r,
                     std::span<double> node_stiffness, MotionTimings& timings, const ReferenceResidual* reference,
                     bool matrix_wanted) {
  const auto start = Clock::now();
  std::fill(node_stiffness.begin(), node_stiffness.end(), 0.0);
  if (k) {
    k->update(s.points);
    timings.assembly += seconds_since(start);
    const auto d = static_cast<std::size_t>(s.kernel.dofs_per_node());
    std::vector<double> blocks(k->size() * d);
    k->diagonal_blocks(blocks);
    for (std::size_t n = 0; n < node_stiffness.size(); ++n) {  // the trace of the diagonal block over d
      for (std::size_t i = 0; i < d; ++i) node_stiffness[n] += blocks[(n * d + i) * d + i] / static_cast<double>(d);
    }
    s.periodic.fold_nodal(node_stiffness);
    k->apply(u, r);
    if (reference) k->apply(reference->u_start, reference->r_start);
  } else {
    if (!assembler) throw std::invalid_argument("newton_residual: neither node blocks of K nor a solver that computes them");
    std::fill(r.begin(), r.end(), 0.0);
    ResidualPass pass{u, r, node_stiffness, static_cast<std::size_t>(s.kernel.dofs_per_node())};
    if (reference) {
      std::fill(reference->r_start.begin(), reference->r_start.end(), 0.0);
      pass.u_start = reference->u_start;
      pass.r_start = reference->r_start;
    }
    assembler->assemble(s, pass, matrix_wanted);
    ranks.sum(r);  // each rank added its cells' part
    if (reference) ranks.sum(reference->r_start);
    ranks.sum(node_stiffness);
    s.periodic.fold_nodal(node_stiffness);
  }
  s.periodic.fold(r);
  s.constraints.project(r);
  if (reference) {
    s.periodic.fold(reference->r_start);
    s.constraints.project(reference->r_start);
  }
  if (!k) timings.assembly += seconds_since(start);
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
