// hotmesh deform: the element kernel over a mesh's cells, and the stiffness operator that sums
// its element matrices into node blocks (storage layer).
#include "hotmesh/deform/stiffness_operator.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/node_order.hpp"
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
  const NodeCells around(cells, nodes);
  // The rows in reverse Cuthill-McKee order where that brings a cell's nodes much closer than
  // the mesh's own numbering does: a row then finds the blocks it reads transposed, and x, in
  // the rows just before it.
  order_ = reverse_cuthill_mckee(cells, around);
  position_.resize(nodes);
  for (std::size_t r = 0; r < nodes; ++r) position_[static_cast<std::size_t>(order_[r])] = static_cast<NodeId>(r);
  if (!(mean_spread(cells, position_) < kRenumberSpread * mean_spread(cells, {}))) {
    order_.clear();
    position_.clear();
  }
  const auto row_of = [&](NodeId n) { return position_.empty() ? n : position_[static_cast<std::size_t>(n)]; };
  const auto node_of = [&](std::size_t r) { return order_.empty() ? r : static_cast<std::size_t>(order_[r]); };
  // Row r stores the blocks of the rows q >= r whose nodes share a cell with its node, sorted,
  // each once; the diagonal block comes first.
  row_start_.assign(nodes + 1, 0);
  std::vector<NodeId> row;
  for (std::size_t r = 0; r < nodes; ++r) {
    row.clear();
    for (CellId c : around.of(node_of(r))) {
      for (NodeId j : cells.nodes(static_cast<std::size_t>(c))) {
        const NodeId q = row_of(j);
        if (static_cast<std::size_t>(q) >= r) row.push_back(q);
      }
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    columns_.insert(columns_.end(), row.begin(), row.end());
    row_start_[r + 1] = static_cast<std::int64_t>(columns_.size());
  }
  if (columns_.size() > std::numeric_limits<std::uint32_t>::max() - 1) {
    throw std::length_error("StiffnessOperator: " + std::to_string(columns_.size()) + " blocks are more than one process holds");
  }
  // Row q's blocks below the diagonal, K_qr = K_rq^T: where row r < q stores K_rq, by
  // increasing r (a pass over the stored blocks in row order visits them so).
  lower_start_.assign(nodes + 1, 0);
  for (NodeId q : columns_) ++lower_start_[static_cast<std::size_t>(q) + 1];
  for (std::size_t q = 0; q < nodes; ++q) lower_start_[q + 1] += lower_start_[q] - 1;  // less the diagonal
  lower_rows_.resize(static_cast<std::size_t>(lower_start_.back()));
  lower_blocks_.resize(lower_rows_.size());
  std::vector<std::int64_t> next(lower_start_.begin(), lower_start_.end() - 1);
  for (std::size_t r = 0; r < nodes; ++r) {
    for (auto k = row_start_[r] + 1; k < row_start_[r + 1]; ++k) {
      const auto at = static_cast<std::size_t>(next[static_cast<std::size_t>(columns_[static_cast<std::size_t>(k)])]++);
      lower_rows_[at] = static_cast<NodeId>(r);
      lower_blocks_[at] = static_cast<std::uint32_t>(k);
    }
  }
  // Where each cell's corner pairs (a, b) add their blocks: in row(a) when row(a) <= row(b),
  // none (kNoBlock) otherwise, the block being the transpose of (b, a)'s.
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
      const auto r = static_cast<std::size_t>(row_of(a));
      const auto first = columns_.begin() + row_start_[r];
      const auto last = columns_.begin() + row_start_[r + 1];
      for (NodeId b : corners) {
        const NodeId q = row_of(b);
        *at++ = q < static_cast<NodeId>(r) ? kNoBlock : static_cast<std::uint32_t>(std::lower_bound(first, last, q) - columns_.begin());
      }
    }
  }
  values_.assign(columns_.size() * d * d, 0.0);
  if (!order_.empty()) in_order_.resize(nodes * d);
}

StiffnessOperator::StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian)
    : StiffnessOperator(std::make_shared<const StiffnessKernel>(mesh, std::move(lame), drop_jacobian)) {}

namespace {

/// The arrays of a StiffnessOperator that a product reads.
struct SymmetricBlocks {
  std::span<const std::int64_t> row_start;
  const NodeId* columns;
  const double* values;
  std::span<const std::int64_t> lower_start;
  const NodeId* lower_rows;
  const std::uint32_t* lower_blocks;
};

/// K_ab += the (a, b) block of K_e for each corner pair of a cell whose block row stores it;
/// N = element dofs, D = dofs per node, `at` the cell's block positions.
template <std::size_t N, std::size_t D>
void add_blocks(const double* ke, const std::uint32_t* at, double* values) {
  constexpr std::size_t kCorners = N / D;
  for (std::size_t a = 0; a < kCorners; ++a) {
    for (std::size_t b = 0; b < kCorners; ++b) {
      const std::uint32_t position = at[a * kCorners + b];
      if (position == StiffnessOperator::kNoBlock) continue;
      double* block = values + static_cast<std::size_t>(position) * D * D;
      for (std::size_t i = 0; i < D; ++i) {
        for (std::size_t j = 0; j < D; ++j) block[i * D + j] += ke[(a * D + i) * N + b * D + j];
      }
    }
  }
}

/// y = K x over the block rows; D = dofs per node, x in row order, y written at the node of
/// each row (`node`, or the row itself if null). Row j sums its blocks below the diagonal
/// (K_ij^T x_i, read from the rows i < j that store them, by increasing i), then its stored
/// blocks (K_jk x_k, k >= j). Each row is one thread's and summed in that order, so y is the
/// same for any number of threads.
template <std::size_t D>
void multiply_rows(const SymmetricBlocks& k, const double* x, const NodeId* node, double* y) {
  const auto rows = static_cast<std::ptrdiff_t>(k.row_start.size() - 1);
  const auto blocks = static_cast<std::ptrdiff_t>(2 * k.row_start.back() - rows);
#pragma omp parallel for schedule(static) if (blocks * static_cast<std::ptrdiff_t>(D * D) >= mesh::kParallelProduct)
  for (std::ptrdiff_t j = 0; j < rows; ++j) {
    const auto row = static_cast<std::size_t>(j);
    std::array<double, D> sum{};
    for (auto l = k.lower_start[row]; l < k.lower_start[row + 1]; ++l) {
      const double* block = k.values + static_cast<std::size_t>(k.lower_blocks[l]) * D * D;
      const double* xi = x + static_cast<std::size_t>(k.lower_rows[l]) * D;
      for (std::size_t c = 0; c < D; ++c) {
        for (std::size_t r = 0; r < D; ++r) sum[r] += block[c * D + r] * xi[c];
      }
    }
    for (auto b = k.row_start[row]; b < k.row_start[row + 1]; ++b) {
      const double* block = k.values + static_cast<std::size_t>(b) * D * D;
      const double* xk = x + static_cast<std::size_t>(k.columns[b]) * D;
      for (std::size_t r = 0; r < D; ++r) {
        for (std::size_t c = 0; c < D; ++c) sum[r] += block[r * D + c] * xk[c];
      }
    }
    const std::size_t at = node ? static_cast<std::size_t>(node[row]) : row;
    for (std::size_t r = 0; r < D; ++r) y[at * D + r] = sum[r];
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
  const auto d = static_cast<std::size_t>(kernel_->dofs_per_node());
  const double* in = x.data();
  if (!order_.empty()) {  // x in row order
    const auto rows = static_cast<std::ptrdiff_t>(order_.size());
#pragma omp parallel for schedule(static) if (rows * static_cast<std::ptrdiff_t>(d) >= mesh::kParallelVector)
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
      const auto from = static_cast<std::size_t>(order_[static_cast<std::size_t>(r)]) * d;
      for (std::size_t c = 0; c < d; ++c) in_order_[static_cast<std::size_t>(r) * d + c] = x[from + c];
    }
    in = in_order_.data();
  }
  const SymmetricBlocks k{row_start_, columns_.data(), values_.data(), lower_start_, lower_rows_.data(), lower_blocks_.data()};
  const NodeId* node = order_.empty() ? nullptr : order_.data();
  if (d == 2) {
    multiply_rows<2>(k, in, node, y.data());
  } else {
    multiply_rows<3>(k, in, node, y.data());
  }
}

std::vector<NodeId> StiffnessOperator::coupled_nodes(NodeId i) const {
  const auto r = static_cast<std::size_t>(position_.empty() ? i : position_[static_cast<std::size_t>(i)]);
  const auto node_of = [&](NodeId row) { return order_.empty() ? row : order_[static_cast<std::size_t>(row)]; };
  std::vector<NodeId> nodes;
  for (auto l = lower_start_[r]; l < lower_start_[r + 1]; ++l) nodes.push_back(node_of(lower_rows_[static_cast<std::size_t>(l)]));
  for (auto k = row_start_[r]; k < row_start_[r + 1]; ++k) nodes.push_back(node_of(columns_[static_cast<std::size_t>(k)]));
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

std::size_t StiffnessOperator::bytes() const {
  return values_.size() * sizeof(double) + columns_.size() * sizeof(NodeId) + row_start_.size() * sizeof(std::int64_t) +
         lower_start_.size() * sizeof(std::int64_t) + lower_rows_.size() * (sizeof(NodeId) + sizeof(std::uint32_t)) +
         (order_.size() + position_.size()) * sizeof(NodeId) + in_order_.size() * sizeof(double) +
         positions_.size() * sizeof(std::uint32_t) + cell_start_.size() * sizeof(std::size_t);
}

void StiffnessOperator::diagonal(std::span<double> d) const {
  const auto dim = static_cast<std::size_t>(kernel_->dofs_per_node());
  std::vector<double> blocks(size() * dim);
  diagonal_blocks(blocks);
  for (std::size_t i = 0; i < size(); ++i) d[i] = blocks[i * dim + i % dim];
}

void StiffnessOperator::diagonal_blocks(std::span<double> out) const {
  const auto dd = static_cast<std::size_t>(kernel_->dofs_per_node() * kernel_->dofs_per_node());
  const std::size_t nodes = row_start_.size() - 1;
  for (std::size_t i = 0; i < nodes; ++i) {  // each row's first stored block is its diagonal one
    const auto r = position_.empty() ? i : static_cast<std::size_t>(position_[i]);
    const double* block = values_.data() + static_cast<std::size_t>(row_start_[r]) * dd;
    std::copy(block, block + dd, out.data() + i * dd);
  }
}

}  // namespace hotmesh::deform
