// hotmesh deform: the global stiffness K of the mesh, in the paper's three layers: the
// pointwise material law (eq. 35, material.hpp), the element kernel (Q1 with the Jacobian
// dropped, element_stiffness.hpp, applied to the cells by StiffnessKernel), and the storage.
// The paper's solver is matrix-free (section 3): it stores the element matrices K_e, computed
// once per Newton iteration at the current coordinates, and y = K x is an element loop over
// the connectivity (eqs. 9-10):
//     (K x)_i = sum_{H containing i} [B_i^H] [K^H] {x^H}
// hotmesh computes the same K_e once per Newton iteration and adds them straight into d x d
// node blocks, K_ij = sum_{H containing i and j} K^H_ij (block CSR, only the blocks on and above
// the diagonal since K is symmetric), and the product is a loop over the rows that reads each
// stored block once, for its row and, transposed, for its column's. The K is the same
// to round-off, and so are the products; the blocks take less memory than the K_e for every
// cell type (1.4 kB against 4.3 kB per node on hexes, 1.1 kB against 6.7 kB on tetrahedra, the
// cells' block positions included) and a product moves only them, so it is faster too
// (docs/method.md, "Storage of K"; bench_operator). The amg solver assembles the same K_e
// into a PETSc matrix in nodal frames instead (petsc_solver.cpp).
// Elements are coloured so that no two of one colour share a node: colours are added one
// after another, the elements of a colour in parallel. Every block then receives its
// contributions in the same order whatever the number of threads, and a product sums fixed
// chunks of rows, each on one thread in a fixed order, then adds what each chunk scattered into
// the next: results are race-free and bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/huge_pages.hpp"
#include "hotmesh/deform/linear_algebra.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform {

/// The cells around each node (CSR), in cell order.
struct NodeCells {
  std::vector<std::int64_t> start;
  std::vector<CellId> cells;

  NodeCells(const ElementList& list, std::size_t nodes);
  std::span<const CellId> of(std::size_t node) const {
    return {cells.data() + start[node], static_cast<std::size_t>(start[node + 1] - start[node])};
  }
};

/// Cells grouped so that no two cells of a group share a node (greedy, in cell order); a
/// colour's cells in cell order.
struct CellColoring {
  std::vector<std::int64_t> offsets;  ///< colour c holds cells[offsets[c] .. offsets[c+1])
  std::vector<CellId> cells;
  std::size_t colors() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};
CellColoring color_cells(const ElementList& cells, std::size_t node_count);

/// The element kernel over the cells of a mesh: K_e of any cell at given points, with the
/// cell's Lamé parameters (eq. 35, material.hpp) and its element of element_stiffness.hpp
/// (Q1 for quads and hexes, the linear tri3, tet4, wedge6 and pyramid5 beside them).
/// It stores nothing per Newton step; StiffnessOperator sums the K_e into node blocks, the
/// amg solver assembles them into its matrix as they come.
class StiffnessKernel {
 public:
  /// The mesh's cells must be of its dimension (tri3 and quad4 in 2D; tet4, hex8, wedge6 and
  /// pyramid5 in 3D, mixed as they come); `lame` has one entry per cell. Throws
  /// hotmesh::InputError otherwise. Keeps a reference to mesh.cells.
  StiffnessKernel(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian);
  /// The same cells (and colouring) with other Lamé parameters, one per cell.
  StiffnessKernel with_lame(std::vector<Lame> lame) const;

  /// K_e of cell c at `points`, row-major into k (element_size(c)^2 values).
  void element_matrix(CellId c, std::span<const Vec3> points, std::span<double> k) const;

  std::size_t size() const { return nodes_ * static_cast<std::size_t>(dim_); }  ///< dofs of the mesh
  int dofs_per_node() const { return dim_; }
  int element_size(CellId c) const { return element_dofs(cells_->type(static_cast<std::size_t>(c))); }
  const ElementList& cells() const { return *cells_; }
  const CellColoring& coloring() const { return coloring_; }

 private:
  const ElementList* cells_;
  std::size_t nodes_;
  int dim_;
  std::vector<Lame> lame_;
  bool drop_jacobian_;
  CellColoring coloring_;
};

/// K in d x d node blocks (block CSR), one row of blocks per node, the upper triangle only: K
/// is symmetric, so a row stores the blocks of the nodes whose rows come at or after its own
/// that share a cell with its node, and the rows before it hold the others as transposes. The
/// rows follow the nodes' numbers, or reverse Cuthill-McKee order where that numbering
/// scatters a cell's nodes (a mesh from an unstructured mesher): see renumbered().
/// update() computes every K_e at the current points and adds its blocks on and above the
/// diagonal; apply() reads each stored block once, for its row and for its transpose.
class StiffnessOperator final : public LinearOperator {
 public:
  explicit StiffnessOperator(std::shared_ptr<const StiffnessKernel> kernel);
  /// The kernel of `mesh` (see StiffnessKernel), with the block pattern of its cells.
  StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian);

  /// K at `points`: every K_e recomputed and summed into the blocks (parallel over the cells
  /// of a colour).
  void update(std::span<const Vec3> points);

  std::size_t size() const override { return kernel_->size(); }
  /// y = K x for dof vectors laid out node after node (x_0, y_0, [z_0,] x_1, ...). Row i adds
  /// K_ij x_j to itself and K_ij^T x_i to row j for each block it stores, chunk of rows by chunk
  /// (in parallel), then each chunk adds what the chunk before it scattered into its first rows.
  /// Uses the operator's own work arrays: one product at a time.
  void apply(std::span<const double> x, std::span<double> y) const override;
  /// The diagonal of K.
  void diagonal(std::span<double> d) const;
  /// The d x d diagonal blocks of K, one per node, row-major, node after node.
  void diagonal_blocks(std::span<double> blocks) const;

  /// The nodes of the blocks that node i's row stores, in row order: itself first, then the
  /// nodes it shares a cell with whose rows come after its own.
  std::vector<NodeId> stored_nodes(NodeId i) const;
  /// Whether the rows are stored in reverse Cuthill-McKee order rather than the nodes' own.
  bool renumbered() const { return !order_.empty(); }
  /// Blocks stored: the nonzero blocks of K on and above the diagonal.
  std::size_t block_count() const { return columns_.size(); }
  /// The nonzero blocks of K, below the diagonal too.
  std::size_t nonzero_blocks() const { return 2 * columns_.size() - (row_start_.size() - 1); }
  /// Bytes held: blocks, their column numbers, row starts, each cell's block positions, the
  /// row order with its copies of x and y, and the chunks' overflows.
  std::size_t bytes() const;

  const StiffnessKernel& kernel() const { return *kernel_; }
  int dofs_per_node() const { return kernel_->dofs_per_node(); }
  const ElementList& cells() const { return kernel_->cells(); }

  /// A cell's corner pair (a, b) whose a comes after b in row order adds no block: its block
  /// is stored as (b, a)'s transpose.
  static constexpr std::uint32_t kNoBlock = 0xffffffffu;
  /// Rows are stored in reverse Cuthill-McKee order when it brings the mean distance between
  /// the rows of a cell's nodes below this share of the nodes' own numbering's (bench_renumbering).
  static constexpr double kRenumberSpread = 0.5;
  /// A product splits the rows into this many chunks, or fewer where the rows reach so far
  /// that the chunks' overflows (the rows past a chunk that its blocks reach) would hold more
  /// than twice x.
  static constexpr std::size_t kProductChunks = 64;
  /// Rows in a chunk of a product (the same for any number of threads).
  std::size_t chunk_rows() const { return chunk_rows_; }
  std::size_t chunk_count() const { return (row_start_.size() - 1 + chunk_rows_ - 1) / chunk_rows_; }

 private:
  // The constructor's phases, in order.
  void order_rows(const NodeCells& around);
  void build_pattern(const NodeCells& around);
  void cut_product_chunks();
  void place_cell_blocks();
  NodeId row_of(NodeId node) const;
  std::size_t node_of(std::size_t row) const;

  std::shared_ptr<const StiffnessKernel> kernel_;
  std::vector<NodeId> order_;              ///< the node of each row (empty: row i is node i)
  std::vector<NodeId> position_;           ///< the row of each node (empty: node i is row i)
  std::vector<std::int64_t> row_start_;    ///< row i stores blocks [row_start_[i], row_start_[i + 1])
  std::vector<NodeId> columns_;            ///< the column (row of a node) of each block
  std::size_t chunk_rows_ = 1;             ///< rows in a chunk of a product
  std::vector<std::size_t> overflow_start_;  ///< chunk c's overflow: rows [overflow_start_[c], overflow_start_[c + 1]) of overflow_
  mutable std::vector<double> overflow_;   ///< per chunk, what it scatters past its end
  mutable std::vector<double> x_rows_;     ///< x in row order, for a product (when renumbered)
  mutable std::vector<double> y_rows_;     ///< ... and y
  std::vector<std::size_t> cell_start_;    ///< cell c's block positions at positions_[cell_start_[c] ..)
  std::vector<std::uint32_t> positions_;   ///< block of corners (a, b) of a cell, a * corners + b, or kNoBlock
  std::vector<double, HugePageAllocator<double>> values_;  ///< block k at values_[k d^2 ..), row-major
};

}  // namespace hotmesh::deform
