// hotmesh deform: the element kernel over a mesh's cells, and the matrix-free stiffness
// operator with stored element matrices (storage layer).
#include "hotmesh/deform/stiffness_operator.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform {
namespace {

constexpr std::size_t kElementTypes = static_cast<std::size_t>(ElementType::pyramid5) + 1;

}  // namespace

CellColoring color_cells(const ElementList& cells, std::size_t node_count) {
  // node -> cells adjacency (CSR)
  std::vector<std::int64_t> start(node_count + 1, 0);
  for (NodeId n : cells.all_nodes()) ++start[static_cast<std::size_t>(n) + 1];
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<CellId> adjacent(static_cast<std::size_t>(start.back()));
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (NodeId n : cells.nodes(c)) adjacent[static_cast<std::size_t>(fill[static_cast<std::size_t>(n)]++)] = static_cast<CellId>(c);
  }
  std::vector<int> color(cells.size(), -1);
  std::vector<CellId> seen_by;  // seen_by[k] == c: colour k is used by a neighbour of c
  int colors = 0;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (NodeId n : cells.nodes(c)) {
      for (auto i = start[static_cast<std::size_t>(n)]; i < start[static_cast<std::size_t>(n) + 1]; ++i) {
        const int k = color[static_cast<std::size_t>(adjacent[static_cast<std::size_t>(i)])];
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
  // Type by type, so that each colour holds its cells grouped by type, in cell order within one.
  std::vector<bool> present(kElementTypes, false);
  for (ElementType t : cells.types()) present[static_cast<std::size_t>(t)] = true;
  for (std::size_t t = 0; t < kElementTypes; ++t) {
    if (!present[t]) continue;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (static_cast<std::size_t>(cells.type(c)) != t) continue;
      coloring.cells[static_cast<std::size_t>(next[static_cast<std::size_t>(color[c])]++)] = static_cast<CellId>(c);
    }
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
  offsets_.resize(cells.size() + 1, 0);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto n = static_cast<std::size_t>(element_dofs(cells.type(c)));
    offsets_[c + 1] = offsets_[c] + n * n;
  }
  matrices_.assign(offsets_.back(), 0.0);
}

StiffnessOperator::StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian)
    : StiffnessOperator(std::make_shared<const StiffnessKernel>(mesh, std::move(lame), drop_jacobian)) {}

void StiffnessOperator::update(std::span<const Vec3> points) {
  const auto n = static_cast<std::ptrdiff_t>(kernel_->cells().size());
#pragma omp parallel for schedule(static) if (n >= mesh::kParallelCells)
  for (std::ptrdiff_t c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(c);
    kernel_->element_matrix(static_cast<CellId>(c), points,
                            std::span<double>(matrices_.data() + offsets_[i], offsets_[i + 1] - offsets_[i]));
  }
}

std::span<const double> StiffnessOperator::element_matrix(CellId c) const {
  const auto i = static_cast<std::size_t>(c);
  return {matrices_.data() + offsets_[i], offsets_[i + 1] - offsets_[i]};
}

namespace {

/// y += K_e x_e for cells of one colour and one type; N = element dofs, D = dofs per node.
template <std::size_t N, std::size_t D>
void apply_cells(const ElementList& cells, std::span<const CellId> run, const double* matrices,
                 std::span<const std::size_t> offsets, std::span<const double> x, std::span<double> y) {
#pragma omp parallel for schedule(static) if (static_cast<std::ptrdiff_t>(run.size() * N * N) >= mesh::kParallelProduct)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(run.size()); ++k) {
    const auto c = static_cast<std::size_t>(run[static_cast<std::size_t>(k)]);
    add_element_product<N, D>(cells.nodes(c), matrices + offsets[c], x, y);
  }
}


}  // namespace

void StiffnessOperator::apply(std::span<const double> x, std::span<double> y) const {
  std::fill(y.begin(), y.end(), 0.0);
  const CellColoring& coloring = kernel_->coloring();
  for (std::size_t k = 0; k < coloring.colors(); ++k) {
    const ElementList& cells = kernel_->cells();
    auto begin = static_cast<std::size_t>(coloring.offsets[k]);
    const auto end = static_cast<std::size_t>(coloring.offsets[k + 1]);
    while (begin < end) {  // a run of cells of one type
      const ElementType type = cells.type(static_cast<std::size_t>(coloring.cells[begin]));
      auto stop = begin + 1;
      while (stop < end && cells.type(static_cast<std::size_t>(coloring.cells[stop])) == type) ++stop;
      const std::span<const CellId> run(coloring.cells.data() + begin, stop - begin);
      with_element_size(static_cast<std::size_t>(node_count(type)), static_cast<std::size_t>(kernel_->dofs_per_node()),
                        [&](auto n, auto d) { apply_cells<n, d>(cells, run, matrices_.data(), offsets_, x, y); });
      begin = stop;
    }
  }
}

void StiffnessOperator::diagonal(std::span<double> d) const {
  const auto dim = static_cast<std::size_t>(kernel_->dofs_per_node());
  std::vector<double> blocks(size() * dim);
  diagonal_blocks(blocks);
  for (std::size_t i = 0; i < size(); ++i) d[i] = blocks[i * dim + i % dim];
}

void StiffnessOperator::diagonal_blocks(std::span<double> blocks) const {
  // Sequential in cell order: deterministic, and cheap next to a product.
  std::fill(blocks.begin(), blocks.end(), 0.0);
  const auto dim = static_cast<std::size_t>(kernel_->dofs_per_node());
  const ElementList& cells = kernel_->cells();
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto ke = element_matrix(static_cast<CellId>(c));
    const auto nodes = cells.nodes(c);
    const std::size_t n = nodes.size() * dim;
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      double* block = blocks.data() + static_cast<std::size_t>(nodes[a]) * dim * dim;
      for (std::size_t i = 0; i < dim; ++i) {
        for (std::size_t j = 0; j < dim; ++j) block[i * dim + j] += ke[(a * dim + i) * n + a * dim + j];
      }
    }
  }
}

}  // namespace hotmesh::deform
