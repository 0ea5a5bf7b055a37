// hotmesh deform: the global stiffness K of the mesh, matrix-free (section 3). The element
// matrices K_e are computed once per Newton iteration at the current coordinates and stored;
// y = K x and the residual are element loops over the connectivity (eqs. 9-10):
//     (K x)_i = sum_{H containing i} [B_i^H] [K^H] {x^H}
// Elements are coloured so that no two of one colour share a node: colours run one after
// another, the elements of a colour in parallel. Every node then receives its contributions
// in the same order whatever the number of threads, so results are race-free and
// bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hotmesh/deform/linear_algebra.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform {

/// Cells grouped so that no two cells of a group share a node (greedy, in cell order).
struct CellColoring {
  std::vector<std::int64_t> offsets;  ///< colour c holds cells[offsets[c] .. offsets[c+1])
  std::vector<CellId> cells;
  std::size_t colors() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};
CellColoring color_cells(const ElementList& cells, std::size_t node_count);

class StiffnessOperator final : public LinearOperator {
 public:
  /// The mesh must have only quad4 (2D) or only hex8 (3D) cells; `lame` has one entry per
  /// cell. Throws hotmesh::InputError otherwise. Keeps a reference to mesh.cells. Without
  /// `store`, the element matrices are not kept (the amg solver computes them while it
  /// assembles): update(), apply(), diagonal() and element_matrix() are then not available,
  /// element_matrix_at() is.
  StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian, bool store = true);

  /// Recomputes every K_e at `points` (parallel over cells).
  void update(std::span<const Vec3> points);
  bool stores_matrices() const { return !matrices_.empty() || cells_->size() == 0; }
  /// K_e of cell c at `points`, computed now, row-major into k.
  void element_matrix_at(CellId c, std::span<const Vec3> points, std::span<double> k) const;

  std::size_t size() const override { return nodes_ * static_cast<std::size_t>(dim_); }
  /// y = K x for dof vectors laid out node after node (x_0, y_0, [z_0,] x_1, ...).
  void apply(std::span<const double> x, std::span<double> y) const override;
  /// The diagonal of K.
  void diagonal(std::span<double> d) const;
  /// The d x d diagonal blocks of K, one per node, row-major, node after node.
  void diagonal_blocks(std::span<double> blocks) const;

  int dofs_per_node() const { return dim_; }
  int element_size() const { return element_dofs_; }
  /// K_e of cell c, row-major.
  std::span<const double> element_matrix(CellId c) const;
  const ElementList& cells() const { return *cells_; }
  const CellColoring& coloring() const { return coloring_; }

 private:
  const ElementList* cells_;
  std::size_t nodes_;
  int dim_;
  int element_dofs_;
  std::vector<Lame> lame_;
  bool drop_jacobian_;
  CellColoring coloring_;
  std::vector<double> matrices_;
};

}  // namespace hotmesh::deform
