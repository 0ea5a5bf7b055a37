// hotmesh deform: increments, the Newton-Raphson cycle (eqs. 7-8), quality checks, increment
// splitting, and the state a run hands out after each accepted step to be resumed from.
#include "hotmesh/deform/mesh_motion.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <optional>

#include <fmt/format.h>

#include "boundary_conditions.hpp"
#include "sliding.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/pcg.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "parallel.hpp"

namespace hotmesh::deform {

std::string_view to_string(BoundaryRole role) {
  switch (role) {
    case BoundaryRole::fixed: return "fixed";
    case BoundaryRole::prescribed: return "prescribed";
    case BoundaryRole::slip: return "slip";
    case BoundaryRole::sliding: return "sliding";
    case BoundaryRole::passive: return "passive";
    case BoundaryRole::periodic: return "periodic";
  }
  return "?";
}

namespace {

using Clock = std::chrono::steady_clock;

/// A Newton residual this many times the initial one means the cycle has blown up: better to
/// split the increment at once than to iterate on. Large transients are normal: the stiffness
/// of the thinnest cells scales with 1/h^2 and follows the geometry, so the ramp case passes
/// through residuals 1e5 times the initial one on its way to converging.
constexpr double kDivergence = 1e10;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// P T^T K T P: the stiffness restricted to the admissible subspace — periodic slaves expanded
/// from their masters before the element loop and folded back after it (periodic.hpp), the
/// normal component at sliding nodes removed (eq. 16), fixed nodes zeroed.
class ConstrainedOperator final : public LinearOperator {
 public:
  ConstrainedOperator(const StiffnessOperator& k, const NodeConstraints& c, const detail::PeriodicCoupling& periodic)
      : k_(k), c_(c), periodic_(periodic), expanded_(periodic.empty() ? 0 : k.size()) {}
  std::size_t size() const override { return k_.size(); }
  void apply(std::span<const double> x, std::span<double> y) const override {
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

 private:
  const StiffnessOperator& k_;
  const NodeConstraints& c_;
  const detail::PeriodicCoupling& periodic_;
  mutable std::vector<double> expanded_;  ///< work space (an operator is used by one thread)
};

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
#pragma omp parallel for schedule(static) if (nodes >= detail::kParallelNodes)
    for (std::ptrdiff_t i = 0; i < nodes; ++i) invert(static_cast<NodeId>(i), c);
  }
  std::size_t size() const override { return blocks_.size() / dim_; }
  void apply(std::span<const double> x, std::span<double> y) const override {
    const auto nodes = static_cast<std::ptrdiff_t>(size() / dim_);
#pragma omp parallel for schedule(static) if (nodes >= detail::kParallelNodes)
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

static_assert(std::tuple_size_v<decltype(SlidingState::hints)> == detail::SlidingNode::kMaxShapes);

class Motion {
 public:
  Motion(const Mesh& mesh, std::span<const PatchMotion> patches, const MaterialOptions& material,
         const SolverOptions& solver, const MotionObservers& observers, const MotionStart* start)
      : mesh_(mesh),
        solver_(solver),
        observers_(observers),
        setup_(detail::set_up_boundaries(mesh, patches, start)),
        sliding_(setup_, static_cast<std::size_t>(mesh.dimension)),
        stiffness_(mesh, element_lame(mesh, material), material.drop_jacobian),
        dim_(static_cast<std::size_t>(mesh.dimension)),
        size_(bounding_diagonal(mesh.points)) {}

  MotionResult run(const MotionCheckpoint* resume) {
    const auto start = Clock::now();
    result_.node_roles = setup_.roles;
    result_.notes = setup_.notes;
    result_.sliding_nodes = sliding_.size();
    result_.passive_nodes = setup_.passive.size();
    result_.periodic_pairs = setup_.periodic.pairs().size();
    for (const auto& s : setup_.sliding) result_.sliding_origins.push_back({s.node, s.origin});
    result_.points = setup_.reference;
    const int n = std::max(solver_.increments, 1);
    // The steps to do, in order; a step that fails is replaced by its two halves (up to
    // max_increment_splits deep), so a split increment's pieces come before the next one.
    std::deque<MotionStep> work;
    if (resume) {
      work.assign(resume->remaining.begin(), resume->remaining.end());
      restore(*resume);
    } else {
      for (int k = 1; k <= n; ++k) work.push_back({k, double(k - 1) / n, double(k) / n, 0});
    }
    while (!work.empty()) {
      const MotionStep step = work.front();
      work.pop_front();
      if (!advance(step, work)) break;
      if (!result_.increments.back().accepted) continue;
      if (work.empty() || work.front().increment != step.increment) finished_increments_ = step.increment;
      if (observers_.checkpoint) observers_.checkpoint(checkpoint(work, seconds_since(start)));
    }
    result_.success = result_.failed_points.empty();
    if (result_.success) result_.lambda_reached = 1.0;
    const auto q = Clock::now();
    result_.quality = scaled_jacobians(mesh_.cells, result_.points);
    result_.summary = summarize_quality(result_.quality);
    result_.periodic_max_mismatch = setup_.periodic.mismatch(result_.points) / size_;
    result_.timings.quality += seconds_since(q);
    result_.timings.total = seconds_since(start) + setup_seconds_ + earlier_seconds_;
    return std::move(result_);
  }

  void set_setup_time(double s) {
    setup_seconds_ = s;
    result_.timings.setup = s;
  }

 private:
  /// Moves the mesh by one step; on failure puts its two halves at the front of `work`
  /// (while splits are left) or ends the run (returns false).
  bool advance(const MotionStep& step, std::deque<MotionStep>& work) {
    const double a = step.lambda_begin, b = step.lambda_end;
    const int increment = step.increment, depth = step.split_depth;
    IncrementRecord record;
    record.increment = increment;
    record.split_depth = depth;
    std::vector<Vec3> moved = attempt(step, record);
    result_.increments.push_back(record);
    if (observers_.increment) observers_.increment(record);
    if (record.accepted) {
      result_.points = std::move(moved);
      result_.lambda_reached = b;
      return true;
    }
    if (depth < solver_.max_increment_splits) {
      const double mid = 0.5 * (a + b);
      work.push_front({increment, mid, b, depth + 1});
      work.push_front({increment, a, mid, depth + 1});
      return true;
    }
    result_.failed_points = std::move(moved);
    result_.failed_quality = scaled_jacobians(mesh_.cells, result_.failed_points);
    const auto worst = summarize_quality(result_.failed_quality);
    result_.message = fmt::format("increment {} of {} failed (stage {:.6g} to {:.6g}{}): {}", increment,
                                  std::max(solver_.increments, 1), a, b,
                                  depth > 0 ? fmt::format(", after splitting it {} times", depth) : "", record.failure);
    if (record.inverted_cells == 0) {  // name the cell that suffered most in the failed attempt
      result_.message += fmt::format("; worst cell {} (scaled Jacobian {:.3g})", mesh_.cell_id(worst.worst_cell),
                                     worst.min_scaled_jacobian);
    }
    return false;
  }

  /// The state to resume from after an accepted step, `work` the steps left.
  MotionCheckpoint checkpoint(const std::deque<MotionStep>& work, double seconds) const {
    MotionCheckpoint c;
    c.increments = std::max(solver_.increments, 1);
    c.finished_increments = finished_increments_;
    c.lambda = result_.lambda_reached;
    c.remaining.assign(work.begin(), work.end());
    c.points = result_.points;
    c.sliding.reserve(setup_.sliding.size());
    for (const detail::SlidingNode& s : setup_.sliding) c.sliding.push_back({s.node, s.target, s.hints});
    c.records = result_.increments;
    c.max_normal_slip = result_.max_normal_slip;
    c.max_sliding_projection_distance = result_.max_sliding_projection_distance;
    c.timings = result_.timings;
    c.timings.total = seconds + setup_seconds_ + earlier_seconds_;
    return c;
  }

  /// Takes up an interrupted run where its checkpoint left it.
  void restore(const MotionCheckpoint& c) {
    const auto refuse = [](const std::string& what) {
      throw InputError("the checkpoint does not fit this run: " + what);
    };
    if (c.increments != std::max(solver_.increments, 1)) {
      refuse(fmt::format("it was written for {} increments, this run has {}", c.increments, solver_.increments));
    }
    if (c.points.size() != mesh_.node_count()) {
      refuse(fmt::format("it holds {} nodes, the mesh {}", c.points.size(), mesh_.node_count()));
    }
    if (c.sliding.size() != setup_.sliding.size()) {
      refuse(fmt::format("it holds {} sliding nodes, this set-up {}", c.sliding.size(), setup_.sliding.size()));
    }
    for (std::size_t i = 0; i < c.sliding.size(); ++i) {
      detail::SlidingNode& s = setup_.sliding[i];
      if (c.sliding[i].node != s.node) refuse(fmt::format("sliding node {} differs", mesh_.node_id(s.node)));
      s.target = c.sliding[i].target;
      s.hints = c.sliding[i].hints;
    }
    for (const MotionStep& step : c.remaining) {
      if (!(step.lambda_begin >= 0.0 && step.lambda_begin < step.lambda_end && step.lambda_end <= 1.0) ||
          step.increment < 1 || step.increment > c.increments || step.split_depth < 0) {
        refuse("its steps left are damaged");
      }
    }
    result_.points = c.points;
    result_.lambda_reached = c.lambda;
    result_.increments = c.records;
    result_.max_normal_slip = c.max_normal_slip;
    result_.max_sliding_projection_distance = c.max_sliding_projection_distance;
    finished_increments_ = c.finished_increments;
    result_.timings = c.timings;  // the interrupted run's, this run's added as they come
    result_.timings.setup += setup_seconds_;
    earlier_seconds_ = c.timings.total;
  }

  /// One increment: Newton-Raphson from the current mesh to stage b. Returns the new points.
  std::vector<Vec3> attempt(const MotionStep& piece, IncrementRecord& record) {
    const auto start = Clock::now();
    const double a = piece.lambda_begin, b = piece.lambda_end;
    record.lambda_begin = a;
    record.lambda_end = b;
    const std::vector<Vec3>& x = result_.points;
    const std::size_t dofs = stiffness_.size();

    // Initial u: the boundary's move to stage b on prescribed nodes, the forcing
    // displacement u0s on sliding nodes (eqs. 13, 22), zero elsewhere.
    std::vector<double> u(dofs, 0.0);
    for (const auto& p : setup_.prescribed) {
      const auto i = static_cast<std::size_t>(p.node);
      const Vec3 target = detail::prescribed_position(p, setup_.reference[i], b);
      for (std::size_t c = 0; c < dim_; ++c) u[i * dim_ + c] = target[c] - x[i][c];
    }
    for (const auto& p : setup_.passive) {  // passive surfaces move with the stage (6.1)
      const auto i = static_cast<std::size_t>(p.node);
      const Vec3 target = setup_.reference[i] + b * p.displacement;
      for (std::size_t c = 0; c < dim_; ++c) u[i * dim_ + c] = target[c] - x[i][c];
    }
    auto t = Clock::now();
    sliding_.begin_increment(a, b, x, u);
    result_.timings.projection += seconds_since(t);
    setup_.periodic.expand(u);  // slaves follow their masters

    std::vector<Vec3> trial(x.size());
    std::vector<double> r(dofs), rhs(dofs), p(dofs);
    double r0 = 0.0;
    const ConstrainedOperator k(stiffness_, setup_.constraints, setup_.periodic);
    for (int it = 0;; ++it) {
      displace(x, u, trial);
      t = Clock::now();
      stiffness_.update(trial);  // K(n) at the current geometry (eq. 8)
      result_.timings.assembly += seconds_since(t);
      // R(n) = K(n) u(n) - f (eq. 7; f is K's action on the boundary motion), with only its
      // tangential part F_t at sliding nodes (eq. 17).
      stiffness_.apply(u, r);
      setup_.periodic.fold(r);
      setup_.constraints.project(r);
      const double residual = norm2(r);
      if (it == 0) r0 = residual;
      record.newton.push_back({residual, 0, true, 0.0});
      record.residual_reduction = r0 > 0.0 ? residual / r0 : 0.0;
      if (it > 0 && observers_.newton) report_step(piece, record, it, seconds_since(start));
      if (!std::isfinite(residual) || residual > kDivergence * r0) {
        record.failure = fmt::format("the Newton-Raphson cycle diverged (residual {:.3g} times the initial one)",
                                     residual / r0);
        break;
      }
      if (residual <= solver_.newton_tolerance * r0 || r0 == 0.0) {
        record.converged = true;
        break;
      }
      if (it == solver_.max_newton_iterations) {
        record.failure = fmt::format("the Newton-Raphson cycle did not converge in {} iterations (residual reduced "
                                     "to {:.3g}, tolerance {:.3g})",
                                     solver_.max_newton_iterations, record.residual_reduction, solver_.newton_tolerance);
        break;
      }
      // K(n) p = -R(n) on the free degrees of freedom, from p = 0 (eq. 8, section 3); at
      // sliding nodes the projected operator solves eq. (16) and keeps p . n = 0 (eq. 19).
      for (std::size_t i = 0; i < dofs; ++i) rhs[i] = -r[i];
      std::fill(p.begin(), p.end(), 0.0);
      t = Clock::now();
      const NodalJacobi m(stiffness_, setup_.constraints, setup_.periodic);
      const auto cg = pcg(k, m, rhs, p,
                          {.relative_tolerance = solver_.pcg_tolerance,
                           .max_iterations = solver_.max_pcg_iterations,
                           .record_history = false,
                           .project = [this](std::span<double> v) { setup_.constraints.project(v); }});
      result_.timings.solve += seconds_since(t);
      auto& step = record.newton.back();
      step.pcg_iterations = cg.iterations;
      step.pcg_converged = cg.converged;
      step.pcg_reduction = cg.initial_residual > 0.0 ? cg.final_residual / cg.initial_residual : 0.0;
      if (cg.breakdown) {
        record.failure = "the linear solver broke down (the stiffness is not positive definite on the free nodes)";
        break;
      }
      record.max_normal_slip = std::max(record.max_normal_slip, sliding_.normal_component(p));
      axpy(1.0, p, u);
      // Every sliding node back onto the partial boundary c_b, with its new normal (4.2).
      t = Clock::now();
      step.max_projection = sliding_.project(b, x, u);
      result_.timings.projection += seconds_since(t);
      setup_.periodic.expand(u);
    }
    if (record.converged) {
      t = Clock::now();
      const auto quality = scaled_jacobians(mesh_.cells, trial);
      const auto summary = summarize_quality(quality);
      result_.timings.quality += seconds_since(t);
      record.min_scaled_jacobian = summary.min_scaled_jacobian;
      record.inverted_cells = summary.inverted_cells;
      record.worst_cell = summary.worst_cell;
      if (summary.inverted_cells > 0) {
        record.failure = fmt::format("{} cells inverted, the worst cell {} (scaled Jacobian {:.3g})",
                                     summary.inverted_cells, mesh_.cell_id(summary.worst_cell),
                                     summary.min_scaled_jacobian);
      } else {
        record.accepted = true;
        sliding_.end_increment(u);
        result_.max_normal_slip = std::max(result_.max_normal_slip, record.max_normal_slip);
        const auto steps = record.newton.size();
        result_.max_sliding_projection_distance = steps >= 2 ? record.newton[steps - 2].max_projection / size_ : 0.0;
      }
    }
    record.seconds = seconds_since(start);
    return trial;
  }

  void report_step(const MotionStep& step, const IncrementRecord& record, int it, double seconds) const {
    const NewtonStep& done = record.newton[static_cast<std::size_t>(it - 1)];
    observers_.newton({.step = step,
                       .increments = std::max(solver_.increments, 1),
                       .iteration = it,
                       .residual_reduction = record.residual_reduction,
                       .pcg_iterations = done.pcg_iterations,
                       .pcg_converged = done.pcg_converged,
                       .max_projection = done.max_projection,
                       .seconds = seconds});
  }

  void displace(const std::vector<Vec3>& x, std::span<const double> u, std::vector<Vec3>& out) const {
#pragma omp parallel for schedule(static) if (static_cast<std::ptrdiff_t>(x.size()) >= detail::kParallelNodes)
    for (std::ptrdiff_t n = 0; n < static_cast<std::ptrdiff_t>(x.size()); ++n) {
      const auto i = static_cast<std::size_t>(n);
      Vec3 p = x[i];
      for (std::size_t c = 0; c < dim_; ++c) p[c] += u[i * dim_ + c];
      out[i] = p;
    }
  }

  static double bounding_diagonal(std::span<const Vec3> points) {
    Vec3 lo = points.front(), hi = lo;
    for (const Vec3& p : points) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    return std::max(norm(hi - lo), 1e-300);
  }

  const Mesh& mesh_;
  SolverOptions solver_;
  const MotionObservers& observers_;
  detail::BoundarySetup setup_;
  detail::SlidingNodes sliding_;
  StiffnessOperator stiffness_;
  std::size_t dim_;
  double size_;
  int finished_increments_ = 0;
  double setup_seconds_ = 0.0;    ///< of this run
  double earlier_seconds_ = 0.0;  ///< total of the interrupted run this one resumes
  MotionResult result_;
};

}  // namespace

MotionResult move_mesh(const Mesh& mesh, std::span<const PatchMotion> patches, const MaterialOptions& material,
                       const SolverOptions& solver, const MotionObservers& observers, const MotionStart* start,
                       const MotionCheckpoint* resume) {
  const auto begin = Clock::now();
  Motion motion(mesh, patches, material, solver, observers, start);
  motion.set_setup_time(seconds_since(begin));
  return motion.run(resume);
}

}  // namespace hotmesh::deform
