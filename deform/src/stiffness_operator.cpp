// hotmesh deform: the element kernel over a mesh's cells, and the matrix-free stiffness
// operator with stored element matrices (storage layer).
#include "hotmesh/deform/stiffness_operator.hpp"

#include <algorithm>
#include <stdexcept>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform {

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
  for (std::size_t c = 0; c < cells.size(); ++c) {
    coloring.cells[static_cast<std::size_t>(next[static_cast<std::size_t>(color[c])]++)] = static_cast<CellId>(c);
  }
  return coloring;
}

StiffnessKernel::StiffnessKernel(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian)
    : cells_(&mesh.cells),
      nodes_(mesh.node_count()),
      dim_(mesh.dimension),
      element_dofs_(0),
      lame_(std::move(lame)),
      drop_jacobian_(drop_jacobian) {
  const ElementType expected = dim_ == 2 ? ElementType::quad4 : ElementType::hex8;
  for (ElementType t : mesh.cells.types()) {
    if (t != expected) {
      throw InputError(std::string("the mesh-motion solver handles ") + (dim_ == 2 ? "2D meshes of quad4" : "3D meshes of hex8") +
                       " cells only; this mesh has " + std::string(name(t)) + " cells");
    }
  }
  if (lame_.size() != mesh.cell_count()) throw std::invalid_argument("StiffnessKernel: one Lame per cell");
  element_dofs_ = element_dofs(expected);
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

StiffnessOperator::StiffnessOperator(std::shared_ptr<const StiffnessKernel> kernel)
    : kernel_(std::move(kernel)),
      matrices_(kernel_->cells().size() * static_cast<std::size_t>(kernel_->element_size() * kernel_->element_size()), 0.0) {}

StiffnessOperator::StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian)
    : StiffnessOperator(std::make_shared<const StiffnessKernel>(mesh, std::move(lame), drop_jacobian)) {}

void StiffnessOperator::update(std::span<const Vec3> points) {
  const auto n = static_cast<std::ptrdiff_t>(kernel_->cells().size());
  const auto block = static_cast<std::size_t>(kernel_->element_size() * kernel_->element_size());
#pragma omp parallel for schedule(static) if (n >= mesh::kParallelCells)
  for (std::ptrdiff_t c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(c);
    kernel_->element_matrix(static_cast<CellId>(c), points, std::span<double>(matrices_.data() + i * block, block));
  }
}

std::span<const double> StiffnessOperator::element_matrix(CellId c) const {
  const auto block = static_cast<std::size_t>(kernel_->element_size() * kernel_->element_size());
  return {matrices_.data() + static_cast<std::size_t>(c) * block, block};
}

namespace {

/// y += K_e x_e for every cell of one colour; N = element dofs, D = dofs per node.
template <std::size_t N, std::size_t D>
void apply_color(const ElementList& cells, std::span<const CellId> color, const double* matrices,
                 std::span<const double> x, std::span<double> y) {
#pragma omp parallel for schedule(static) if (static_cast<std::ptrdiff_t>(color.size() * N * N) >= mesh::kParallelProduct)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(color.size()); ++k) {
    const auto c = static_cast<std::size_t>(color[static_cast<std::size_t>(k)]);
    add_element_product<N, D>(cells.nodes(c), matrices + c * N * N, x, y);
  }
}

}  // namespace

void StiffnessOperator::apply(std::span<const double> x, std::span<double> y) const {
  std::fill(y.begin(), y.end(), 0.0);
  const CellColoring& coloring = kernel_->coloring();
  for (std::size_t k = 0; k < coloring.colors(); ++k) {
    const std::span<const CellId> color(coloring.cells.data() + coloring.offsets[k],
                                        static_cast<std::size_t>(coloring.offsets[k + 1] - coloring.offsets[k]));
    if (kernel_->dofs_per_node() == 2) {
      apply_color<8, 2>(kernel_->cells(), color, matrices_.data(), x, y);
    } else {
      apply_color<24, 3>(kernel_->cells(), color, matrices_.data(), x, y);
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
  const auto n = static_cast<std::size_t>(kernel_->element_size());
  const auto dim = static_cast<std::size_t>(kernel_->dofs_per_node());
  const ElementList& cells = kernel_->cells();
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto ke = element_matrix(static_cast<CellId>(c));
    const auto nodes = cells.nodes(c);
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      double* block = blocks.data() + static_cast<std::size_t>(nodes[a]) * dim * dim;
      for (std::size_t i = 0; i < dim; ++i) {
        for (std::size_t j = 0; j < dim; ++j) block[i * dim + j] += ke[(a * dim + i) * n + a * dim + j];
      }
    }
  }
}

}  // namespace hotmesh::deform
