// hotmesh deform: nodal constraints and their projection.
#include "hotmesh/deform/constraints.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

#include <algorithm>
#include <cmath>

namespace hotmesh::deform {

NodeConstraints::NodeConstraints(std::size_t nodes, int dimension) : dim_(dimension), state_(nodes, kFree) {}

void NodeConstraints::fix(NodeId n) {
  auto& s = state_[static_cast<std::size_t>(n)];
  if (s == kFixed) return;
  if (s >= 0) partial_[static_cast<std::size_t>(s)].count = 0;  // stays in the list, inert
  s = kFixed;
  fixed_.push_back(n);
}

void NodeConstraints::constrain(NodeId n, const Vec3& normal) {
  auto& s = state_[static_cast<std::size_t>(n)];
  if (s == kFixed) return;
  Vec3 v = normal;
  if (dim_ == 2) v.z = 0.0;
  const double length = norm(v);
  if (!(length > 0.0)) return;
  v = v / length;
  if (s == kFree) {
    s = static_cast<std::int32_t>(partial_.size());
    partial_.push_back({n, 0, {}});
  }
  Partial& p = partial_[static_cast<std::size_t>(s)];
  for (int k = 0; k < p.count; ++k) v -= dot(v, p.normals[static_cast<std::size_t>(k)]) * p.normals[static_cast<std::size_t>(k)];
  const double rest = norm(v);
  if (rest < 1e-8) return;  // already constrained in this direction
  if (p.count + 1 >= dim_) {
    fix(n);
    return;
  }
  p.normals[static_cast<std::size_t>(p.count++)] = v / rest;
}

void NodeConstraints::track(NodeId n) {
  auto& s = state_[static_cast<std::size_t>(n)];
  if (s != kFree) return;
  s = static_cast<std::int32_t>(partial_.size());
  partial_.push_back({n, 0, {}});
}

void NodeConstraints::set_normals(NodeId n, std::span<const Vec3> normals) {
  const auto s = state_[static_cast<std::size_t>(n)];
  if (s < 0) return;  // fixed (or not tracked)
  Partial& p = partial_[static_cast<std::size_t>(s)];
  p.count = 0;
  for (Vec3 v : normals) {
    if (p.count + 1 >= dim_) break;
    if (dim_ == 2) v.z = 0.0;
    for (int k = 0; k < p.count; ++k) v -= dot(v, p.normals[static_cast<std::size_t>(k)]) * p.normals[static_cast<std::size_t>(k)];
    const double length = norm(v);
    if (length < 1e-8) continue;
    p.normals[static_cast<std::size_t>(p.count++)] = v / length;
  }
}

void NodeConstraints::release(NodeId n) {
  const auto s = state_[static_cast<std::size_t>(n)];
  if (s >= 0) partial_[static_cast<std::size_t>(s)].count = 0;
}

int NodeConstraints::constrained_directions(NodeId n) const {
  const auto s = state_[static_cast<std::size_t>(n)];
  if (s == kFixed) return dim_;
  return s >= 0 ? partial_[static_cast<std::size_t>(s)].count : 0;
}

std::span<const Vec3> NodeConstraints::normals(NodeId n) const {
  const auto s = state_[static_cast<std::size_t>(n)];
  if (s < 0) return {};
  const Partial& p = partial_[static_cast<std::size_t>(s)];
  return {p.normals.data(), static_cast<std::size_t>(p.count)};
}

void NodeConstraints::project(std::span<double> v) const {
  const auto d = static_cast<std::size_t>(dim_);
#pragma omp parallel for schedule(dynamic, mesh::kChunkNodes) if (static_cast<std::ptrdiff_t>(fixed_.size()) >= mesh::kParallelNodes)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(fixed_.size()); ++k) {
    const auto base = static_cast<std::size_t>(fixed_[static_cast<std::size_t>(k)]) * d;
    for (std::size_t i = 0; i < d; ++i) v[base + i] = 0.0;
  }
#pragma omp parallel for schedule(dynamic, mesh::kChunkNodes) if (static_cast<std::ptrdiff_t>(partial_.size()) >= mesh::kParallelNodes)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(partial_.size()); ++k) {
    const Partial& p = partial_[static_cast<std::size_t>(k)];
    const auto base = static_cast<std::size_t>(p.node) * d;
    for (int m = 0; m < p.count; ++m) {
      const Vec3& n = p.normals[static_cast<std::size_t>(m)];
      double vn = 0.0;
      for (std::size_t i = 0; i < d; ++i) vn += v[base + i] * n[i];
      for (std::size_t i = 0; i < d; ++i) v[base + i] -= vn * n[i];
    }
  }
}

std::size_t NodeConstraints::free_dofs() const {
  std::size_t constrained = fixed_.size() * static_cast<std::size_t>(dim_);
  for (const Partial& p : partial_) constrained += static_cast<std::size_t>(p.count);
  return state_.size() * static_cast<std::size_t>(dim_) - constrained;
}

}  // namespace hotmesh::deform
