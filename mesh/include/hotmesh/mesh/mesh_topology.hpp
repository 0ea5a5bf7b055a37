// hotmesh mesh: faces of cells and how they meet. Faces are matched by their node sets
// through an index that buckets every cell face under its smallest node (a CSR array, one
// pass to count and one to fill): memory is one CellFace per cell face, and a lookup
// compares a face with the handful of faces sharing its smallest node.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::mesh {

/// Face `local` (an index into faces(type)) of cell `cell`.
struct CellFace {
  CellId cell = 0;
  std::int32_t local = 0;
  friend bool operator==(const CellFace&, const CellFace&) = default;
};

/// The nodes of a face in its outward orientation.
struct FaceNodes {
  int count = 0;
  std::array<NodeId, kMaxFaceNodes> nodes{};
  std::span<const NodeId> view() const { return {nodes.data(), static_cast<std::size_t>(count)}; }
};
FaceNodes face_nodes(const ElementList& cells, CellFace face);

/// True if a and b hold the same nodes, in any order.
bool same_node_set(std::span<const NodeId> a, std::span<const NodeId> b);
/// For faces with the same node set: true if they are traversed in opposite directions, as
/// the common face of two consistently oriented neighbouring cells must be.
bool opposite_orientation(std::span<const NodeId> a, std::span<const NodeId> b);

class FaceIndex {
 public:
  FaceIndex(const ElementList& cells, std::size_t node_count);

  /// Every cell face whose node set equals `face`.
  std::vector<CellFace> find(std::span<const NodeId> face) const;
  /// The cell faces filed under node n (those whose smallest node is n).
  std::span<const CellFace> bucket(NodeId n) const {
    const auto i = static_cast<std::size_t>(n);
    return {faces_.data() + offsets_[i], faces_.data() + offsets_[i + 1]};
  }
  std::size_t node_count() const { return offsets_.size() - 1; }
  const ElementList& cells() const { return *cells_; }

 private:
  const ElementList* cells_;
  std::vector<std::int64_t> offsets_;
  std::vector<CellFace> faces_;
};

/// What the faces of a mesh look like: the faces on the boundary (belonging to one cell), and
/// any face where the cells are not a consistently oriented manifold.
struct FaceTopology {
  std::vector<CellFace> boundary;
  std::vector<CellFace> non_manifold;   ///< shared by more than two cells (first of them)
  std::vector<CellFace> inconsistent;   ///< two cells traverse it the same way (one of them)
};
FaceTopology face_topology(const FaceIndex& index);

}  // namespace hotmesh::mesh
