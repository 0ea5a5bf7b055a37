// hotmesh deform: where an increment's Newton cycle starts (motion.hpp): the boundary's move,
// the sliding nodes' forcing (eqs. 13, 22), and the predictor along the last step's secant.
#include <span>
#include <vector>

#include "hotmesh/mesh/quality.hpp"
#include "motion/increment_system.hpp"
#include "motion/motion.hpp"
#include "hotmesh/core/clock.hpp"

namespace hotmesh::deform::detail {

/// Initial u of an increment from stage a to b: the boundary's move to stage b on prescribed
/// nodes, the forcing displacement u0s on sliding nodes (eqs. 13, 22), zero elsewhere.
std::vector<double> Motion::initial_displacements(double a, double b) {
  const std::vector<Vec3>& x = result_.points;
  std::vector<double> u(kernel_->size(), 0.0);
  for (const auto& p : setup_.prescribed) {
    const auto i = static_cast<std::size_t>(p.node);
    const Vec3 target = prescribed_position(p, setup_.reference[i], b);
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
std::vector<double> Motion::predict(double a, double b, std::vector<double>& u) {
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
  displace(x, u, dim_, trial);
  if (summarize_quality(scaled_jacobians(mesh_.cells, trial)).inverted_cells == 0) return start;
  u = initial_displacements(a, b);  // the sliding nodes' forcing and normals again
  return {};
}

}  // namespace hotmesh::deform::detail
