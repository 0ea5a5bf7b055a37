// hotmesh deform: the stiffness operator that sums the element kernel's matrices
// (element/stiffness_kernel.cpp) into node blocks (storage layer).
#include "hotmesh/deform/stiffness_operator.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/node_order.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform {

StiffnessOperator::StiffnessOperator(std::shared_ptr<const StiffnessKernel> kernel) : kernel_(std::move(kernel)) {
  const auto d = static_cast<std::size_t>(kernel_->dofs_per_node());
  const std::size_t nodes = kernel_->size() / d;
  const NodeCells around(kernel_->cells(), nodes);
  order_rows(around);
  build_pattern(around);
  cut_product_chunks();
  place_cell_blocks();
  values_.assign(columns_.size() * d * d, 0.0);
  if (!order_.empty()) {
    x_rows_.resize(nodes * d);
    y_rows_.resize(nodes * d);
  }
}

NodeId StiffnessOperator::row_of(NodeId node) const { return position_.empty() ? node : position_[static_cast<std::size_t>(node)]; }

std::size_t StiffnessOperator::node_of(std::size_t row) const { return order_.empty() ? row : static_cast<std::size_t>(order_[row]); }

// The rows in reverse Cuthill-McKee order where that brings a cell's nodes much closer than
// the mesh's own numbering does: a row then finds the rows it scatters into, and x, just after it.
void StiffnessOperator::order_rows(const NodeCells& around) {
  const ElementList& cells = kernel_->cells();
  order_ = reverse_cuthill_mckee(cells, around);
  position_.resize(order_.size());
  for (std::size_t r = 0; r < order_.size(); ++r) position_[static_cast<std::size_t>(order_[r])] = static_cast<NodeId>(r);
  if (!(mean_spread(cells, position_) < kRenumberSpread * mean_spread(cells, {}))) {
    order_.clear();
    position_.clear();
  }
}

// Row r stores the blocks of the rows q >= r whose nodes share a cell with its node, sorted,
// each once; the diagonal block comes first.
void StiffnessOperator::build_pattern(const NodeCells& around) {
  const ElementList& cells = kernel_->cells();
  const std::size_t nodes = around.start.size() - 1;
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
}

// A product runs over chunks of rows; each chunk scatters past its end into its own overflow,
// which runs up to the furthest row its blocks reach. Chunks of a 64th of the rows, twice as
// long while the overflows would hold more than twice x (a mesh whose numbering wraps around:
// its first rows reach the last).
void StiffnessOperator::cut_product_chunks() {
  const std::size_t nodes = row_start_.size() - 1;
  const auto overflow_rows = [&](std::size_t chunk_rows) {
    std::vector<std::size_t> start{0};
    for (std::size_t begin = 0; begin < nodes; begin += chunk_rows) {
      const std::size_t end = std::min(nodes, begin + chunk_rows);
      std::size_t last = end;  // one past the furthest row reached
      for (std::size_t r = begin; r < end; ++r) {
        if (row_start_[r + 1] == row_start_[r]) continue;  // a node in no cell
        const NodeId furthest = columns_[static_cast<std::size_t>(row_start_[r + 1] - 1)];
        last = std::max(last, static_cast<std::size_t>(furthest) + 1);
      }
      start.push_back(start.back() + last - end);
    }
    return start;
  };
  chunk_rows_ = std::max<std::size_t>(1, (nodes + kProductChunks - 1) / kProductChunks);
  overflow_start_ = overflow_rows(chunk_rows_);
  while (overflow_start_.back() > 2 * nodes && chunk_rows_ < nodes) overflow_start_ = overflow_rows(chunk_rows_ *= 2);
  overflow_.resize(overflow_start_.back() * static_cast<std::size_t>(kernel_->dofs_per_node()));
}

// Where each cell's corner pairs (a, b) add their blocks: in row(a) when row(a) <= row(b),
// none (kNoBlock) otherwise, the block being the transpose of (b, a)'s.
void StiffnessOperator::place_cell_blocks() {
  const ElementList& cells = kernel_->cells();
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
}

StiffnessOperator::StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian)
    : StiffnessOperator(std::make_shared<const StiffnessKernel>(mesh, std::move(lame), drop_jacobian)) {}

namespace {

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

// The product's kernel (eqs. 9-10 over node blocks). Each stored block K_ij (j >= i,
// row-major) is read once, in row i: row i gathers K_ij x_j into its own sum and scatters
// K_ji x_i = K_ij^T x_i into row j. Two-wide vectors (GCC's and Clang's vector extensions:
// SSE2 on any x86-64, NEON on ARM) hold two entries of a block; row i keeps one sum per block
// entry, so consecutive blocks add into independent registers, and the sums are reduced once,
// at the end of the row.
using Pair = double __attribute__((vector_size(16)));
inline Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void add_pair(double* p, Pair v) {
  const Pair sum = load_pair(p) + v;
  std::memcpy(p, &sum, sizeof sum);
}
inline Pair both(double v) { return Pair{v, v}; }

/// One row of 2 x 2 blocks [a b; c d]: sums a x_0, b x_1 in one pair and c x_0, d x_1 in the other.
class Row2 {
 public:
  explicit Row2(const double* xi) : xi0_(both(xi[0])), xi1_(both(xi[1])) {}
  void gather(const double* block, const double* xj) {
    const Pair x = load_pair(xj);
    top_ += load_pair(block) * x;
    bottom_ += load_pair(block + 2) * x;
  }
  /// y_j += K_ij^T x_i.
  void scatter(const double* block, double* yj) const { add_pair(yj, xi0_ * load_pair(block) + xi1_ * load_pair(block + 2)); }
  void add_to(double* yi) const {
    yi[0] += top_[0] + top_[1];
    yi[1] += bottom_[0] + bottom_[1];
  }

 private:
  Pair xi0_, xi1_, top_{}, bottom_{};
};

/// One row of 3 x 3 blocks, entries 0..8 row-major: pairs (0, 1), (2, 3), (4, 5), (6, 7) and
/// entry 8 alone, times (x_0, x_1), (x_2, x_0), (x_1, x_2), (x_0, x_1) and x_2.
class Row3 {
 public:
  explicit Row3(const double* xi) : xi0_(both(xi[0])), xi1_(both(xi[1])), xi2_(both(xi[2])) {}
  void gather(const double* block, const double* xj) {
    const Pair x01 = load_pair(xj), x12 = load_pair(xj + 1), x20 = {xj[2], xj[0]};
    s01_ += load_pair(block) * x01;
    s23_ += load_pair(block + 2) * x20;
    s45_ += load_pair(block + 4) * x12;
    s67_ += load_pair(block + 6) * x01;
    s8_ += block[8] * xj[2];
  }
  /// y_j += K_ij^T x_i: (y_0, y_1) from the first two columns, y_2 from the third.
  void scatter(const double* block, double* yj) const {
    add_pair(yj, xi0_ * load_pair(block) + xi1_ * load_pair(block + 3) + xi2_ * load_pair(block + 6));
    yj[2] += xi0_[0] * block[2] + xi1_[0] * block[5] + xi2_[0] * block[8];
  }
  void add_to(double* yi) const {
    yi[0] += s01_[0] + s01_[1] + s23_[0];
    yi[1] += s23_[1] + s45_[0] + s45_[1];
    yi[2] += s67_[0] + s67_[1] + s8_;
  }

 private:
  Pair xi0_, xi1_, xi2_, s01_{}, s23_{}, s45_{}, s67_{};
  double s8_ = 0.0;
};

/// Blocks a product asks the memory for ahead of the one it multiplies (4.6 kB of 3 x 3 blocks):
/// without it, products on the 100^3 hex block took 1.3 times as long (bench_operator).
constexpr std::int64_t kPrefetchBlocks = 64;

/// The rows [begin, end) of y = K x (`Row` is Row2 or Row3), x and y in row order. Zeroes
/// their y first; what their blocks scatter past `end` goes to `overflow` (`overflow_rows`
/// rows from row `end` on).
template <class Row, std::size_t D>
void multiply_chunk(std::span<const std::int64_t> row_start, const NodeId* columns, const double* values, std::size_t begin,
                    std::size_t end, std::size_t overflow_rows, const double* x, double* y, double* overflow) {
  std::fill(y + begin * D, y + end * D, 0.0);
  std::fill(overflow, overflow + overflow_rows * D, 0.0);
  const std::int64_t blocks_end = row_start.back() - 1;
  for (std::size_t i = begin; i < end; ++i) {
    auto b = row_start[i];
    if (b == row_start[i + 1]) continue;  // a node in no cell
    Row row(x + i * D);
    row.gather(values + static_cast<std::size_t>(b) * D * D, x + i * D);  // the diagonal block
    for (++b; b < row_start[i + 1]; ++b) {
      const double* block = values + static_cast<std::size_t>(b) * D * D;
      __builtin_prefetch(values + static_cast<std::size_t>(std::min(b + kPrefetchBlocks, blocks_end)) * D * D);
      const auto j = static_cast<std::size_t>(columns[b]);
      row.gather(block, x + j * D);
      row.scatter(block, j < end ? y + j * D : overflow + (j - end) * D);
    }
    row.add_to(y + i * D);
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
#pragma omp parallel for schedule(dynamic, mesh::kChunkCells) if (end - begin >= mesh::kParallelCells)
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
  const std::size_t rows = row_start_.size() - 1;
  const std::size_t chunks = chunk_count();
  const bool renumbered = !order_.empty();
  const double* in = renumbered ? x_rows_.data() : x.data();
  double* out = renumbered ? y_rows_.data() : y.data();
  const auto work = static_cast<std::ptrdiff_t>(nonzero_blocks() * d * d);
  // Each chunk's rows are summed by one thread in a fixed order, and what a chunk scattered
  // into the next one is added after it: y is the same for any number of threads. Threads
  // take chunks as they finish the last (a thread whose core is busy takes fewer).
#pragma omp parallel if (work >= mesh::kParallelProduct)
  {
    if (renumbered) {
#pragma omp for schedule(dynamic, mesh::kChunkNodes)
      for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(rows); ++r) {
        const auto from = static_cast<std::size_t>(order_[static_cast<std::size_t>(r)]) * d;
        for (std::size_t c = 0; c < d; ++c) x_rows_[static_cast<std::size_t>(r) * d + c] = x[from + c];
      }
    }
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks); ++c) {
      const auto chunk = static_cast<std::size_t>(c);
      const std::size_t begin = chunk * chunk_rows_, end = std::min(rows, begin + chunk_rows_);
      const std::size_t overflow_rows = overflow_start_[chunk + 1] - overflow_start_[chunk];
      double* overflow = overflow_.data() + overflow_start_[chunk] * d;
      if (d == 2) {
        multiply_chunk<Row2, 2>(row_start_, columns_.data(), values_.data(), begin, end, overflow_rows, in, out, overflow);
      } else {
        multiply_chunk<Row3, 3>(row_start_, columns_.data(), values_.data(), begin, end, overflow_rows, in, out, overflow);
      }
    }
#pragma omp for schedule(dynamic)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks); ++c) {
      const auto chunk = static_cast<std::size_t>(c);
      const std::size_t begin = chunk * chunk_rows_, end = std::min(rows, begin + chunk_rows_);
      for (std::size_t earlier = 0; earlier < chunk; ++earlier) {  // what the chunks before scattered into this one, in order
        const std::size_t from = (earlier + 1) * chunk_rows_;       // the first row of the earlier chunk's overflow
        const std::size_t past = std::min(end, from + overflow_start_[earlier + 1] - overflow_start_[earlier]);
        const double* overflow = overflow_.data() + overflow_start_[earlier] * d;
        for (std::size_t e = begin * d; e < past * d; ++e) out[e] += overflow[e - from * d];
      }
      if (renumbered) {
        for (std::size_t r = begin; r < end; ++r) {
          const auto to = static_cast<std::size_t>(order_[r]) * d;
          for (std::size_t k = 0; k < d; ++k) y[to + k] = y_rows_[r * d + k];
        }
      }
    }
  }
}

std::vector<NodeId> StiffnessOperator::stored_nodes(NodeId i) const {
  const auto r = static_cast<std::size_t>(row_of(i));
  std::vector<NodeId> nodes;
  for (auto k = row_start_[r]; k < row_start_[r + 1]; ++k) {
    nodes.push_back(static_cast<NodeId>(node_of(static_cast<std::size_t>(columns_[static_cast<std::size_t>(k)]))));
  }
  return nodes;
}

std::size_t StiffnessOperator::bytes() const {
  return values_.size() * sizeof(double) + columns_.size() * sizeof(NodeId) + row_start_.size() * sizeof(std::int64_t) +
         (order_.size() + position_.size()) * sizeof(NodeId) + (x_rows_.size() + y_rows_.size() + overflow_.size()) * sizeof(double) +
         positions_.size() * sizeof(std::uint32_t) + (cell_start_.size() + overflow_start_.size()) * sizeof(std::size_t);
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
    const auto r = static_cast<std::size_t>(row_of(static_cast<NodeId>(i)));
    const double* block = values_.data() + static_cast<std::size_t>(row_start_[r]) * dd;
    std::copy(block, block + dd, out.data() + i * dd);
  }
}

}  // namespace hotmesh::deform
