#include "hotmesh/mesh/mesh_topology.hpp"

#include <algorithm>

namespace hotmesh::mesh {

FaceNodes face_nodes(const ElementList& cells, CellFace face) {
  const auto cell = static_cast<std::size_t>(face.cell);
  const LocalFace& local = faces(cells.type(cell))[static_cast<std::size_t>(face.local)];
  const auto nodes = cells.nodes(cell);
  FaceNodes f;
  f.count = local.count;
  for (int i = 0; i < local.count; ++i) f.nodes[static_cast<std::size_t>(i)] = nodes[local.nodes[static_cast<std::size_t>(i)]];
  return f;
}

bool same_node_set(std::span<const NodeId> a, std::span<const NodeId> b) {
  if (a.size() != b.size()) return false;
  // Faces have distinct nodes, so equal sizes and a in b means equal sets.
  return std::all_of(a.begin(), a.end(), [b](NodeId n) { return std::find(b.begin(), b.end(), n) != b.end(); });
}

bool opposite_orientation(std::span<const NodeId> a, std::span<const NodeId> b) {
  const std::size_t n = a.size();
  if (n == 2) return a[0] == b[1];
  // In a, the node after a[0]; in b, the node before a[0]: equal iff b runs the other way.
  const auto at = static_cast<std::size_t>(std::find(b.begin(), b.end(), a[0]) - b.begin());
  return b[(at + n - 1) % n] == a[1];
}

namespace {
NodeId smallest(std::span<const NodeId> face) { return *std::min_element(face.begin(), face.end()); }
}  // namespace

FaceIndex::FaceIndex(const ElementList& cells, std::size_t node_count)
    : cells_(&cells), offsets_(node_count + 1, 0) {
  const std::size_t n = cells.size();
  // Pass 1: count faces per smallest node; pass 2: fill the buckets.
  for (std::size_t c = 0; c < n; ++c) {
    const auto local = faces(cells.type(c));
    for (std::size_t f = 0; f < local.size(); ++f) {
      const FaceNodes fn = face_nodes(cells, {static_cast<CellId>(c), static_cast<std::int32_t>(f)});
      ++offsets_[static_cast<std::size_t>(smallest(fn.view())) + 1];
    }
  }
  for (std::size_t i = 1; i < offsets_.size(); ++i) offsets_[i] += offsets_[i - 1];
  faces_.resize(static_cast<std::size_t>(offsets_.back()));
  std::vector<std::int64_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t c = 0; c < n; ++c) {
    const auto local = faces(cells.type(c));
    for (std::size_t f = 0; f < local.size(); ++f) {
      const CellFace cf{static_cast<CellId>(c), static_cast<std::int32_t>(f)};
      const auto bucket = static_cast<std::size_t>(smallest(face_nodes(cells, cf).view()));
      faces_[static_cast<std::size_t>(fill[bucket]++)] = cf;
    }
  }
}

std::vector<CellFace> FaceIndex::find(std::span<const NodeId> face) const {
  std::vector<CellFace> found;
  const NodeId low = smallest(face);
  if (low < 0 || static_cast<std::size_t>(low) >= node_count()) return found;
  for (const CellFace& cf : bucket(low)) {
    if (same_node_set(face_nodes(*cells_, cf).view(), face)) found.push_back(cf);
  }
  return found;
}

FaceTopology face_topology(const FaceIndex& index) {
  FaceTopology t;
  const ElementList& cells = index.cells();
  std::vector<FaceNodes> nodes;
  std::vector<char> matched;
  for (std::size_t n = 0; n < index.node_count(); ++n) {
    const auto bucket = index.bucket(static_cast<NodeId>(n));
    nodes.clear();
    for (const CellFace& cf : bucket) nodes.push_back(face_nodes(cells, cf));
    matched.assign(bucket.size(), 0);
    for (std::size_t i = 0; i < bucket.size(); ++i) {
      if (matched[i]) continue;
      std::size_t copies = 1;
      std::size_t partner = i;
      for (std::size_t j = i + 1; j < bucket.size(); ++j) {
        if (!matched[j] && same_node_set(nodes[i].view(), nodes[j].view())) {
          matched[j] = 1;
          partner = j;
          ++copies;
        }
      }
      if (copies == 1) {
        t.boundary.push_back(bucket[i]);
      } else if (copies > 2) {
        t.non_manifold.push_back(bucket[i]);
      } else if (!opposite_orientation(nodes[i].view(), nodes[partner].view())) {
        t.inconsistent.push_back(bucket[i]);
      }
    }
  }
  return t;
}

}  // namespace hotmesh::mesh
