// hotmesh deform: the paper's linear solver (section 3): PCG on the projected operator
// P T^T K T P (eq. 16; periodic.hpp) with nodal Jacobi, from p = 0, K in node blocks
// (stiffness_operator.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "hotmesh/deform/pcg.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"
#include "storage/linear_solver.hpp"
#include "hotmesh/core/clock.hpp"

namespace hotmesh::deform::detail {

void ConstrainedOperator::apply(std::span<const double> x, std::span<double> y) const {
  if (periodic_.empty()) {
    k_.apply(x, y);
  } else {
    std::copy(x.begin(), x.end(), expanded_.begin());
    periodic_.expand(expanded_);
    k_.apply(expanded_, y);
    periodic_.fold(y);
  }
  c_.project(y);
}

namespace {

/// Nodal (block) Jacobi: y_i = M_i x_i with M_i the inverse of the node's d x d diagonal block
/// B_i of K on the directions the node may move in: M_i = P (P B_i P + I - P)^-1 P, P the
/// projector that removes the node's constrained normals (zero for fixed nodes). For a free
/// node it is B_i^-1; for a sliding node it inverts the stiffness along the boundary only, so
/// the result stays tangential ("apply, then project" in one step). It takes the coupling of
/// a node's components into account, which point Jacobi does not: in the stretched cells of a
/// boundary layer, or on a sliding wall at an angle, that roughly halves the PCG iterations.
class NodalJacobi final : public LinearOperator {
 public:
  NodalJacobi(const StiffnessOperator& k, const NodeConstraints& c, const detail::PeriodicCoupling& periodic)
      : dim_(static_cast<std::size_t>(k.dofs_per_node())), blocks_(k.size() * dim_) {
    k.diagonal_blocks(blocks_);
    periodic.fold_blocks(blocks_);  // a master carries its slave's stiffness
    const auto nodes = static_cast<std::ptrdiff_t>(c.node_count());
#pragma omp parallel for schedule(dynamic, mesh::kChunkNodes) if (nodes >= mesh::kParallelNodes)
    for (std::ptrdiff_t i = 0; i < nodes; ++i) invert(static_cast<NodeId>(i), c);
  }
  std::size_t size() const override { return blocks_.size() / dim_; }
  void apply(std::span<const double> x, std::span<double> y) const override {
    const auto nodes = static_cast<std::ptrdiff_t>(size() / dim_);
#pragma omp parallel for schedule(dynamic, mesh::kChunkNodes) if (nodes >= mesh::kParallelNodes)
    for (std::ptrdiff_t i = 0; i < nodes; ++i) {
      const auto base = static_cast<std::size_t>(i) * dim_;
      const double* m = blocks_.data() + base * dim_;
      for (std::size_t r = 0; r < dim_; ++r) {
        double s = 0.0;
        for (std::size_t j = 0; j < dim_; ++j) s += m[r * dim_ + j] * x[base + j];
        y[base + r] = s;
      }
    }
  }

 private:
  void invert(NodeId n, const NodeConstraints& c) {
    double* b = blocks_.data() + static_cast<std::size_t>(n) * dim_ * dim_;
    if (c.is_fixed(n)) {
      std::fill(b, b + dim_ * dim_, 0.0);
      return;
    }
    // P = I - sum n n^T; A = P B P + (I - P).
    std::array<double, 9> p{}, a{}, inv{};
    for (std::size_t i = 0; i < dim_; ++i) p[i * dim_ + i] = 1.0;
    for (const Vec3& normal : c.normals(n)) {
      for (std::size_t i = 0; i < dim_; ++i) {
        for (std::size_t j = 0; j < dim_; ++j) p[i * dim_ + j] -= normal[i] * normal[j];
      }
    }
    const auto at = [this](const std::array<double, 9>& m, std::size_t i, std::size_t j) { return m[i * dim_ + j]; };
    std::array<double, 9> bp{};
    for (std::size_t i = 0; i < dim_; ++i) {
      for (std::size_t j = 0; j < dim_; ++j) {
        for (std::size_t k = 0; k < dim_; ++k) bp[i * dim_ + j] += b[i * dim_ + k] * at(p, k, j);
      }
    }
    for (std::size_t i = 0; i < dim_; ++i) {
      for (std::size_t j = 0; j < dim_; ++j) {
        double s = (i == j ? 1.0 : 0.0) - at(p, i, j);
        for (std::size_t k = 0; k < dim_; ++k) s += at(p, i, k) * at(bp, k, j);
        a[i * dim_ + j] = s;
      }
    }
    if (!invert_small(a, inv)) {
      std::fill(b, b + dim_ * dim_, 0.0);
      return;
    }
    for (std::size_t i = 0; i < dim_; ++i) {  // M = P A^-1 P
      for (std::size_t j = 0; j < dim_; ++j) {
        double s = 0.0;
        for (std::size_t k = 0; k < dim_; ++k) {
          for (std::size_t l = 0; l < dim_; ++l) s += at(p, i, k) * at(inv, k, l) * at(p, l, j);
        }
        b[i * dim_ + j] = s;
      }
    }
  }

  bool invert_small(const std::array<double, 9>& a, std::array<double, 9>& inv) const {
    if (dim_ == 2) {
      const double det = a[0] * a[3] - a[1] * a[2];
      if (!(std::abs(det) > 0.0)) return false;
      inv = {a[3] / det, -a[1] / det, -a[2] / det, a[0] / det};
      return true;
    }
    const double det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
                       a[2] * (a[3] * a[7] - a[4] * a[6]);
    if (!(std::abs(det) > 0.0)) return false;
    inv = {(a[4] * a[8] - a[5] * a[7]) / det, (a[2] * a[7] - a[1] * a[8]) / det, (a[1] * a[5] - a[2] * a[4]) / det,
           (a[5] * a[6] - a[3] * a[8]) / det, (a[0] * a[8] - a[2] * a[6]) / det, (a[2] * a[3] - a[0] * a[5]) / det,
           (a[3] * a[7] - a[4] * a[6]) / det, (a[1] * a[6] - a[0] * a[7]) / det, (a[0] * a[4] - a[1] * a[3]) / det};
    return true;
  }

  std::size_t dim_;
  std::vector<double> blocks_;  ///< B_i, then M_i, row-major per node
};

/// ||D^-1 r|| with the system's node stiffness for the Newton norm; the plain ||r|| otherwise.
std::function<double(std::span<const double>)> residual_norm(const ConstrainedSystem& s, bool newton_norm) {
  if (!newton_norm) return {};
  const auto d = static_cast<std::size_t>(s.kernel.dofs_per_node());
  return [&s, d](std::span<const double> r) { return scaled_residual_norm(r, s.node_stiffness, d); };
}

class JacobiPcgSolver final : public LinearSolver {
 public:
  JacobiPcgSolver(const SolverOptions& options, const StiffnessOperator& k)
      : k_(k), max_iterations_(options.max_pcg_iterations) {}

  LinearSolveResult solve(const ConstrainedSystem& s, std::span<const double> rhs, std::span<double> p,
                          const LinearTarget& target, MotionTimings& timings) override {
    const ConstrainedOperator k(k_, s.constraints, s.periodic);
    auto t = Clock::now();
    const NodalJacobi m(k_, s.constraints, s.periodic);
    timings.preconditioner += seconds_since(t);
    t = Clock::now();
    std::vector<double> own_rhs;  // p is cleared below: where p is rhs, rhs is kept apart
    if (rhs.data() == p.data()) {
      own_rhs.assign(rhs.begin(), rhs.end());
      rhs = own_rhs;
    }
    std::fill(p.begin(), p.end(), 0.0);
    const auto cg = pcg(k, m, rhs, p,
                        {.relative_tolerance = target.tolerance,
                         .max_iterations = max_iterations_,
                         .record_history = false,
                         .project = [&s](std::span<double> v) { s.constraints.project(v); },
                         .norm = residual_norm(s, target.newton_norm)});
    timings.solve += seconds_since(t);
    return {cg.iterations, cg.converged, cg.breakdown,
            cg.initial_residual > 0.0 ? cg.final_residual / cg.initial_residual : 0.0};
  }

 private:
  const StiffnessOperator& k_;  ///< K(n) in node blocks, as the Newton loop updated it
  int max_iterations_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_jacobi_pcg_solver(const SolverOptions& options, const StiffnessOperator& k) {
  return std::make_unique<JacobiPcgSolver>(options, k);
}

}  // namespace hotmesh::deform::detail
