// hotmesh deform: the increment scheduler (motion.hpp): increments k = 1..N, a failed one split
// into halves, and one attempt at an increment, Newton-Raphson (eqs. 7-8, newton.hpp) on its
// system (increment_system.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "hotmesh/mesh/quality.hpp"
#include "motion/increment_system.hpp"
#include "motion/motion.hpp"
#include "motion/newton.hpp"
#include "support/free_memory.hpp"
#include "hotmesh/core/clock.hpp"

namespace hotmesh::deform::detail {

/// `kernel`: the K_e of the mesh's cells (eq. 35 and the Q1 element), shared with the
/// corner pass.
Motion::Motion(const Mesh& mesh, std::span<const PatchMotion> patches, std::shared_ptr<const StiffnessKernel> kernel,
               const SolverOptions& solver, const MotionObservers& observers, const MotionStart* start,
               const parallel::RankExchange& ranks)
    : mesh_(mesh),
      solver_(solver),
      observers_(observers),
      setup_(set_up_boundaries(mesh, patches, start)),
      sliding_(setup_, static_cast<std::size_t>(mesh.dimension), ranks),
      ranks_(ranks),
      kernel_(std::move(kernel)),
      blocks_(solves_with_node_blocks(solver) ? std::optional<StiffnessOperator>(kernel_) : std::nullopt),
      linear_(make_linear_solver(solver, ranks, blocks_ ? &*blocks_ : nullptr)),
      dim_(static_cast<std::size_t>(mesh.dimension)),
      size_(std::max(bounding_diagonal(mesh.points), 1e-300)) {}

MotionResult Motion::run(const MotionCheckpoint* resume) {
  const auto start = Clock::now();
  result_.node_roles = setup_.roles;
  result_.notes = setup_.notes;
  result_.wall_gaps = setup_.wall_gaps;
  result_.sliding_nodes = sliding_.size();
  result_.passive_nodes = setup_.passive.size();
  result_.periodic_pairs = setup_.periodic.pairs().size();
  for (const auto& s : setup_.sliding) result_.sliding_origins.push_back({s.node, s.origin});
  result_.points.assign(setup_.reference.begin(), setup_.reference.end());
  const int n = increments();
  // The steps to do, in order: the pieces of a split increment first (a step that fails is
  // replaced by its two halves, up to max_increment_splits deep), then the whole increments
  // from `next` to N, made as they come (nothing is held per increment of the run).
  std::deque<MotionStep> pieces;
  int next = 1;
  if (resume) {
    restore(*resume);
    pieces.assign(resume->split_pieces.begin(), resume->split_pieces.end());
    next = resume->finished_increments + (pieces.empty() ? 1 : 2);
  }
  while (!pieces.empty() || next <= n) {
    MotionStep step;
    if (!pieces.empty()) {
      step = pieces.front();
      pieces.pop_front();
    } else {
      step = {next, double(next - 1) / n, double(next) / n, 0};
      ++next;
    }
    if (!advance(step, pieces)) break;
    if (!result_.increments.back().accepted) continue;
    if (pieces.empty()) finished_increments_ = step.increment;
    if (observers_.checkpoint) observers_.checkpoint(checkpoint(pieces, seconds_since(start)));
    release_free_memory();  // the increment's and its checkpoint's freed blocks
  }
  result_.success = result_.failed_points.empty();
  if (result_.success) result_.lambda_reached = 1.0;
  measure_accepted_steps();
  const auto q = Clock::now();
  result_.quality = scaled_jacobians(mesh_.cells, result_.points);
  result_.summary = summarize_quality(result_.quality);
  result_.length_scale = size_;
  result_.max_periodic_mismatch = setup_.periodic.mismatch(result_.points);
  report_corners();
  for (std::string& note : linear_->notes()) result_.notes.push_back(std::move(note));
  result_.timings.quality += seconds_since(q);
  result_.timings.total = seconds_since(start) + setup_seconds_ + earlier_seconds_;
  return std::move(result_);
}

void Motion::set_setup_time(double s) {
  setup_seconds_ = s;
  result_.timings.setup = s;
}

/// Moves the mesh by one step; on failure puts its two halves at the front of `pieces`
/// (while splits are left) or ends the run (returns false).
bool Motion::advance(const MotionStep& step, std::deque<MotionStep>& pieces) {
  const double a = step.lambda_begin, b = step.lambda_end;
  const int increment = step.increment, depth = step.split_depth;
  IncrementRecord record;
  record.increment = increment;
  record.split_depth = depth;
  std::vector<Vec3> moved = attempt(step, record);
  result_.increments.push_back(record);
  if (observers_.increment) observers_.increment(record);
  if (record.accepted) {
    previous_points_ = std::move(result_.points);
    previous_stage_ = a;
    result_.points = std::move(moved);
    result_.lambda_reached = b;
    return true;
  }
  if (depth < solver_.max_increment_splits) {
    const double mid = 0.5 * (a + b);
    pieces.push_front({increment, mid, b, depth + 1});
    pieces.push_front({increment, a, mid, depth + 1});
    return true;
  }
  result_.failed_points = std::move(moved);
  result_.failed_quality = scaled_jacobians(mesh_.cells, result_.failed_points);
  const auto worst = summarize_quality(result_.failed_quality);
  result_.failure = std::move(failure_);
  result_.message = fmt::format("increment {} of {} failed (stage {:.6g} to {:.6g}{}): {}", increment,
                                increments(), a, b,
                                depth > 0 ? fmt::format(", after splitting it {} times", depth) : "", record.failure);
  if (record.inverted_cells == 0 && failure_.kind != MotionFailure::Kind::quality_limits) {  // the cell that suffered most
    result_.message += fmt::format("; no cell inverted, the worst at the failed stage is cell {} (scaled Jacobian {:.3g})",
                                   mesh_.cell_id(worst.worst_cell), worst.min_scaled_jacobian);
  }
  result_.message += where_it_failed();
  return false;
}

/// The residual ||D^-1 R|| (a length) that rounding alone leaves in a mesh of this size at
/// rest: an increment with nothing to move (zero deflection on a curved sliding wall) starts
/// there, and no relative reduction of it can be asked for.
double Motion::round_off_residual(std::size_t dofs) const {
  return 64.0 * std::numeric_limits<double>::epsilon() * size_ * std::sqrt(static_cast<double>(dofs));
}

/// One increment: Newton-Raphson from the current mesh to stage b. Returns the new points.
std::vector<Vec3> Motion::attempt(const MotionStep& piece, IncrementRecord& record) {
  const auto start = Clock::now();
  const double a = piece.lambda_begin, b = piece.lambda_end;
  record.lambda_begin = a;
  record.lambda_end = b;

  std::vector<double> u = initial_displacements(a, b);
  std::vector<double> unpredicted = predict(a, b, u);

  IncrementSystem system(result_.points, b, *kernel_, setup_, sliding_, blocks_ ? &*blocks_ : nullptr,
                         linear_->assembler(), ranks_, result_.timings);
  NewtonSolver newton(solver_, *linear_, result_.timings, round_off_residual(kernel_->size()));
  NewtonResult solved = newton.solve(system, u, std::move(unpredicted), [&](const NewtonResult& so_far, int it) {
    if (observers_.newton) report_step(piece, so_far, it, seconds_since(start));
  });
  record.newton = std::move(solved.steps);
  record.residual_reduction = solved.residual_reduction;
  record.max_normal_slip = solved.max_normal_slip;
  record.converged = solved.stop == NewtonStop::converged;
  record.failure = std::move(solved.failure);
  if (solved.stop == NewtonStop::diverged) {
    note_failure(MotionFailure::Kind::newton_diverged, newton.residual(), newton.node_stiffness());
  } else if (solved.stop == NewtonStop::stalled) {
    note_failure(MotionFailure::Kind::newton_stalled, newton.residual(), newton.node_stiffness());
  } else if (solved.stop == NewtonStop::linear_breakdown) {
    note_failure(MotionFailure::Kind::linear_breakdown);
  }
  std::vector<Vec3>& trial = system.points();
  if (record.converged) {
    if (solver_.quality.smoothing) smooth_for_solver(trial, record);
    accept_if_valid(trial, u, record);
    if (!record.accepted) {
      note_failure(record.inverted_cells > 0 ? MotionFailure::Kind::inverted_cells : MotionFailure::Kind::quality_limits);
    }
  }
  record.seconds = seconds_since(start);
  return std::move(trial);
}

/// A Newton step done, to the observer (NewtonProgress).
void Motion::report_step(const MotionStep& step, const NewtonResult& newton, int it, double seconds) const {
  const NewtonStep& done = newton.steps[static_cast<std::size_t>(it - 1)];
  observers_.newton({.step = step,
                     .increments = increments(),
                     .iteration = it,
                     .residual_reduction = newton.residual_reduction,
                     .pcg_iterations = done.pcg_iterations,
                     .pcg_converged = done.pcg_converged,
                     .newton_norm = done.linear_newton_norm,
                     .max_projection = done.max_projection,
                     .seconds = seconds});
}

}  // namespace hotmesh::deform::detail
