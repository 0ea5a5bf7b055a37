// hotmesh deform: the global stiffness K of the mesh, in the paper's three layers: the
// pointwise material law (eq. 35, material.hpp), the element kernel (Q1 with the Jacobian
// dropped, element_stiffness.hpp, applied to the cells by StiffnessKernel), and the storage.
// Here the storage is matrix-free (section 3): the element matrices K_e are computed once per
// Newton iteration at the current coordinates and stored, and y = K x is an element loop over
// the connectivity (eqs. 9-10):
//     (K x)_i = sum_{H containing i} [B_i^H] [K^H] {x^H}
// (the amg solver assembles the same K_e into a PETSc matrix instead, petsc_solver.cpp).
// Elements are coloured so that no two of one colour share a node: colours run one after
// another, the elements of a colour in parallel. Every node then receives its contributions
// in the same order whatever the number of threads, so results are race-free and
// bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/linear_algebra.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform {

/// Cells grouped so that no two cells of a group share a node (greedy, in cell order); within
/// a colour the cells are grouped by type (in cell order within a type), so that the element
/// loops run over cells of one size at a time.
struct CellColoring {
  std::vector<std::int64_t> offsets;  ///< colour c holds cells[offsets[c] .. offsets[c+1])
  std::vector<CellId> cells;
  std::size_t colors() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};
CellColoring color_cells(const ElementList& cells, std::size_t node_count);

/// The element kernel over the cells of a mesh: K_e of any cell at given points, with the
/// cell's Lamé parameters (eq. 35, material.hpp) and its element of element_stiffness.hpp
/// (Q1 for quads and hexes, the linear tri3, tet4, wedge6 and pyramid5 beside them).
/// It stores nothing per Newton step; StiffnessOperator stores the K_e, the amg solver
/// assembles them as they come.
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

/// K matrix-free with stored element matrices (the paper's section 3): update() computes every
/// K_e at the current points, apply() is the element loop of eqs. (9)-(10).
class StiffnessOperator final : public LinearOperator {
 public:
  explicit StiffnessOperator(std::shared_ptr<const StiffnessKernel> kernel);
  /// The kernel of `mesh` (see StiffnessKernel), with storage for its element matrices.
  StiffnessOperator(const Mesh& mesh, std::vector<Lame> lame, bool drop_jacobian);

  /// Recomputes every K_e at `points` (parallel over cells).
  void update(std::span<const Vec3> points);

  std::size_t size() const override { return kernel_->size(); }
  /// y = K x for dof vectors laid out node after node (x_0, y_0, [z_0,] x_1, ...).
  void apply(std::span<const double> x, std::span<double> y) const override;
  /// The diagonal of K.
  void diagonal(std::span<double> d) const;
  /// The d x d diagonal blocks of K, one per node, row-major, node after node.
  void diagonal_blocks(std::span<double> blocks) const;

  /// K_e of cell c as update() stored it, row-major.
  std::span<const double> element_matrix(CellId c) const;
  const StiffnessKernel& kernel() const { return *kernel_; }
  int dofs_per_node() const { return kernel_->dofs_per_node(); }
  const ElementList& cells() const { return kernel_->cells(); }

 private:
  std::shared_ptr<const StiffnessKernel> kernel_;
  std::vector<std::size_t> offsets_;  ///< K_e of cell c at matrices_[offsets_[c] ..), element_size(c)^2 values
  std::vector<double> matrices_;
};

}  // namespace hotmesh::deform
