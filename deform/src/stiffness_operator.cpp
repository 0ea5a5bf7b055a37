// hotmesh deform: the element kernel over a mesh's cells, and the stiffness operator that sums
// its element matrices into node blocks (storage layer).
#include "hotmesh/deform/stiffness_operator.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

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

StiffnessOperator::StiffnessOperator(std::shared_ptr<const StiffnessKernel> kernel) : kernel_(std::move(kernel)) {
  const ElementList& cells = kernel_->cells();
  const auto d = static_cast<std::size_t>(kernel_->dofs_per_node());
  const std::size_t nodes = kernel_->size() / d;
  // Row i's columns: the corners of the cells around i, sorted, each once.
  const NodeCells around(cells, nodes);
  row_start_.assign(nodes + 1, 0);
  std::vector<NodeId> row;
  for (std::size_t i = 0; i < nodes; ++i) {
    row.clear();
    for (CellId c : around.of(i)) {
      const auto corners = cells.nodes(static_cast<std::size_t>(c));
      row.insert(row.end(), corners.begin(), corners.end());
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    columns_.insert(columns_.end(), row.begin(), row.end());
    row_start_[i + 1] = static_cast<std::int64_t>(columns_.size());
  }
  if (columns_.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("StiffnessOperator: " + std::to_string(columns_.size()) + " blocks are more than one process holds");
  }
  // Where each cell's corner pairs (a, b) add their blocks.
  cell_start_.assign(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const std::size_t corners = cells.nodes(c).size();
    cell_start_[c + 1] = cell_start_[c] + corners * corners;
  }
  positions_.resize(cell_start_.back());
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto corners = cells.nodes(c);
    std::uint32_t* at = positions_.data() + cell_start_[c];
    for (NodeId a : corners) {
      const auto first = columns_.begin() + row_start_[static_cast<std::size_t>(a)];
      const auto last = columns_.begin() + row_start_[static_cast<std::size_t>(a) + 1];
      for (NodeId b : corners) *at++ = static_cast<std::uint32_t>(std::lower_bound(first, last, b) - columns_.begin());
    }
  }
  values_.assign(columns_.size() * d * d, 0.0);
}

StiffnessOperator::StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian)
    : StiffnessOperator(std::make_shared<const StiffnessKernel>(mesh, std::move(lame), drop_jacobian)) {}

namespace {

/// K_ab += the (a, b) block of K_e for each corner pair of a cell; N = element dofs, D = dofs
/// per node, `at` the cell's block positions.
template <std::size_t N, std::size_t D>
void add_blocks(const double* ke, const std::uint32_t* at, double* values) {
  constexpr std::size_t kCorners = N / D;
  for (std::size_t a = 0; a < kCorners; ++a) {
    for (std::size_t b = 0; b < kCorners; ++b) {
      double* block = values + static_cast<std::size_t>(at[a * kCorners + b]) * D * D;
      for (std::size_t i = 0; i < D; ++i) {
        for (std::size_t j = 0; j < D; ++j) block[i * D + j] += ke[(a * D + i) * N + b * D + j];
      }
    }
  }
}

/// y = K x over the block rows; D = dofs per node. Each row is one thread's, summed in column
/// order.
template <std::size_t D>
void multiply_rows(std::span<const std::int64_t> row_start, const NodeId* columns, const double* values,
                   const double* x, double* y) {
  const auto rows = static_cast<std::ptrdiff_t>(row_start.size() - 1);
#pragma omp parallel for schedule(static) if (static_cast<std::ptrdiff_t>(row_start.back()) * static_cast<std::ptrdiff_t>(D * D) >= mesh::kParallelProduct)
  for (std::ptrdiff_t i = 0; i < rows; ++i) {
    std::array<double, D> sum{};
    for (auto k = row_start[static_cast<std::size_t>(i)]; k < row_start[static_cast<std::size_t>(i) + 1]; ++k) {
      const double* block = values + static_cast<std::size_t>(k) * D * D;
      const double* xj = x + static_cast<std::size_t>(columns[k]) * D;
      for (std::size_t r = 0; r < D; ++r) {
        for (std::size_t j = 0; j < D; ++j) sum[r] += block[r * D + j] * xj[j];
      }
    }
    for (std::size_t r = 0; r < D; ++r) y[static_cast<std::size_t>(i) * D + r] = sum[r];
  }
}

}  // namespace

void StiffnessOperator::update(std::span<const Vec3> points) {
  std::fill(values_.begin(), values_.end(), 0.0);
  const CellColoring& coloring = kernel_->coloring();
  const ElementList& cells = kernel_->cells();
  const auto d = static_cast<std::size_t>(kernel_->dofs_per_node());
  for (std::size_t k = 0; k < coloring.colors(); ++k) {  // no two cells of a colour share a block
    const auto begin = coloring.offsets[k], end = coloring.offsets[k + 1];
#pragma omp parallel for schedule(static) if (end - begin >= mesh::kParallelCells)
    for (std::int64_t i = begin; i < end; ++i) {
      const CellId c = coloring.cells[static_cast<std::size_t>(i)];
      const std::size_t corners = cells.nodes(static_cast<std::size_t>(c)).size();
      std::array<double, kMaxElementDofs * kMaxElementDofs> ke;
      kernel_->element_matrix(c, points, {ke.data(), corners * d * corners * d});
      const std::uint32_t* at = positions_.data() + cell_start_[static_cast<std::size_t>(c)];
      with_element_size(corners, d, [&](auto n, auto dofs) { add_blocks<n, dofs>(ke.data(), at, values_.data()); });
    }
  }
}

void StiffnessOperator::apply(std::span<const double> x, std::span<double> y) const {
  if (kernel_->dofs_per_node() == 2) {
    multiply_rows<2>(row_start_, columns_.data(), values_.data(), x.data(), y.data());
  } else {
    multiply_rows<3>(row_start_, columns_.data(), values_.data(), x.data(), y.data());
  }
}

std::span<const NodeId> StiffnessOperator::columns(NodeId i) const {
  const auto r = static_cast<std::size_t>(i);
  return {columns_.data() + row_start_[r], static_cast<std::size_t>(row_start_[r + 1] - row_start_[r])};
}

std::span<const double> StiffnessOperator::blocks(NodeId i) const {
  const auto r = static_cast<std::size_t>(i);
  const auto dd = static_cast<std::size_t>(kernel_->dofs_per_node() * kernel_->dofs_per_node());
  return {values_.data() + static_cast<std::size_t>(row_start_[r]) * dd,
          static_cast<std::size_t>(row_start_[r + 1] - row_start_[r]) * dd};
}

std::size_t StiffnessOperator::bytes() const {
  return values_.size() * sizeof(double) + columns_.size() * sizeof(NodeId) + row_start_.size() * sizeof(std::int64_t) +
         positions_.size() * sizeof(std::uint32_t) + cell_start_.size() * sizeof(std::size_t);
}

void StiffnessOperator::diagonal(std::span<double> d) const {
  const auto dim = static_cast<std::size_t>(kernel_->dofs_per_node());
  std::vector<double> blocks(size() * dim);
  diagonal_blocks(blocks);
  for (std::size_t i = 0; i < size(); ++i) d[i] = blocks[i * dim + i % dim];
}

void StiffnessOperator::diagonal_blocks(std::span<double> out) const {
  const auto dim = static_cast<std::size_t>(kernel_->dofs_per_node());
  const std::size_t nodes = row_start_.size() - 1;
  for (std::size_t i = 0; i < nodes; ++i) {
    const auto row = columns(static_cast<NodeId>(i));
    const auto k = static_cast<std::size_t>(std::lower_bound(row.begin(), row.end(), static_cast<NodeId>(i)) - row.begin());
    const double* block = blocks(static_cast<NodeId>(i)).data() + k * dim * dim;
    std::copy(block, block + dim * dim, out.data() + i * dim * dim);
  }
}

}  // namespace hotmesh::deform
