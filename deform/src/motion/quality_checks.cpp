// hotmesh deform: whether a converged increment is accepted (motion.hpp): no cell inverted, and
// the case's quality limits kept (SolverOptions::quality).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <string>
#include <vector>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/solver_quality.hpp"
#include "motion/motion.hpp"
#include "hotmesh/core/clock.hpp"

namespace hotmesh::deform::detail {

namespace {

/// The quality step moves no cell below min(its node's worst cell, this or the mesh's worst if
/// higher): cells pushed down to a low worst cell invert in the next increment (the ramp).
constexpr double kSmoothingJacobianFloor = 0.5;

/// Orthonormal directions completing `normals` (orthonormal) to a basis of the first `dim` axes.
MovableNode free_directions(NodeId n, std::span<const Vec3> normals, int dim) {
  MovableNode node{n};
  for (int axis = 0; axis < dim && node.count + static_cast<int>(normals.size()) < dim; ++axis) {
    Vec3 e{};
    e[static_cast<std::size_t>(axis)] = 1.0;
    for (const Vec3& v : normals) e = e - dot(e, v) * v;
    for (int k = 0; k < node.count; ++k) e = e - dot(e, node.directions[static_cast<std::size_t>(k)]) * node.directions[static_cast<std::size_t>(k)];
    const double length = norm(e);
    if (length > 0.5) node.directions[static_cast<std::size_t>(node.count++)] = e / length;
  }
  return node;
}

}  // namespace

/// The quality step (quality_step.hpp) on a converged increment's mesh: the interior nodes in
/// every direction, the nodes of slip patches along their planes.
void Motion::smooth_for_solver(std::vector<Vec3>& trial, IncrementRecord& record) {
  const auto t = Clock::now();
  if (movable_.empty()) {
    const int dim = mesh_.dimension;
    const auto slip = node_role_code(BoundaryRole::slip);
    for (std::size_t n = 0; n < mesh_.node_count(); ++n) {
      const NodeRoleCode role = setup_.roles[n];
      const auto id = static_cast<NodeId>(n);
      if ((role != kInteriorNodeCode && role != slip) || setup_.constraints.is_fixed(id)) continue;
      MovableNode node = free_directions(id, setup_.constraints.normals(id), dim);
      if (node.count > 0) movable_.push_back(node);
    }
  }
  const double floor =
      std::max(summarize_quality(scaled_jacobians(mesh_.cells, trial)).min_scaled_jacobian, kSmoothingJacobianFloor);
  const mesh::SolverFaces faces(mesh_, trial, solver_.quality.layer);
  const QualityStepResult r = improve_for_solver(mesh_, faces, trial, movable_, floor);
  record.smoothed_nodes = r.nodes_moved;
  result_.timings.quality += seconds_since(t);
}

/// A converged increment is accepted if no cell of the moved mesh `trial` is inverted.
void Motion::accept_if_valid(const std::vector<Vec3>& trial, std::span<const double> u, IncrementRecord& record) {
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
std::string Motion::broken_limits(const std::vector<Vec3>& trial, std::span<const double> jacobians,
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

}  // namespace hotmesh::deform::detail
