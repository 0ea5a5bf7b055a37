// hotmesh deform: the system of one increment (increment_system.hpp): the Newton residual from
// the node blocks or the assembled solver's element pass, and the constraints after each step.
#include "motion/increment_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "hotmesh/mesh/parallel_loops.hpp"
#include "hotmesh/core/clock.hpp"

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

void displace(std::span<const Vec3> x, std::span<const double> u, std::size_t d, std::span<Vec3> out) {
#pragma omp parallel for schedule(dynamic, mesh::kChunkNodes) if (static_cast<std::ptrdiff_t>(x.size()) >= mesh::kParallelNodes)
  for (std::ptrdiff_t n = 0; n < static_cast<std::ptrdiff_t>(x.size()); ++n) {
    const auto i = static_cast<std::size_t>(n);
    Vec3 p = x[i];
    for (std::size_t c = 0; c < d; ++c) p[c] += u[i * d + c];
    out[i] = p;
  }
}

ConstrainedSystem IncrementSystem::residual(std::span<const double> u, std::span<double> r,
                                            std::span<double> node_stiffness, const ReferenceResidual* reference,
                                            bool matrix_wanted) {
  displace(x_, u, dofs_per_node(), trial_);
  const ConstrainedSystem system{kernel_, setup_.constraints, setup_.periodic, trial_, node_stiffness};
  newton_residual(system, k_, assembler_, ranks_, u, r, node_stiffness, timings_, reference, matrix_wanted);
  return system;
}

double IncrementSystem::normal_slip(std::span<const double> p) const { return sliding_.normal_component(p); }

double IncrementSystem::restore(std::span<double> u) {
  // Every sliding node back onto the partial boundary c_b, with its new normal (4.2).
  const auto t = Clock::now();
  const double moved = sliding_.project(b_, x_, u);
  timings_.projection += seconds_since(t);
  setup_.periodic.expand(u);
  return moved;
}

}  // namespace hotmesh::deform::detail
