// hotmesh deform: sliding nodes onto their walls (Fig. 4), and across an increment (section 4,
// eqs. 13-22) with the passive surfaces their rims carry.
#include "constraints/sliding.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "constraints/boundary_conditions.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform::detail {

Placement place_sliding_node(SlidingNode& node, const Vec3& p, double lambda, std::span<const SlipPlane> planes) {
  Placement out;
  out.point = p;
  // One pass for a single wall; where walls meet, alternate projections converge on their
  // intersection (for walls that are not tangent there).
  const int passes = node.shape_count + node.plane_count > 1 ? 8 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    out.normal_count = 0;
    for (int s = 0; s < node.shape_count; ++s) {
      const auto i = static_cast<std::size_t>(s);
      const geometry::ShapePoint q = node.shapes[i]->project(out.point, lambda, node.hints[i], node.segments[i]);
      node.hints[i] = q.parameter;
      out.point = q.point;
      out.normals[static_cast<std::size_t>(out.normal_count++)] = q.normal;
    }
    for (int k = 0; k < node.plane_count; ++k) {
      const SlipPlane& plane = planes[static_cast<std::size_t>(node.planes[static_cast<std::size_t>(k)])];
      out.point -= dot(out.point - plane.origin, plane.normal) * plane.normal;
      out.normals[static_cast<std::size_t>(out.normal_count++)] = plane.normal;
    }
  }
  return out;
}

void follow_sliding_rims(const BoundarySetup& setup, std::span<const Vec3> x, std::span<double> u) {
  if (setup.following.empty()) return;
  const auto d = static_cast<std::size_t>(setup.constraints.dimension());
  const auto moved = [&](NodeId n) -> std::optional<Vec3> {
    const auto i = static_cast<std::size_t>(n);
    Vec3 p = x[i] - setup.reference[i];
    for (std::size_t c = 0; c < d; ++c) p[c] += u[i * d + c];
    return p;
  };
  for (const FollowingSurface& f : setup.following) {  // in order: one may be the rim of the next
    const std::vector<Vec3> displacement = f.surface.solve(moved);
    for (const auto& [k, n] : f.nodes) {
      const auto i = static_cast<std::size_t>(n);
      for (std::size_t c = 0; c < d; ++c) u[i * d + c] = setup.reference[i][c] + displacement[k][c] - x[i][c];
    }
  }
}

std::size_t SlidingNodes::size() const { return setup_.sliding.size(); }

Vec3 SlidingNodes::displacement(std::span<const double> u, NodeId n) const {
  Vec3 d;
  const auto base = static_cast<std::size_t>(n) * dim_;
  for (std::size_t c = 0; c < dim_; ++c) d[c] = u[base + c];
  return d;
}

void SlidingNodes::set_displacement(std::span<double> u, NodeId n, const Vec3& d) const {
  const auto base = static_cast<std::size_t>(n) * dim_;
  for (std::size_t c = 0; c < dim_; ++c) u[base + c] = d[c];
}

void SlidingNodes::begin_increment(double a, double b, std::span<const Vec3> x, std::span<double> u) {
  auto& nodes = setup_.sliding;
  forcing_.assign(nodes.size(), {});
  if (!ranks_.alone()) placed_.assign(nodes.size(), {});

  const double share = (b - a) / (1.0 - a);  // 1 / (N - k + 1) for equal increments (eq. 22)
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    forcing_[k] = share * (nodes[k].target - x[static_cast<std::size_t>(nodes[k].node)]);
  }
  place_all(b, x, u, [&](std::size_t k, const Vec3& start) { return start + forcing_[k]; });
}

template <class From>
double SlidingNodes::place_all(double b, std::span<const Vec3> x, std::span<double> u, const From& from) {
  auto& nodes = setup_.sliding;
  double largest = 0.0;
  const parallel::Share mine = ranks_.my_share(nodes.size());
  const auto count = static_cast<std::ptrdiff_t>(mine.end - mine.begin);
  mesh::LoopExceptions errors;  // the projections run behind geometry's BoundaryShape interface
#pragma omp parallel for schedule(dynamic, 64) reduction(max : largest) if (count >= mesh::kParallelProjections)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    errors.run([&] {  // `largest` here is this thread's copy of the reduction
      const auto k = mine.begin + static_cast<std::size_t>(i);
      SlidingNode& s = nodes[k];
      const Vec3& start = x[static_cast<std::size_t>(s.node)];
      const Vec3 moved = from(k, start);
      const Placement p = place_sliding_node(s, moved, b, setup_.slip_planes);
      largest = std::max(largest, distance(p.point, moved));
      set_displacement(u, s.node, p.point - start);
      setup_.constraints.set_normals(s.node, {p.normals.data(), static_cast<std::size_t>(p.normal_count)});
      record(k, p.point - start, p);
    });
  }
  errors.rethrow();
  share_placements(u);
  follow_sliding_rims(setup_, x, u);
  return largest;
}

double SlidingNodes::project(double b, std::span<const Vec3> x, std::span<double> u) {
  const auto& nodes = setup_.sliding;
  const double largest =
      place_all(b, x, u, [&](std::size_t k, const Vec3& start) { return start + displacement(u, nodes[k].node); });
  return ranks_.max(largest);
}

double SlidingNodes::normal_component(std::span<const double> p) const {
  double largest = 0.0;
  for (const SlidingNode& s : setup_.sliding) {
    const Vec3 step = displacement(p, s.node);
    for (const Vec3& normal : setup_.constraints.normals(s.node)) largest = std::max(largest, std::abs(dot(step, normal)));
  }
  return largest;
}

void SlidingNodes::end_increment(std::span<const double> u) {
  auto& nodes = setup_.sliding;
  const parallel::Share mine = ranks_.my_share(nodes.size());
  const auto count = static_cast<std::ptrdiff_t>(mine.end - mine.begin);
  mesh::LoopExceptions errors;
#pragma omp parallel for schedule(dynamic, 64) if (count >= mesh::kParallelProjections)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    errors.run([&] {
      const auto k = mine.begin + static_cast<std::size_t>(i);
      SlidingNode& s = nodes[k];
      // Section 4.3: the slide vector a = dx2 - dx1 moves the target, which is projected on
      // the boundary of the complete deformation.
      const Vec3 a = displacement(u, s.node) - forcing_[k];
      s.target = place_sliding_node(s, s.target + a, 1.0, setup_.slip_planes).point;
    });
  }
  errors.rethrow();
  share_targets();
}

// With several processes each rank placed its share of the nodes; every rank needs them all.

void SlidingNodes::record(std::size_t k, const Vec3& displacement, const Placement& p) {
  if (placed_.empty()) return;
  placed_[k] = {displacement, p.normals, p.normal_count, setup_.sliding[k].hints};
}

void SlidingNodes::share_placements(std::span<double> u) {
  if (placed_.empty()) return;
  auto& nodes = setup_.sliding;
  ranks_.gather_shares(std::span(placed_));
  const parallel::Share mine = ranks_.my_share(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (mine.contains(k)) continue;
    // The placing rank's own results, so that every rank holds the same bits.
    const PlacedNode& placed = placed_[k];
    set_displacement(u, nodes[k].node, placed.displacement);
    setup_.constraints.set_normals(nodes[k].node, {placed.normals.data(), static_cast<std::size_t>(placed.normal_count)});
    nodes[k].hints = placed.hints;
  }
}

void SlidingNodes::share_targets() {
  if (ranks_.alone()) return;
  auto& nodes = setup_.sliding;
  std::vector<MovedTarget> moved(nodes.size());
  const parallel::Share mine = ranks_.my_share(nodes.size());
  for (std::size_t k = mine.begin; k < mine.end; ++k) moved[k] = {nodes[k].target, nodes[k].hints};
  ranks_.gather_shares(std::span(moved));
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    nodes[k].target = moved[k].target;
    nodes[k].hints = moved[k].hints;
  }
}

}  // namespace hotmesh::deform::detail
