#include "hotmesh/deform/mesh.hpp"

#include <algorithm>

namespace hotmesh::deform {

void ElementList::reserve(std::size_t elements, std::size_t nodes) {
  types_.reserve(elements);
  offsets_.reserve(elements + 1);
  nodes_.reserve(nodes);
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

}  // namespace hotmesh::deform
