// hotmesh deform: sliding nodes across an increment (section 4, eqs. 13-22).
#include "sliding.hpp"

#include <algorithm>
#include <cmath>

#include "parallel.hpp"

namespace hotmesh::deform::detail {

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

  const double share = (b - a) / (1.0 - a);  // 1 / (N - k + 1) for equal increments (eq. 22)
#pragma omp parallel for schedule(dynamic, 64) if (static_cast<std::ptrdiff_t>(nodes.size()) >= kParallelNodes)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(nodes.size()); ++i) {
    const auto k = static_cast<std::size_t>(i);
    SlidingNode& s = nodes[k];
    const Vec3& start = x[static_cast<std::size_t>(s.node)];
    forcing_[k] = share * (s.target - start);
    const Placement p = place_sliding_node(s, start + forcing_[k], b, setup_.slip_planes);
    set_displacement(u, s.node, p.point - start);
    setup_.constraints.set_normals(s.node, {p.normals.data(), static_cast<std::size_t>(p.normal_count)});
  }
}

double SlidingNodes::project(double b, std::span<const Vec3> x, std::span<double> u) {
  auto& nodes = setup_.sliding;
  double largest = 0.0;
#pragma omp parallel for schedule(dynamic, 64) reduction(max : largest) \
    if (static_cast<std::ptrdiff_t>(nodes.size()) >= kParallelNodes)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(nodes.size()); ++i) {
    SlidingNode& s = nodes[static_cast<std::size_t>(i)];
    const Vec3& start = x[static_cast<std::size_t>(s.node)];
    const Vec3 moved = start + displacement(u, s.node);
    const Placement p = place_sliding_node(s, moved, b, setup_.slip_planes);
    largest = std::max(largest, distance(p.point, moved));
    set_displacement(u, s.node, p.point - start);
    setup_.constraints.set_normals(s.node, {p.normals.data(), static_cast<std::size_t>(p.normal_count)});
  }
  return largest;
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
#pragma omp parallel for schedule(dynamic, 64) if (static_cast<std::ptrdiff_t>(nodes.size()) >= kParallelNodes)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(nodes.size()); ++i) {
    const auto k = static_cast<std::size_t>(i);
    SlidingNode& s = nodes[k];
    // Section 4.3: the slide vector a = dx2 - dx1 moves the target, which is projected on the
    // boundary of the complete deformation.
    const Vec3 a = displacement(u, s.node) - forcing_[k];
    s.target = place_sliding_node(s, s.target + a, 1.0, setup_.slip_planes).point;
  }
}

}  // namespace hotmesh::deform::detail
