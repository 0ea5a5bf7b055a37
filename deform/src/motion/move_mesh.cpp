// hotmesh deform: increments, the Newton-Raphson cycle (eqs. 7-8), quality checks, increment
// splitting, and the state a run hands out after each accepted step to be resumed from.
#include "hotmesh/deform/move_mesh.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "constraints/boundary_conditions.hpp"
#include "constraints/sliding.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"
#include "hotmesh/mesh/solver_quality.hpp"
#include "motion/newton.hpp"
#include "motion/quality_repair.hpp"
#include "storage/linear_solver.hpp"
#include "support/free_memory.hpp"

namespace hotmesh::deform {

namespace {

using Clock = std::chrono::steady_clock;

/// A Newton residual this many times the initial one means the cycle has blown up: better to
/// split the increment at once than to iterate on. Large transients are normal: the stiffness
/// of the thinnest cells scales with 1/h^2 and follows the geometry, so the ramp case passes
/// through residuals 1e5 times the initial one on its way to converging.
constexpr double kDivergence = 1e10;
/// A failed run names this many nodes where its residual is largest.
constexpr std::size_t kResidualNodesShown = 3;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

static_assert(std::tuple_size_v<decltype(SlidingState::hints)> == detail::SlidingNode::kMaxShapes);

class Motion {
 public:
  /// `kernel`: the K_e of the mesh's cells (eq. 35 and the Q1 element), shared with the
  /// corner pass.
  Motion(const Mesh& mesh, std::span<const PatchMotion> patches, std::shared_ptr<const StiffnessKernel> kernel,
         const SolverOptions& solver, const MotionObservers& observers, const MotionStart* start,
         const parallel::RankExchange& ranks)
      : mesh_(mesh),
        solver_(solver),
        observers_(observers),
        setup_(detail::set_up_boundaries(mesh, patches, start)),
        sliding_(setup_, static_cast<std::size_t>(mesh.dimension), ranks),
        ranks_(ranks),
        kernel_(std::move(kernel)),
        blocks_(detail::solves_with_node_blocks(solver) ? std::optional<StiffnessOperator>(kernel_) : std::nullopt),
        linear_(detail::make_linear_solver(solver, ranks, blocks_ ? &*blocks_ : nullptr)),
        dim_(static_cast<std::size_t>(mesh.dimension)),
        size_(std::max(bounding_diagonal(mesh.points), 1e-300)) {}

  MotionResult run(const MotionCheckpoint* resume) {
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
      detail::release_free_memory();  // the increment's and its checkpoint's freed blocks
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

  void set_setup_time(double s) {
    setup_seconds_ = s;
    result_.timings.setup = s;
  }

 private:
  int increments() const { return std::max(solver_.increments, 1); }

  /// The corners of the sliding walls and the creases of those made of faces, and how far
  /// their nodes are from them at the end.
  void report_corners() {
    for (const detail::WallCorner& c : setup_.corners) {
      WallFeature f{c.patch,
                    c.held.feature.parameter,
                    c.held.feature.angle,
                    {},
                    c.held.nodes,
                    c.held.nodes.size(),
                    c.held.largest_offset,
                    0.0,
                    c.held.unheld_edges,
                    c.held.from_start};
      f.nodes.insert(f.nodes.end(), c.held.held_by_role.begin(), c.held.held_by_role.end());
      for (NodeId n : f.nodes) {
        const Vec3& x = result_.points[static_cast<std::size_t>(n)];
        f.distance = std::max(f.distance, distance(x, c.shape->at({.t = f.parameter}, result_.lambda_reached, x).point));
      }
      const Vec3& reference = f.nodes.empty() ? c.reference : result_.points[static_cast<std::size_t>(f.nodes.front())];
      f.point = c.shape->at({.t = f.parameter}, result_.lambda_reached, reference).point;
      result_.features.push_back(std::move(f));
    }
    for (const detail::WallCrease& c : setup_.creases) {
      const Vec3 reference = c.nodes.empty() ? Vec3{} : result_.points[static_cast<std::size_t>(c.nodes.front())];
      WallFeature f{c.patch,        0.0, c.angle, reference, c.nodes, c.nodes.size(), c.largest_offset, 0.0, c.unheld_edges,
                    c.wall == nullptr, c.faces};
      if (c.wall != nullptr) f.point = c.wall->crease_point(c.line, reference, result_.lambda_reached).point;
      for (NodeId n : c.nodes) {
        const Vec3& x = result_.points[static_cast<std::size_t>(n)];
        for (const geometry::BoundaryShape* side : c.sides) {
          f.distance = std::max(f.distance, side->project(x, result_.lambda_reached).distance);
        }
        if (c.sides.empty()) {
          f.distance = std::max(f.distance, distance(x, c.wall->crease_point(c.line, x, result_.lambda_reached).point));
        }
      }
      result_.features.push_back(std::move(f));
    }
  }

  /// The run's maxima over every Newton step of its accepted attempts, from their records (so
  /// a resumed run, which holds the interrupted run's records, finds the same).
  void measure_accepted_steps() {
    for (const IncrementRecord& r : result_.increments) {
      if (!r.accepted) continue;
      result_.max_normal_slip = std::max(result_.max_normal_slip, r.max_normal_slip);
      for (const NewtonStep& step : r.newton) {
        result_.max_projection_distance = std::max(result_.max_projection_distance, step.max_projection);
      }
      // The last step's: the last entry of `newton` holds the final residual, not a step.
      const std::size_t steps = r.newton.size();
      result_.final_projection_distance = steps >= 2 ? r.newton[steps - 2].max_projection : 0.0;
    }
  }

  /// Moves the mesh by one step; on failure puts its two halves at the front of `pieces`
  /// (while splits are left) or ends the run (returns false).
  bool advance(const MotionStep& step, std::deque<MotionStep>& pieces) {
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

  /// What the last attempt ran into, and, where Newton did not converge, the residual
  /// ||D^-1 R|| of its last step at each node (from r and the node stiffness k of that step;
  /// none where the linear solver broke down or cells inverted).
  void note_failure(MotionFailure::Kind kind, std::span<const double> r = {}, std::span<const double> k = {}) {
    failure_ = {};
    failure_.kind = kind;
    if (k.empty()) return;
    failure_.residual.assign(k.size(), 0.0);
    for (std::size_t node = 0; node < k.size(); ++node) {
      if (!(k[node] > 0.0)) continue;
      double sum = 0.0;
      for (std::size_t c = 0; c < dim_; ++c) sum += (r[node * dim_ + c] / k[node]) * (r[node * dim_ + c] / k[node]);
      failure_.residual[node] = std::sqrt(sum);
    }
    std::vector<NodeId> order(k.size());
    for (std::size_t n = 0; n < order.size(); ++n) order[n] = static_cast<NodeId>(n);
    const std::size_t shown = std::min<std::size_t>(kResidualNodesShown, order.size());
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(shown), order.end(), [&](NodeId a, NodeId b) {
      return failure_.residual[static_cast<std::size_t>(a)] > failure_.residual[static_cast<std::size_t>(b)];
    });
    for (std::size_t i = 0; i < shown; ++i) {
      const double value = failure_.residual[static_cast<std::size_t>(order[i])];
      if (value > 0.0) failure_.largest_residuals.push_back({order[i], value});
    }
  }

  /// Where the failed attempt's Newton residual is largest, each node with its place and role,
  /// and what the user can try.
  std::string where_it_failed() const {
    const MotionFailure& f = result_.failure;
    if (f.kind == MotionFailure::Kind::inverted_cells) {
      return ". Try more increments (solver.increments) or splits (solver.max_increment_splits); a deflection as "
             "large as the cells beside the wall needs finer cells there";
    }
    if (f.kind == MotionFailure::Kind::quality_limits) {
      return ". The motion cannot keep the case's quality limits: try finer cells where the walls move most, more "
             "increments, or looser limits";
    }
    if (f.largest_residuals.empty()) return "";
    std::string text = "; the residual is largest at";
    bool on_walls = false;
    for (const MotionFailure::ResidualNode& r : f.largest_residuals) {
      const Vec3& x = result_.failed_points[static_cast<std::size_t>(r.node)];
      const std::string role = role_of(r.node);
      on_walls = on_walls || role.find("sliding") != std::string::npos;
      text += fmt::format("{} node {} at ({:.6g}, {:.6g}, {:.6g}), {} ({:.3g})", &r == &f.largest_residuals.front() ? "" : ",",
                          mesh_.node_id(r.node), x.x, x.y, x.z, role, r.residual);
    }
    text += on_walls ? ". A sliding wall may turn sharply there between its nodes, or fold: look at the deflection "
                       "table there (its degree, a missing FEM node on a corner), or split the patch where it turns; "
                       "more increments (solver.increments) help a large motion"
                     : ". Try more increments (solver.increments), or a looser solver.newton_tolerance";
    return text;
  }

  /// "sliding on 'floor'", "sliding where 'floor' meets 'outlet'", "interior", ...: what moves
  /// node n, and the patches it lies on.
  std::string role_of(NodeId n) const {
    std::vector<std::string> patches;
    for (const Patch& p : mesh_.patches) {
      if (std::find(p.nodes.begin(), p.nodes.end(), n) != p.nodes.end()) patches.push_back("'" + p.name + "'");
    }
    const NodeRoleCode code = setup_.roles[static_cast<std::size_t>(n)];
    if (code == kInteriorNodeCode) return "interior";
    const std::string role(to_string(role_of_node_code(code)));
    const auto sliding = std::find_if(setup_.sliding.begin(), setup_.sliding.end(),
                                      [n](const detail::SlidingNode& s) { return s.node == n; });
    const bool on_corner_line = sliding != setup_.sliding.end() && std::any_of(setup_.corner_paths.begin(), setup_.corner_paths.end(), [&](const auto& path) {
                                  return path.get() == sliding->shapes[0];
                                });
    if (on_corner_line) return fmt::format("{} along a corner of {}", role, fmt::join(patches, ", "));
    if (patches.size() > 1) return fmt::format("{} where {} meet", role, fmt::join(patches, " and "));
    return fmt::format("{} on {}", role, fmt::join(patches, ", "));
  }

  /// The state to resume from after an accepted step, `pieces` those of a split increment left.
  MotionCheckpoint checkpoint(const std::deque<MotionStep>& pieces, double seconds) const {
    MotionCheckpoint c;
    c.increments = increments();
    c.finished_increments = finished_increments_;
    c.lambda = result_.lambda_reached;
    c.split_pieces.assign(pieces.begin(), pieces.end());
    c.points = result_.points;
    c.previous_points = previous_points_;
    c.previous_lambda = previous_stage_;
    c.sliding.reserve(setup_.sliding.size());
    for (const detail::SlidingNode& s : setup_.sliding) c.sliding.push_back({s.node, s.target, s.hints});
    c.records = result_.increments;
    c.timings = result_.timings;
    c.timings.total = seconds + setup_seconds_ + earlier_seconds_;
    return c;
  }

  /// Takes up an interrupted run where its checkpoint left it.
  void restore(const MotionCheckpoint& c) {
    const auto refuse = [](const std::string& what) {
      throw InputError("the checkpoint does not fit this run: " + what);
    };
    if (c.increments != increments()) {
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
    if (c.finished_increments < 0 || c.finished_increments > c.increments) refuse("its increments done are damaged");
    for (const MotionStep& step : c.split_pieces) {
      if (!(step.lambda_begin >= 0.0 && step.lambda_begin < step.lambda_end && step.lambda_end <= 1.0) ||
          step.increment != c.finished_increments + 1 || step.split_depth < 1) {
        refuse("its steps left are damaged");
      }
    }
    if (!c.previous_points.empty() &&
        (c.previous_points.size() != c.points.size() || !(c.previous_lambda >= 0.0 && c.previous_lambda < c.lambda))) {
      refuse("its previous mesh is damaged");
    }
    result_.points = c.points;
    previous_points_ = c.previous_points;
    previous_stage_ = c.previous_lambda;
    result_.lambda_reached = c.lambda;
    result_.increments = c.records;
    finished_increments_ = c.finished_increments;
    result_.timings = c.timings;  // the interrupted run's, this run's added as they come
    result_.timings.setup += setup_seconds_;
    earlier_seconds_ = c.timings.total;
  }

  /// The residual ||D^-1 R|| (a length) that rounding alone leaves in a mesh of this size at
  /// rest: an increment with nothing to move (zero deflection on a curved sliding wall) starts
  /// there, and no relative reduction of it can be asked for.
  double round_off_residual(std::size_t dofs) const {
    return 64.0 * std::numeric_limits<double>::epsilon() * size_ * std::sqrt(static_cast<double>(dofs));
  }

  /// Initial u of an increment from stage a to b: the boundary's move to stage b on prescribed
  /// nodes, the forcing displacement u0s on sliding nodes (eqs. 13, 22), zero elsewhere.
  std::vector<double> initial_displacements(double a, double b) {
    const std::vector<Vec3>& x = result_.points;
    std::vector<double> u(kernel_->size(), 0.0);
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
    const auto t = Clock::now();
    sliding_.begin_increment(a, b, x, u);
    result_.timings.projection += seconds_since(t);
    setup_.periodic.expand(u);  // slaves follow their masters
    return u;
  }

  /// The predictor of an increment from stage a > 0 to b (SolverOptions::predictor): every
  /// interior, periodic and sliding node goes on along the secant of the last accepted step,
  /// from the mesh x' at its start a' to x at a, as the boundary's prescribed motion goes on:
  /// u = (b - a)/(a - a') (x - x'); before the first, x' = x_ref at stage 0. The sliding nodes
  /// are then placed on c_b (4.2). Returns u as it was without the prediction, or nothing when
  /// there is nothing to predict or the prediction would invert a cell.
  std::vector<double> predict(double a, double b, std::vector<double>& u) {
    if (!solver_.predictor || !(a > 0.0) || !(b > a)) return {};
    std::vector<double> start = u;
    const bool secant = !previous_points_.empty() && previous_stage_ < a;
    const std::span<const Vec3> from = secant ? std::span<const Vec3>(previous_points_) : setup_.reference;
    const double scale = (b - a) / (a - (secant ? previous_stage_ : 0.0));
    const std::vector<Vec3>& x = result_.points;
    const auto t = Clock::now();
    for (std::size_t i = 0; i < x.size(); ++i) {
      const NodeRoleCode r = setup_.roles[i];
      if (r != kInteriorNodeCode && r != node_role_code(BoundaryRole::periodic) &&
          r != node_role_code(BoundaryRole::sliding)) {
        continue;
      }
      for (std::size_t c = 0; c < dim_; ++c) u[i * dim_ + c] = scale * (x[i][c] - from[i][c]);
    }
    sliding_.project(b, x, u);
    setup_.periodic.expand(u);  // slaves follow their masters
    result_.timings.projection += seconds_since(t);
    std::vector<Vec3> trial(x.size());
    displace(x, u, trial);
    if (summarize_quality(scaled_jacobians(mesh_.cells, trial)).inverted_cells == 0) return start;
    u = initial_displacements(a, b);  // the sliding nodes' forcing and normals again
    return {};
  }

  /// A converged increment is accepted if no cell of the moved mesh `trial` is inverted.
  void accept_if_valid(const std::vector<Vec3>& trial, std::span<const double> u, IncrementRecord& record) {
    const auto t = Clock::now();
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
    } else if (std::string broken = broken_limits(trial, quality, summary); !broken.empty()) {
      record.failure = std::move(broken);
    } else {
      record.accepted = true;
      sliding_.end_increment(u);
    }
  }

  /// The case's quality limits (SolverOptions::quality) that the mesh `trial` breaks, each with
  /// its cells: how many, the worst and its value; empty if it keeps them all.
  std::string broken_limits(const std::vector<Vec3>& trial, std::span<const double> jacobians,
                            const QualitySummary& summary) {
    const QualityLimits& limits = solver_.quality;
    std::vector<std::string> broken;
    const auto count_beyond = [](std::span<const double> values, auto beyond) {
      return static_cast<std::size_t>(std::count_if(values.begin(), values.end(), beyond));
    };
    if (limits.min_scaled_jacobian > 0.0 && summary.min_scaled_jacobian < limits.min_scaled_jacobian) {
      const double limit = limits.min_scaled_jacobian;
      broken.push_back(fmt::format("{} cells below quality.min_scaled_jacobian {:.3g}, the worst cell {} ({:.3g})",
                                   count_beyond(jacobians, [limit](double q) { return q < limit; }), limit,
                                   mesh_.cell_id(summary.worst_cell), summary.min_scaled_jacobian));
    }
    if (!limits.solver_measures()) return fmt::format("{}", fmt::join(broken, "; "));
    const auto t = Clock::now();
    const mesh::SolverQuality measured = mesh::solver_quality(mesh_, trial, limits.layer);
    result_.timings.quality += seconds_since(t);
    const auto above = [&](const char* name, double limit, const mesh::WorstCell& worst, std::span<const double> per_cell,
                           const char* unit) {
      if (limit <= 0.0 || worst.value <= limit) return;
      broken.push_back(fmt::format("{} cells above quality.{} {:.3g}{}, the worst cell {} ({:.3g}{})",
                                   count_beyond(per_cell, [limit](double v) { return v > limit; }), name, limit, unit,
                                   mesh_.cell_id(worst.cell), worst.value, unit));
    };
    above("max_non_orthogonality", limits.max_non_orthogonality, measured.summary.max_non_orthogonality,
          measured.non_orthogonality, " deg");
    above("max_skewness", limits.max_skewness, measured.summary.max_skewness, measured.skewness, "");
    return fmt::format("{}", fmt::join(broken, "; "));
  }

  /// One increment: Newton-Raphson from the current mesh to stage b. Returns the new points.
  std::vector<Vec3> attempt(const MotionStep& piece, IncrementRecord& record) {
    const auto start = Clock::now();
    const double a = piece.lambda_begin, b = piece.lambda_end;
    record.lambda_begin = a;
    record.lambda_end = b;
    const std::vector<Vec3>& x = result_.points;
    const std::size_t dofs = kernel_->size();

    std::vector<double> u = initial_displacements(a, b);
    std::vector<double> unpredicted = predict(a, b, u);
    std::vector<double> reference_residual(unpredicted.empty() ? 0 : dofs);

    std::vector<Vec3> trial(x.size());
    std::vector<double> r(dofs), node_stiffness(dofs / dim_);
    double r0 = 0.0, previous = 0.0;
    // Whether this step's element pass assembles the solver's matrix too (amg, direct, icc): not when
    // the residual will likely end the loop (the solve assembles it if not).
    bool matrix_wanted = true;
    linear_->begin_increment();
    detail::Forcing forcing(solver_);
    for (int it = 0;; ++it) {
      displace(x, u, trial);
      // K(n) at the current geometry (eq. 8) and R(n) = K(n) u(n) - f (eq. 7; f is K's action on
      // the boundary motion), with only its tangential part F_t at sliding nodes (eq. 17).
      const detail::ConstrainedSystem system{*kernel_, setup_.constraints, setup_.periodic, trial, node_stiffness};
      const bool referenced = it == 0 && !unpredicted.empty();
      const detail::ReferenceResidual reference{unpredicted, reference_residual};
      detail::newton_residual(system, blocks_ ? &*blocks_ : nullptr, linear_->assembler(), ranks_, u, r, node_stiffness,
                              result_.timings, referenced ? &reference : nullptr, matrix_wanted);
      const double residual = detail::scaled_residual_norm(r, node_stiffness, dim_);
      // The tolerance is relative to the residual of the increment's start without the
      // predictor, so that a good prediction does not tighten it.
      if (it == 0) {
        r0 = referenced ? detail::scaled_residual_norm(reference_residual, node_stiffness, dim_) : residual;
        // Needed no more: given back before the solves (two vectors the mesh's size).
        std::vector<double>().swap(unpredicted);
        std::vector<double>().swap(reference_residual);
      }
      record.newton.push_back({residual, 0, true, 0.0});
      record.residual_reduction = r0 > 0.0 ? residual / r0 : 0.0;
      if (it > 0 && observers_.newton) report_step(piece, record, it, seconds_since(start));
      if (!std::isfinite(residual) || residual > kDivergence * r0) {
        record.failure = fmt::format("the Newton-Raphson cycle diverged (residual {:.3g} times the initial one)",
                                     residual / r0);
        note_failure(MotionFailure::Kind::newton_diverged, r, node_stiffness);
        break;
      }
      if (residual <= solver_.newton_tolerance * r0 || residual <= round_off_residual(dofs)) {
        record.converged = true;
        break;
      }
      if (it == solver_.max_newton_iterations) {
        record.failure = fmt::format("the Newton-Raphson cycle did not converge in {} iterations (residual reduced "
                                     "to {:.3g}, tolerance {:.3g})",
                                     solver_.max_newton_iterations, record.residual_reduction, solver_.newton_tolerance);
        note_failure(MotionFailure::Kind::newton_stalled, r, node_stiffness);
        break;
      }
      // K(n) p = -R(n) on the free degrees of freedom, from p = 0 (eq. 8, section 3); at
      // sliding nodes the projected operator solves eq. (16) and keeps p . n = 0 (eq. 19).
      for (double& value : r) value = -value;  // the right-hand side, in place: R is not needed again
      // Its tolerance, and whether it stops on this loop's ||D^-1 r|| or the cheaper ||r||: Forcing.
      const auto target = forcing.next(it, residual, r0);
      const std::span<double> p = r;  // solved in place: p over -R (one vector the mesh's size less)
      const auto solved = linear_->solve(system, r, p, target, result_.timings);
      // The next residual, expected from this solve's tolerance and the last step's reduction.
      const double reduction = std::max(target.tolerance, it > 0 && previous > 0.0 ? residual / previous : 0.0);
      matrix_wanted = reduction * residual > solver_.newton_tolerance * r0;
      previous = residual;
      auto& step = record.newton.back();
      step.pcg_iterations = solved.iterations;
      step.pcg_converged = solved.converged;
      step.pcg_reduction = solved.reduction;
      step.linear_tolerance = target.tolerance;
      step.linear_newton_norm = target.newton_norm;
      if (solved.breakdown) {
        record.failure = "the linear solver broke down (the stiffness is not positive definite on the free nodes)";
        note_failure(MotionFailure::Kind::linear_breakdown);
        break;
      }
      record.max_normal_slip = std::max(record.max_normal_slip, sliding_.normal_component(p));
      axpy(1.0, p, u);
      // Every sliding node back onto the partial boundary c_b, with its new normal (4.2).
      const auto t = Clock::now();
      step.max_projection = sliding_.project(b, x, u);
      result_.timings.projection += seconds_since(t);
      setup_.periodic.expand(u);
    }
    if (record.converged) {
      accept_if_valid(trial, u, record);
      if (!record.accepted) {
        note_failure(record.inverted_cells > 0 ? MotionFailure::Kind::inverted_cells : MotionFailure::Kind::quality_limits);
      }
    }
    record.seconds = seconds_since(start);
    return trial;
  }

  void report_step(const MotionStep& step, const IncrementRecord& record, int it, double seconds) const {
    const NewtonStep& done = record.newton[static_cast<std::size_t>(it - 1)];
    observers_.newton({.step = step,
                       .increments = increments(),
                       .iteration = it,
                       .residual_reduction = record.residual_reduction,
                       .pcg_iterations = done.pcg_iterations,
                       .pcg_converged = done.pcg_converged,
                       .newton_norm = done.linear_newton_norm,
                       .max_projection = done.max_projection,
                       .seconds = seconds});
  }

  void displace(const std::vector<Vec3>& x, std::span<const double> u, std::vector<Vec3>& out) const {
#pragma omp parallel for schedule(dynamic, mesh::kChunkNodes) if (static_cast<std::ptrdiff_t>(x.size()) >= mesh::kParallelNodes)
    for (std::ptrdiff_t n = 0; n < static_cast<std::ptrdiff_t>(x.size()); ++n) {
      const auto i = static_cast<std::size_t>(n);
      Vec3 p = x[i];
      for (std::size_t c = 0; c < dim_; ++c) p[c] += u[i * dim_ + c];
      out[i] = p;
    }
  }

  const Mesh& mesh_;
  SolverOptions solver_;
  const MotionObservers& observers_;
  detail::BoundarySetup setup_;
  detail::SlidingNodes sliding_;
  const parallel::RankExchange& ranks_;
  std::shared_ptr<const StiffnessKernel> kernel_;  ///< K_e of any cell (eq. 35 and the Q1 element)
  std::optional<StiffnessOperator> blocks_;         ///< K of each Newton step in node blocks (jacobi-pcg)
  std::unique_ptr<detail::LinearSolver> linear_;
  std::size_t dim_;
  double size_;
  int finished_increments_ = 0;
  double setup_seconds_ = 0.0;    ///< of this run
  double earlier_seconds_ = 0.0;  ///< total of the interrupted run this one resumes
  std::vector<Vec3> previous_points_;  ///< the mesh at the start of the last accepted step (predict())
  double previous_stage_ = 0.0;        ///< its stage
  MotionFailure failure_;              ///< of the last attempt that failed
  MotionResult result_;
};

}  // namespace

namespace {

/// Increments of the corner pass: its nodes move at most half a wall edge along their walls.
constexpr int kCornerPassIncrements = 2;

/// A wall at its fully deflected stage for every lambda: the walls of the corner pass, which
/// starts where the motion ended and moves nothing but the nodes given corners.
class FinalStage final : public geometry::BoundaryShape {
 public:
  explicit FinalStage(std::shared_ptr<const geometry::BoundaryShape> shape) : shape_(std::move(shape)) {}
  geometry::ShapePoint project(const Vec3& p, double /*lambda*/, const geometry::ShapeParameter& hint,
                               const geometry::ParameterRange& range) const override {
    return shape_->project(p, 1.0, hint, range);
  }
  geometry::ShapePoint at(const geometry::ShapeParameter& where, double /*lambda*/, const Vec3& reference) const override {
    return shape_->at(where, 1.0, reference);
  }
  std::vector<geometry::ShapeFeature> features(double min_angle) const override { return shape_->features(min_angle); }
  std::vector<std::shared_ptr<const geometry::BoundaryShape>> crease_sides(const geometry::ShapeParameter& where,
                                                                         double min_angle) const override {
    auto sides = shape_->crease_sides(where, min_angle);
    for (auto& side : sides) side = std::make_shared<const FinalStage>(std::move(side));
    return sides;
  }
  std::vector<geometry::ShapeCrease> creases(double min_angle) const override { return shape_->creases(min_angle); }
  int crease_region(int face, double min_angle) const override { return shape_->crease_region(face, min_angle); }
  geometry::CreasePoint crease_point(const geometry::ShapeCrease& crease, const Vec3& p,
                                     double /*lambda*/) const override {
    return shape_->crease_point(crease, p, 1.0);
  }

 private:
  std::shared_ptr<const geometry::BoundaryShape> shape_;
};

/// Whether a sliding wall has corners (or creases) for nodes to hold.
bool has_corners(std::span<const PatchMotion> patches) {
  return std::any_of(patches.begin(), patches.end(), [](const PatchMotion& m) {
    return m.role == BoundaryRole::sliding && m.features.enabled && m.shape &&
           (!m.shape->features(m.features.angle).empty() ||
            !m.shape->creases(m.features.angle).empty());
  });
}

MotionResult with_corner_pass(const Mesh& mesh, MotionResult moved, MotionResult pass);

/// The corner pass is kept only if its worst cell, after the repair, keeps at least this share
/// of the motion's worst: holding corners must not ruin the mesh it sharpens.
constexpr double kPassKeepsQuality = 0.5;

/// Sweeps of the repair after the corner pass (quality_repair.hpp), at most.
constexpr int kRepairSweeps = 50;

/// The pass must not cost quality: where it left cells below the motion's worst cell
/// (`motion`), the interior nodes of those cells are moved to restore it (quality_repair.hpp).
void restore_worst_cell(const Mesh& mesh, const QualitySummary& motion, MotionResult& pass) {
  std::vector<char> interior(pass.node_roles.size());
  std::transform(pass.node_roles.begin(), pass.node_roles.end(), interior.begin(),
                 [](NodeRoleCode role) { return role == kInteriorNodeCode ? 1 : 0; });
  const detail::QualityRepair r =
      detail::repair_cells_below(mesh, pass.points, interior, motion.min_scaled_jacobian, kRepairSweeps);
  pass.corner_repair = {r.cells_below, r.nodes_moved, r.min_before, r.min_after};
  pass.quality = scaled_jacobians(mesh.cells, pass.points);
  pass.summary = summarize_quality(pass.quality);
}

/// The nodes of the walls that move: the prescribed and sliding patches (for the stiffening by
/// distance to them, MaterialOptions::wall_distance_exponent).
std::vector<NodeId> moving_wall_nodes(const Mesh& mesh, std::span<const PatchMotion> patches) {
  std::vector<NodeId> nodes;
  for (const PatchMotion& m : patches) {
    if (!follows_shape(m.role)) continue;
    if (const mesh::Patch* patch = mesh.find_patch(m.patch)) nodes.insert(nodes.end(), patch->nodes.begin(), patch->nodes.end());
  }
  return nodes;
}

/// The corner pass after a successful motion `moved` (issue 20, beyond the paper): each corner
/// of a sliding wall is given the node nearest it, which moves onto it; the other sliding
/// nodes keep to their segments between corners. Run after the motion, not through it, so
/// that nodes still gather where the wall needs them (on a ramp, across its corners): corners
/// held from the start would freeze the number of nodes between them. If the pass fails, the
/// mesh of the motion stands, with a note.
///
/// The pass is an elastic problem of its own whose original mesh is the motion's result, so
/// eq. (35)'s measures |phi_s|, |phi_v| are taken there (`motion_kernel` with new Lamé
/// parameters): the cells the motion sheared stiffen and take less of the corners' moves
/// (ramp: worst cell 0.512 against 0.496 with the measures of the undeformed mesh).
MotionResult hold_corners(const Mesh& mesh, std::span<const PatchMotion> patches,
                          const StiffnessKernel& motion_kernel, const MaterialOptions& material,
                          const SolverOptions& solver, const MotionObservers& observers,
                          const parallel::RankExchange& ranks, MotionResult moved) {
  std::vector<PatchMotion> final_walls(patches.begin(), patches.end());
  for (PatchMotion& m : final_walls) {
    if (m.shape) m.shape = std::make_shared<const FinalStage>(m.shape);
  }
  const int n = std::max(solver.increments, 1);
  SolverOptions pass_options = solver;
  pass_options.increments = kCornerPassIncrements;
  // Its increments follow the motion's, N + 1 ..., at stage 1; no checkpoints (a resumed run
  // repeats the pass from the motion's last checkpoint).
  const auto as_corner_pass = [n](IncrementRecord r) {
    r.increment += n;
    r.lambda_begin = r.lambda_end = 1.0;
    r.corner_pass = true;
    return r;
  };
  MotionObservers pass_observers;
  if (observers.increment) {
    pass_observers.increment = [&](const IncrementRecord& r) { observers.increment(as_corner_pass(r)); };
  }
  if (observers.newton) {
    pass_observers.newton = [&](NewtonProgress p) {
      p.step.increment += n;
      p.step.lambda_begin = p.step.lambda_end = 1.0;
      p.increments = n + kCornerPassIncrements;
      observers.newton(p);
    };
  }
  const MotionStart from{moved.points, moved.sliding_origins};
  const auto begin = Clock::now();
  auto kernel = std::make_shared<const StiffnessKernel>(
      motion_kernel.with_lame(element_lame(mesh, moved.points, material, moving_wall_nodes(mesh, patches))));
  std::optional<Motion> motion;
  try {  // the motion's mesh as the pass's input: a node it left off its walls is no user error now
    motion.emplace(mesh, final_walls, std::move(kernel), pass_options, pass_observers, &from, ranks);
  } catch (const InputError& e) {
    moved.notes.push_back(fmt::format("the corners of the sliding walls could not be given nodes ({}); the mesh is the "
                                      "one the motion gave, whose walls may cut them",
                                      e.what()));
    return moved;
  }
  motion->set_setup_time(seconds_since(begin));
  MotionResult pass = motion->run(nullptr);

  for (const IncrementRecord& r : pass.increments) moved.increments.push_back(as_corner_pass(r));
  return with_corner_pass(mesh, std::move(moved), std::move(pass));
}

/// The motion's result `moved` with the corner pass's `pass` after it: its times added, and,
/// if it succeeded, its mesh, quality and corners.
MotionResult with_corner_pass(const Mesh& mesh, MotionResult moved, MotionResult pass) {
  MotionTimings& t = moved.timings;
  t.setup += pass.timings.setup;
  t.assembly += pass.timings.assembly;
  t.preconditioner += pass.timings.preconditioner;
  t.solve += pass.timings.solve;
  t.projection += pass.timings.projection;
  t.quality += pass.timings.quality;
  t.total += pass.timings.total;
  if (!pass.success) {
    moved.notes.push_back("the corners of the sliding walls could not be given nodes (" + pass.message +
                          "); the mesh is the one the motion gave, whose walls may cut them");
    return moved;
  }
  for (std::string& note : pass.notes) {  // the setup's notes on the walls are the motion's too
    if (std::find(moved.notes.begin(), moved.notes.end(), note) == moved.notes.end()) {
      moved.notes.push_back(std::move(note));
    }
  }
  // The pass's walls are the fully deflected ones at every stage: a feature's turn on the
  // undeformed wall is the motion's measure.
  for (WallFeature& f : pass.features) {
    const auto same = std::find_if(moved.features.begin(), moved.features.end(), [&](const WallFeature& m) {
      return m.patch == f.patch && m.faces == f.faces && m.parameter == f.parameter;
    });
    if (same != moved.features.end()) f.angle = std::max(f.angle, same->angle);
  }
  if (pass.summary.min_scaled_jacobian < moved.summary.min_scaled_jacobian) restore_worst_cell(mesh, moved.summary, pass);
  if (pass.summary.min_scaled_jacobian < kPassKeepsQuality * moved.summary.min_scaled_jacobian) {
    moved.notes.push_back(fmt::format(
        "the corner pass was undone: holding the corners of the sliding walls would leave cell {} at a scaled "
        "Jacobian of {:.3g}, against the motion's worst {:.3g} (corners within a cell of each other: a deflection "
        "table without a node on a corner of the wall cuts it with kinks of its own; give it a node there, or take "
        "form: displacement); the mesh is the one the motion gave, whose walls may cut the corners it did not hold",
        mesh.cell_id(pass.summary.worst_cell), pass.summary.min_scaled_jacobian, moved.summary.min_scaled_jacobian));
    return moved;
  }
  moved.corner_repair = pass.corner_repair;
  moved.restart_points = std::exchange(moved.points, std::move(pass.points));
  moved.quality = std::move(pass.quality);
  moved.summary = pass.summary;
  moved.features = std::move(pass.features);
  moved.max_periodic_mismatch = pass.max_periodic_mismatch;
  moved.max_projection_distance = std::max(moved.max_projection_distance, pass.max_projection_distance);
  moved.final_projection_distance = pass.final_projection_distance;
  moved.max_normal_slip = std::max(moved.max_normal_slip, pass.max_normal_slip);
  return moved;
}

}  // namespace

LinearSolverChoice choose_linear_solver(const Mesh& mesh, std::span<const PatchMotion> patches, int processes) {
  const bool sliding = std::any_of(patches.begin(), patches.end(), [](const PatchMotion& m) { return m.role == BoundaryRole::sliding; });
  return choose_linear_solver(mesh.dimension, mesh.cell_count(), sliding, processes);
}

MotionResult move_mesh(const Mesh& mesh, std::span<const PatchMotion> patches, const MaterialOptions& material,
                       const SolverOptions& options, const MotionObservers& observers, const MotionStart* start,
                       const MotionCheckpoint* resume, const parallel::RankExchange& ranks) {
  const auto begin = Clock::now();
  SolverOptions solver = options;
  if (solver.linear == LinearSolverKind::automatic) solver.linear = choose_linear_solver(mesh, patches, ranks.ranks()).kind;
  require_motion_cells(mesh);  // before eq. (35), which would measure the other cell types
  const bool corners = has_corners(patches);
  std::vector<PatchMotion> sliding_freely(patches.begin(), patches.end());
  for (PatchMotion& m : sliding_freely) m.features.enabled = false;  // corners and creases on nodes stay held
  auto kernel = std::make_shared<const StiffnessKernel>(mesh, element_lame(mesh, material, moving_wall_nodes(mesh, patches)),
                                                        material.drop_jacobian);
  Motion motion(mesh, sliding_freely, kernel, solver, observers, start, ranks);
  motion.set_setup_time(seconds_since(begin));
  MotionResult result = motion.run(resume);
  if (!corners || !result.success) return result;
  return hold_corners(mesh, patches, *kernel, material, solver, observers, ranks, std::move(result));
}

}  // namespace hotmesh::deform
