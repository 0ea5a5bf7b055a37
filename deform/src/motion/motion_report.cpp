// hotmesh deform: what a run's result reports beyond its mesh (motion.hpp): the corners of the
// sliding walls, the maxima over its Newton steps, and where and why a failed run stopped.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "motion/motion.hpp"

namespace hotmesh::deform::detail {

namespace {

/// A failed run names this many nodes where its residual is largest.
constexpr std::size_t kResidualNodesShown = 3;

}  // namespace

/// The corners of the sliding walls and the creases of those made of faces, and how far
/// their nodes are from them at the end.
void Motion::report_corners() {
  for (const WallCorner& c : setup_.corners) {
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
  for (const WallCrease& c : setup_.creases) {
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
void Motion::measure_accepted_steps() {
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

/// What the last attempt ran into, and, where Newton did not converge, the residual
/// ||D^-1 R|| of its last step at each node (from r and the node stiffness k of that step;
/// none where the linear solver broke down or cells inverted).
void Motion::note_failure(MotionFailure::Kind kind, std::span<const double> r, std::span<const double> k) {
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
std::string Motion::where_it_failed() const {
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
std::string Motion::role_of(NodeId n) const {
  std::vector<std::string> patches;
  for (const Patch& p : mesh_.patches) {
    if (std::find(p.nodes.begin(), p.nodes.end(), n) != p.nodes.end()) patches.push_back("'" + p.name + "'");
  }
  const NodeRoleCode code = setup_.roles[static_cast<std::size_t>(n)];
  if (code == kInteriorNodeCode) return "interior";
  const std::string role(to_string(role_of_node_code(code)));
  const auto sliding = std::find_if(setup_.sliding.begin(), setup_.sliding.end(),
                                    [n](const SlidingNode& s) { return s.node == n; });
  const bool on_corner_line = sliding != setup_.sliding.end() && std::any_of(setup_.corner_paths.begin(), setup_.corner_paths.end(), [&](const auto& path) {
                                return path.get() == sliding->shapes[0];
                              });
  if (on_corner_line) return fmt::format("{} along a corner of {}", role, fmt::join(patches, ", "));
  if (patches.size() > 1) return fmt::format("{} where {} meet", role, fmt::join(patches, " and "));
  return fmt::format("{} on {}", role, fmt::join(patches, ", "));
}

}  // namespace hotmesh::deform::detail
