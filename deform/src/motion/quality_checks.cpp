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
