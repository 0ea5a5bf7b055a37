#include "hotmesh/mesh/mesh.hpp"

#include <algorithm>

namespace hotmesh::mesh {

void ElementList::reserve(std::size_t elements, std::size_t nodes) {
  types_.reserve(elements);
  offsets_.reserve(elements + 1);
  nodes_.reserve(nodes);
}

void ElementList::shrink_to_fit() {
  types_.shrink_to_fit();
  offsets_.shrink_to_fit();
  nodes_.shrink_to_fit();
}

void ElementList::add(ElementType type, std::span<const NodeId> nodes) {
  types_.push_back(type);
  nodes_.insert(nodes_.end(), nodes.begin(), nodes.end());
  offsets_.push_back(static_cast<std::int64_t>(nodes_.size()));
}

const Patch* Mesh::find_patch(std::string_view patch_name) const {
  for (const Patch& p : patches) {
    if (p.name == patch_name) return &p;
  }
  return nullptr;
}

void Mesh::derive_node_sets() {
  for (Patch& patch : patches) {
    auto all = patch.faces.all_nodes();
    patch.nodes.assign(all.begin(), all.end());
    std::sort(patch.nodes.begin(), patch.nodes.end());
    patch.nodes.erase(std::unique(patch.nodes.begin(), patch.nodes.end()), patch.nodes.end());
  }
}

namespace {
template <class PointAt>
double box_diagonal(std::size_t count, PointAt point_at) {
  if (count == 0) return 0.0;
  Vec3 lo = point_at(0), hi = lo;
  for (std::size_t i = 1; i < count; ++i) {
    const Vec3& p = point_at(i);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return norm(hi - lo);
}
}  // namespace

double bounding_diagonal(std::span<const Vec3> points) {
  return box_diagonal(points.size(), [&](std::size_t i) -> const Vec3& { return points[i]; });
}

double bounding_diagonal(std::span<const Vec3> points, std::span<const NodeId> nodes) {
  return box_diagonal(nodes.size(),
                      [&](std::size_t i) -> const Vec3& { return points[static_cast<std::size_t>(nodes[i])]; });
}

}  // namespace hotmesh::mesh
