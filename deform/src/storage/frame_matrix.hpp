// hotmesh deform (internal): the matrix of the amg solver (petsc_solver.cpp). K~ = T^T K T in
// the nodal frames (nodal_frames.hpp) as a PETSc AIJ matrix of block size d: which rank does
// each cell's element work (partition_cells), which block row each node's unknowns take and
// which rank owns it (BlockRows), the matrix preallocated from the node graph
// (create_frame_matrix) and the element pass that fills it (assemble_frame_matrix). With one
// process everything is on PETSC_COMM_SELF and the partition is trivial. PETSc types: include
// only where PETSc is used.
#pragma once

#include <petscmat.h>

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "constraints/nodal_frames.hpp"
#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/parallel/processes.hpp"
#include "storage/linear_solver.hpp"

namespace hotmesh::deform::detail {

inline void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc failed in ") + what + " (error code " + std::to_string(code) + ")");
}

/// The rank that does each cell's element work. With several processes: PETSc's partitioner
/// (PT-Scotch by default, -hotmesh_mat_partitioning_type to change) on the graph of cells
/// that share a face (d nodes or more), each rank giving the edges of its share of the cells.
std::vector<int> partition_cells(const ElementList& list, const NodeCells& around, int d, const parallel::Processes& job);

/// The block rows of the matrix: one per node with at least one unknown (free or sliding);
/// a slave shares its master's. Fixed nodes (and slaves of fixed masters) have none and are
/// left out: as rows holding only a diagonal they would be isolated vertices of the matrix
/// graph, which PCGAMG makes aggregates of one node (whose d rows cannot carry the rigid-body
/// rotations, see set_near_null_space), and work for nothing. The set does not change
/// during a run: sliding nodes keep at least one tangential direction. A node's row belongs
/// to the lowest rank among its cells; rows are numbered rank by rank, nodes in order within
/// a rank (with one process: in node order).
struct BlockRows {
  std::vector<PetscInt> of_node;  ///< block row of each node's unknowns (a slave: its master's), -1 for none
  std::vector<NodeId> node_of;    ///< the node each block row belongs to
  std::vector<PetscInt> first;    ///< rank r owns the block rows [first[r], first[r + 1])
  PetscInt count = 0;

  BlockRows(const NodalFrames& frames, const NodeCells& around, std::span<const int> rank_of_cell, int ranks);
  PetscInt operator[](NodeId n) const { return of_node[static_cast<std::size_t>(n)]; }
  PetscInt begin(int rank) const { return first[static_cast<std::size_t>(rank)]; }
  PetscInt end(int rank) const { return first[static_cast<std::size_t>(rank) + 1]; }

  /// A full vector (d entries per node) at the block rows (as many as `rows` holds, from
  /// `first_row` on), and back (every block row; zero elsewhere).
  void gather(std::span<const double> full, std::span<double> rows, std::size_t d, PetscInt first_row = 0) const;
  void scatter(std::span<const double> rows, std::span<double> full, std::size_t d) const;
};

/// A square matrix of block size d over the block rows, the rows of `job.rank` stored by this
/// process, preallocated from the node graph with slaves merged into their masters.
Mat create_frame_matrix(const ElementList& cells, const NodeCells& around, const NodalFrames& frames,
                        const BlockRows& rows, const parallel::Processes& job);

/// The order cells are assembled in with one process: the colours of the stiffness operator
/// (no two cells of a colour share a node, so threads may add into the matrix side by side),
/// without the cells that hold a periodic slave, which write into their masters' rows and
/// come last, one after another.
struct AssemblyOrder {
  std::vector<std::vector<CellId>> colours;
  std::vector<CellId> with_slaves;

  AssemblyOrder(const StiffnessKernel& k, const NodalFrames& frames);
};

/// K~_e of one cell and the block rows of its corners (negative for a node without unknowns:
/// PETSc skips them).
struct FrameElement {
  std::array<double, kMaxElementDofs * kMaxElementDofs> values{};  ///< K~_e, (d corners)^2 values row-major
  std::array<PetscInt, mesh::kMaxElementNodes> index{};
  std::size_t corners = 0;
};

/// An element pass computes each K_e from the system's kernel at its points (nothing stored:
/// the matrices computed once per pass). With a `residual`, the pass also hands each K_e to it
/// (the Newton loop's residual).
struct ElementPass {
  const ConstrainedSystem& s;
  const ResidualPass* residual = nullptr;

  /// K~_e of `cell` in `frames`, its corners' block rows; K_e to the residual.
  void frame_element(CellId cell, const NodalFrames& frames, const BlockRows& rows, FrameElement& out) const;
  /// K_e of `cell` into `ke` ((d corners)^2 values), and to the residual.
  void element(CellId cell, std::span<double> ke) const;
};

/// K~ into the preallocated `a`, from the K_e of this rank's cells `local` (and their part of
/// the residual, see ElementPass). Each block is added straight into the AIJ values of this
/// rank's rows, and only the blocks of rows owned by other ranks go through
/// MatSetValuesBlocked. With one process the cells of a colour are added in parallel. The
/// first assembly first fixes the sparsity through MatSetValuesBlocked, then adds the values
/// as every later one does: the same sums in the same order, so that a run resumed from a
/// checkpoint (a new process, a first assembly) reproduces the uninterrupted run bit for bit.
void assemble_frame_matrix(Mat a, const ElementPass& pass, const NodalFrames& frames, const BlockRows& rows,
                           const AssemblyOrder& order, std::span<const CellId> local, bool first);

/// The d translations written in the frames (Q_n^T e_k at each block row's node, zero on the
/// constrained components), orthonormalised over all ranks, as the near-null space of `a`:
/// PCGAMG's aggregates interpolate them exactly. Built on this rank's rows only. Not the
/// rotations: with them PCGAMG of PETSc 3.18 makes aggregates of one node here and there, whose
/// d rows cannot carry 3 (2D) or 6 (3D) modes; their prolongator columns vanish, the coarse
/// matrices get zero rows and the smoother fails (the sliding ramp, the stator well). With the
/// translations alone every aggregate has enough rows.
void set_near_null_space(Mat a, const NodalFrames& frames, const BlockRows& rows);

/// The residual of the pass alone: each K_e of this rank's cells handed to pass.residual in the
/// order assemble_frame_matrix hands them (the same sums, bit for bit), none added to a matrix.
void residual_pass(const ElementPass& pass, const AssemblyOrder& order, std::span<const CellId> local, bool distributed);

}  // namespace hotmesh::deform::detail
