// hotmesh deform: the element kernel over a mesh's cells (StiffnessKernel, stiffness_operator.hpp),
// the cells around each node, and the colouring that lets a colour's cells be added in parallel.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"

namespace hotmesh::deform {

NodeCells::NodeCells(const ElementList& list, std::size_t nodes) : start(nodes + 1, 0) {
  for (NodeId n : list.all_nodes()) ++start[static_cast<std::size_t>(n) + 1];
  for (std::size_t i = 1; i <= nodes; ++i) start[i] += start[i - 1];
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  cells.resize(static_cast<std::size_t>(start.back()));
  for (std::size_t c = 0; c < list.size(); ++c) {
    for (NodeId n : list.nodes(c)) cells[static_cast<std::size_t>(fill[static_cast<std::size_t>(n)]++)] = static_cast<CellId>(c);
  }
}

CellColoring color_cells(const ElementList& cells, std::size_t node_count) {
  const NodeCells around(cells, node_count);
  std::vector<int> color(cells.size(), -1);
  std::vector<CellId> seen_by;  // seen_by[k] == c: colour k is used by a neighbour of c
  int colors = 0;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (NodeId n : cells.nodes(c)) {
      for (CellId other : around.of(static_cast<std::size_t>(n))) {
        const int k = color[static_cast<std::size_t>(other)];
        if (k >= 0) seen_by[static_cast<std::size_t>(k)] = static_cast<CellId>(c);
      }
    }
    int k = 0;
    while (k < colors && seen_by[static_cast<std::size_t>(k)] == static_cast<CellId>(c)) ++k;
    if (k == colors) {
      ++colors;
      seen_by.push_back(-1);
    }
    color[c] = k;
  }
  CellColoring coloring;
  coloring.offsets.assign(static_cast<std::size_t>(colors) + 1, 0);
  for (int k : color) ++coloring.offsets[static_cast<std::size_t>(k) + 1];
  for (std::size_t i = 1; i < coloring.offsets.size(); ++i) coloring.offsets[i] += coloring.offsets[i - 1];
  coloring.cells.resize(cells.size());
  std::vector<std::int64_t> next(coloring.offsets.begin(), coloring.offsets.end() - 1);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    coloring.cells[static_cast<std::size_t>(next[static_cast<std::size_t>(color[c])]++)] = static_cast<CellId>(c);
  }
  return coloring;
}

StiffnessKernel::StiffnessKernel(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian)
    : cells_(&mesh.cells),
      nodes_(mesh.node_count()),
      dim_(mesh.dimension),
      lame_(std::move(lame)),
      drop_jacobian_(drop_jacobian) {
  require_motion_cells(mesh);
  if (lame_.size() != mesh.cell_count()) throw std::invalid_argument("StiffnessKernel: one Lame per cell");
  coloring_ = color_cells(mesh.cells, nodes_);
}

StiffnessKernel StiffnessKernel::with_lame(std::vector<Lame> lame) const {
  if (lame.size() != lame_.size()) throw std::invalid_argument("StiffnessKernel::with_lame: one Lame per cell");
  StiffnessKernel other = *this;
  other.lame_ = std::move(lame);
  return other;
}

void StiffnessKernel::element_matrix(CellId c, std::span<const Vec3> points, std::span<double> k) const {
  const auto i = static_cast<std::size_t>(c);
  element_stiffness(cells_->type(i), gather(cells_->nodes(i), points), lame_[i], drop_jacobian_, k);
}

}  // namespace hotmesh::deform
