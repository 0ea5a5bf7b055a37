// hotmesh deform: the matrix of the amg solver in nodal frames (frame_matrix.hpp): the cell
// partition among ranks, the block rows and their owners, preallocation and assembly.
#include "storage/frame_matrix.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>  // setenv (POSIX)
#include <optional>
#include <vector>

#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform::detail {

namespace {

/// A copy in memory from PetscMalloc, for PETSc to free.
PetscInt* petsc_copy(const std::vector<PetscInt>& v) {
  PetscInt* copy = nullptr;
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
  check(PetscMalloc1(std::max<std::size_t>(v.size(), 1), &copy), "PetscMalloc1");
#pragma GCC diagnostic pop
  std::copy(v.begin(), v.end(), copy);
  return copy;
}

}  // namespace

std::vector<int> partition_cells(const ElementList& list, const NodeCells& around, int d, const parallel::Processes& job) {
  std::vector<int> rank_of(list.size(), 0);
  if (job.count == 1) return rank_of;
  const parallel::Share mine = parallel::share_of(list.size(), job.rank, job.count);
  std::vector<PetscInt> offsets{0}, neighbours;
  std::vector<CellId> touching;
  for (std::size_t c = mine.begin; c < mine.end; ++c) {
    touching.clear();
    for (NodeId n : list.nodes(c)) {
      for (CellId other : around.of(static_cast<std::size_t>(n))) {
        if (other != static_cast<CellId>(c)) touching.push_back(other);
      }
    }
    std::sort(touching.begin(), touching.end());
    for (std::size_t i = 0; i < touching.size();) {
      std::size_t j = i;
      while (j < touching.size() && touching[j] == touching[i]) ++j;
      if (static_cast<int>(j - i) >= d) neighbours.push_back(static_cast<PetscInt>(touching[i]));
      i = j;
    }
    offsets.push_back(static_cast<PetscInt>(neighbours.size()));
  }
  // MatCreateMPIAdj takes arrays from PetscMalloc and frees them with the matrix.
  PetscInt* ia = petsc_copy(offsets);
  PetscInt* ja = petsc_copy(neighbours);
  Mat graph = nullptr;
  check(MatCreateMPIAdj(PETSC_COMM_WORLD, static_cast<PetscInt>(mine.end - mine.begin), static_cast<PetscInt>(list.size()),
                        ia, ja, nullptr, &graph),
        "MatCreateMPIAdj");
  MatPartitioning partitioner = nullptr;
  check(MatPartitioningCreate(PETSC_COMM_WORLD, &partitioner), "MatPartitioningCreate");
  check(MatPartitioningSetAdjacency(partitioner, graph), "MatPartitioningSetAdjacency");
  check(MatPartitioningSetType(partitioner, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType");
  check(PetscObjectSetOptionsPrefix(reinterpret_cast<PetscObject>(partitioner), "hotmesh_"), "PetscObjectSetOptionsPrefix");
  check(MatPartitioningSetFromOptions(partitioner), "MatPartitioningSetFromOptions");
  // PT-Scotch's threaded algorithms let the partition depend on how the threads are scheduled:
  // on a loaded machine two runs of one case on two ranks took other CG iterations and wrote
  // other meshes (2 runs in 6 on the 18 000-cell sector). One thread per rank makes the
  // partition, and so the run, the same every time; a user's SCOTCH_PTHREAD_NUMBER stands.
  setenv("SCOTCH_PTHREAD_NUMBER", "1", 0);
  IS part = nullptr, all = nullptr;
  check(MatPartitioningApply(partitioner, &part), "MatPartitioningApply");
  check(ISAllGather(part, &all), "ISAllGather");
  const PetscInt* ranks = nullptr;
  check(ISGetIndices(all, &ranks), "ISGetIndices");
  std::copy(ranks, ranks + list.size(), rank_of.begin());
  check(ISRestoreIndices(all, &ranks), "ISRestoreIndices");
  ISDestroy(&all);
  ISDestroy(&part);
  MatPartitioningDestroy(&partitioner);
  MatDestroy(&graph);
  return rank_of;
}

BlockRows::BlockRows(const NodalFrames& frames, const NodeCells& around, std::span<const int> rank_of_cell, int ranks)
    : of_node(frames.node_count(), -1), first(static_cast<std::size_t>(ranks) + 1, 0) {
  const int d = frames.dimension();
  std::vector<int> owner(of_node.size(), 0);
  for (std::size_t n = 0; n < of_node.size(); ++n) {
    const auto node = static_cast<NodeId>(n);
    if (frames.is_slave(node) || frames.constrained(node) == d) {
      owner[n] = -1;
      continue;
    }
    int lowest = ranks;
    for (CellId c : around.of(n)) lowest = std::min(lowest, rank_of_cell[static_cast<std::size_t>(c)]);
    owner[n] = lowest == ranks ? 0 : lowest;
    ++first[static_cast<std::size_t>(owner[n]) + 1];
  }
  for (std::size_t r = 1; r < first.size(); ++r) first[r] += first[r - 1];
  count = first.back();
  node_of.resize(static_cast<std::size_t>(count));
  std::vector<PetscInt> next(first.begin(), first.end() - 1);
  for (std::size_t n = 0; n < of_node.size(); ++n) {
    if (owner[n] < 0) continue;
    const PetscInt row = next[static_cast<std::size_t>(owner[n])]++;
    of_node[n] = row;
    node_of[static_cast<std::size_t>(row)] = static_cast<NodeId>(n);
  }
  for (std::size_t n = 0; n < of_node.size(); ++n) {
    const auto node = static_cast<NodeId>(n);
    if (frames.is_slave(node)) of_node[n] = of_node[static_cast<std::size_t>(frames.owner(node))];
  }
}

void BlockRows::gather(std::span<const double> full, std::span<double> rows, std::size_t d, PetscInt first_row) const {
  for (std::size_t r = 0; r < rows.size() / d; ++r) {
    const auto n = static_cast<std::size_t>(node_of[static_cast<std::size_t>(first_row) + r]);
    for (std::size_t i = 0; i < d; ++i) rows[r * d + i] = full[n * d + i];
  }
}
void BlockRows::scatter(std::span<const double> rows, std::span<double> full, std::size_t d) const {
  std::fill(full.begin(), full.end(), 0.0);
  for (std::size_t r = 0; r < node_of.size(); ++r) {
    const auto n = static_cast<std::size_t>(node_of[r]);
    for (std::size_t i = 0; i < d; ++i) full[n * d + i] = rows[r * d + i];
  }
}

Mat create_frame_matrix(const ElementList& cells, const NodeCells& around, const NodalFrames& frames,
                        const BlockRows& rows, const parallel::Processes& job) {
  const int d = frames.dimension();
  const PetscInt lo = rows.begin(job.rank), hi = rows.end(job.rank);
  // Every node adds the blocks of its cells' nodes to its own block row (a master's row thus
  // gathers its slaves' neighbours too); columns in [lo, hi) are the diagonal part.
  std::vector<std::vector<NodeId>> members(static_cast<std::size_t>(hi - lo));
  for (std::size_t n = 0; n < frames.node_count(); ++n) {
    const PetscInt row = rows[static_cast<NodeId>(n)];
    if (row >= lo && row < hi) members[static_cast<std::size_t>(row - lo)].push_back(static_cast<NodeId>(n));
  }
  std::vector<PetscInt> diagonal(members.size(), 0), off_diagonal(members.size(), 0);
  std::vector<PetscInt> mark(static_cast<std::size_t>(rows.count), -1);
  for (PetscInt row = lo; row < hi; ++row) {
    for (const NodeId member : members[static_cast<std::size_t>(row - lo)]) {
      for (CellId c : around.of(static_cast<std::size_t>(member))) {
        for (NodeId n : cells.nodes(static_cast<std::size_t>(c))) {
          const PetscInt column = rows[n];
          if (column < 0 || mark[static_cast<std::size_t>(column)] == row) continue;
          mark[static_cast<std::size_t>(column)] = row;
          ++(column >= lo && column < hi ? diagonal : off_diagonal)[static_cast<std::size_t>(row - lo)];
        }
      }
    }
  }
  const PetscInt local = (hi - lo) * d, size = rows.count * d;
  Mat a = nullptr;
  check(MatCreate(job.count > 1 ? PETSC_COMM_WORLD : PETSC_COMM_SELF, &a), "MatCreate");
  check(MatSetSizes(a, local, local, size, size), "MatSetSizes");
  check(MatSetBlockSize(a, d), "MatSetBlockSize");
  check(MatSetType(a, MATAIJ), "MatSetType");
  check(MatSetOptionsPrefix(a, "hotmesh_"), "MatSetOptionsPrefix");
  check(MatSetFromOptions(a), "MatSetFromOptions");
  check(MatXAIJSetPreallocation(a, d, diagonal.data(), off_diagonal.data(), nullptr, nullptr), "MatXAIJSetPreallocation");
  check(MatSetOption(a, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(a, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  // Every assembly sends the same rows to the same ranks: PETSc keeps the pattern.
  check(MatSetOption(a, MAT_SUBSET_OFF_PROC_ENTRIES, PETSC_TRUE), "MatSetOption");
  return a;
}

AssemblyOrder::AssemblyOrder(const StiffnessKernel& k, const NodalFrames& frames) {
  const CellColoring& coloring = k.coloring();
  for (std::size_t c = 0; c < coloring.colors(); ++c) {
    colours.emplace_back();
    for (auto i = coloring.offsets[c]; i < coloring.offsets[c + 1]; ++i) {
      const CellId cell = coloring.cells[static_cast<std::size_t>(i)];
      const auto nodes = k.cells().nodes(static_cast<std::size_t>(cell));
      const bool slave = std::any_of(nodes.begin(), nodes.end(), [&](NodeId n) { return frames.is_slave(n); });
      (slave ? with_slaves : colours.back()).push_back(cell);
    }
  }
}

void ElementPass::element(CellId cell, std::span<double> ke) const {
  s.kernel.element_matrix(cell, s.points, ke);
  if (residual) residual->add(s.kernel.cells().nodes(static_cast<std::size_t>(cell)), ke);
}

void ElementPass::frame_element(CellId cell, const NodalFrames& frames, const BlockRows& rows, FrameElement& out) const {
  const auto d = static_cast<std::size_t>(frames.dimension());
  const auto nodes = s.kernel.cells().nodes(static_cast<std::size_t>(cell));
  const std::size_t corners = nodes.size();
  const std::size_t n = corners * d;
  std::array<double, kMaxElementDofs * kMaxElementDofs> scratch{};
  const double* ke = scratch.data();
  element(cell, {scratch.data(), n * n});
  std::array<std::int32_t, mesh::kMaxElementNodes> owners{};
  frames.transform_element(nodes, {ke, n * n}, {out.values.data(), n * n}, {owners.data(), corners});
  for (std::size_t k = 0; k < corners; ++k) out.index[k] = rows[owners[k]];
  out.corners = corners;
}

namespace {

/// Calls fn(cell, may_send) for this rank's cells: with several ranks its `local` cells in order
/// (may_send: rows of other ranks go through PETSc); with one the cells of each colour in
/// parallel, then the cells with periodic slaves one after another.
template <class Fn>
void for_each_cell(const AssemblyOrder& order, std::span<const CellId> local, bool distributed, const Fn& fn) {
  if (distributed) {
    for (const CellId cell : local) fn(cell, true);
    return;
  }
  for (const auto& colour : order.colours) {
    const auto count = static_cast<std::ptrdiff_t>(colour.size());
    mesh::LoopExceptions errors;  // fn throws on a broken invariant
#pragma omp parallel for schedule(static) if (count >= mesh::kParallelCells)
    for (std::ptrdiff_t k = 0; k < count; ++k) errors.run([&] { fn(colour[static_cast<std::size_t>(k)], false); });
    errors.rethrow();
  }
  for (const CellId cell : order.with_slaves) fn(cell, false);
}

/// The stored values of one SeqAIJ part of the matrix (the whole matrix with one process; the
/// diagonal or the off-diagonal block of a rank's rows of an MPIAIJ matrix).
class AijValues {
 public:
  explicit AijValues(Mat part) : part_(part) {
    PetscBool done = PETSC_FALSE;
    check(MatGetRowIJ(part_, 0, PETSC_FALSE, PETSC_FALSE, &rows_, &ia_, &ja_, &done), "MatGetRowIJ");
    if (!done) throw std::runtime_error("PETSc: MatGetRowIJ gave no row structure");
    check(MatSeqAIJGetArray(part_, &v_), "MatSeqAIJGetArray");
    std::fill(v_, v_ + ia_[rows_], 0.0);
  }
  ~AijValues() {
    MatSeqAIJRestoreArray(part_, &v_);  // marks the values changed
    PetscBool done = PETSC_FALSE;
    MatRestoreRowIJ(part_, 0, PETSC_FALSE, PETSC_FALSE, &rows_, &ia_, &ja_, &done);
  }
  AijValues(const AijValues&) = delete;
  AijValues& operator=(const AijValues&) = delete;

  /// Adds the d x d block `in` (row stride `stride`) at local block row `row`, whose first
  /// column is the local scalar column `column`; the d rows of a block row share a pattern.
  void add(PetscInt row, PetscInt column, const double* in, std::size_t stride, std::size_t d) const {
    const auto bs = static_cast<PetscInt>(d);
    const PetscInt* begin = ja_ + ia_[row * bs];
    const auto k = std::lower_bound(begin, ja_ + ia_[row * bs + 1], column) - begin;
    for (std::size_t i = 0; i < d; ++i) {
      PetscScalar* out = v_ + ia_[row * bs + static_cast<PetscInt>(i)] + k;
      for (std::size_t j = 0; j < d; ++j) out[j] += in[i * stride + j];
    }
  }

 private:
  Mat part_;
  PetscInt rows_ = 0;
  const PetscInt* ia_ = nullptr;
  const PetscInt* ja_ = nullptr;
  PetscScalar* v_ = nullptr;
};

}  // namespace

void assemble_frame_matrix(Mat a, const ElementPass& pass, const NodalFrames& frames, const BlockRows& rows,
                           const AssemblyOrder& order, std::span<const CellId> local, bool first) {
  const auto d = static_cast<std::size_t>(frames.dimension());
  const auto bs = static_cast<PetscInt>(d);
  if (first) {  // the sparsity only (zero blocks, no K_e): the values are added below, as every later assembly adds them
    const std::vector<double> zeros(kMaxElementDofs * kMaxElementDofs, 0.0);
    std::array<PetscInt, mesh::kMaxElementNodes> index{};
    for (const CellId cell : local) {
      const auto nodes = pass.s.kernel.cells().nodes(static_cast<std::size_t>(cell));
      const auto corners = static_cast<PetscInt>(nodes.size());  // block rows and columns of K~_e
      for (std::size_t k = 0; k < nodes.size(); ++k) index[k] = rows[frames.owner(nodes[k])];
      check(MatSetValuesBlocked(a, corners, index.data(), corners, index.data(), zeros.data(), ADD_VALUES),
            "MatSetValuesBlocked");
    }
    check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    check(MatSetOption(a, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  }
  PetscBool distributed = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(a), MATMPIAIJ, &distributed), "PetscObjectTypeCompare");
  Mat diagonal_part = a, off_diagonal_part = nullptr;
  const PetscInt* garray = nullptr;  // global scalar column of each off-diagonal column, ascending
  if (distributed) check(MatMPIAIJGetSeqAIJ(a, &diagonal_part, &off_diagonal_part, &garray), "MatMPIAIJGetSeqAIJ");
  PetscInt lo = 0, hi = 0, off_columns = 0;
  check(MatGetOwnershipRange(a, &lo, &hi), "MatGetOwnershipRange");
  const PetscInt first_row = lo / bs, end_row = hi / bs;
  {
    const AijValues diagonal(diagonal_part);
    std::optional<AijValues> off;
    if (off_diagonal_part) {
      off.emplace(off_diagonal_part);
      check(MatGetSize(off_diagonal_part, nullptr, &off_columns), "MatGetSize");
    }
    const auto add = [&](CellId cell, bool may_send) {
      FrameElement e;
      pass.frame_element(cell, frames, rows, e);
      const auto& index = e.index;
      const auto corners = static_cast<PetscInt>(e.corners);  // block rows and columns of K~_e
      const std::size_t n = e.corners * d;
      for (std::size_t p = 0; p < static_cast<std::size_t>(corners); ++p) {
        const PetscInt row = index[p];
        if (row < 0) continue;
        const double* block_row = e.values.data() + p * d * n;
        if (row < first_row || row >= end_row) {  // another rank's row: PETSc sends it
          if (!may_send) throw std::logic_error("assemble_frame_matrix: a row of another rank in a parallel loop");
          check(MatSetValuesBlocked(a, 1, &row, corners, index.data(), block_row, ADD_VALUES),
                "MatSetValuesBlocked");
          continue;
        }
        for (std::size_t q = 0; q < static_cast<std::size_t>(corners); ++q) {
          const PetscInt column = index[q];
          if (column < 0) continue;
          if (column >= first_row && column < end_row) {
            diagonal.add(row - first_row, (column - first_row) * bs, block_row + q * d, n, d);
          } else {
            const auto k = std::lower_bound(garray, garray + off_columns, column * bs) - garray;
            off->add(row - first_row, static_cast<PetscInt>(k), block_row + q * d, n, d);
          }
        }
      }
    };
    for_each_cell(order, local, distributed, add);
  }  // the values are given back before PETSc adds the rows other ranks sent
  if (distributed) {
    check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
}

void residual_pass(const ElementPass& pass, const AssemblyOrder& order, std::span<const CellId> local, bool distributed) {
  const auto d = static_cast<std::size_t>(pass.s.kernel.dofs_per_node());
  for_each_cell(order, local, distributed, [&](CellId cell, bool) {
    const std::size_t n = pass.s.kernel.cells().nodes(static_cast<std::size_t>(cell)).size() * d;
    std::array<double, kMaxElementDofs * kMaxElementDofs> ke{};
    pass.element(cell, {ke.data(), n * n});
  });
}

void set_near_null_space(Mat a, const NodalFrames& frames, const BlockRows& rows) {
  const int d = frames.dimension();
  PetscInt lo = 0, hi = 0;
  check(MatGetOwnershipRange(a, &lo, &hi), "MatGetOwnershipRange");
  std::vector<Vec> modes;
  for (int k = 0; k < d; ++k) {
    Vec mode = nullptr;
    check(MatCreateVecs(a, &mode, nullptr), "MatCreateVecs");
    PetscScalar* x = nullptr;
    check(VecGetArrayWrite(mode, &x), "VecGetArrayWrite");
    // Q_n^T e_k at each of this rank's block rows: row k of Q_n, without the constrained
    // components (a row's node is never a slave: slaves share their master's row).
    for (PetscInt row = lo / d; row < hi / d; ++row) {
      const NodeId n = rows.node_of[static_cast<std::size_t>(row)];
      const std::span<const double> q = frames.frame(n);
      const int c = frames.constrained(n);
      for (int i = 0; i < d; ++i) x[(row - lo / d) * d + i] = i < c ? 0.0 : q[static_cast<std::size_t>(k * d + i)];
    }
    check(VecRestoreArrayWrite(mode, &x), "VecRestoreArrayWrite");
    // Modified Gram-Schmidt, twice, against the modes kept so far; a mode that vanishes on the
    // unknowns (a direction fixed everywhere) is dropped.
    PetscReal before = 0.0, after = 0.0;
    check(VecNorm(mode, NORM_2, &before), "VecNorm");
    for (int pass = 0; pass < 2; ++pass) {
      for (Vec kept : modes) {
        PetscScalar along = 0.0;
        check(VecDot(mode, kept, &along), "VecDot");
        check(VecAXPY(mode, -along, kept), "VecAXPY");
      }
    }
    check(VecNorm(mode, NORM_2, &after), "VecNorm");
    if (after > 1e-8 * before) {
      check(VecScale(mode, 1.0 / after), "VecScale");
      modes.push_back(mode);
    } else {
      check(VecDestroy(&mode), "VecDestroy");
    }
  }
  MatNullSpace space = nullptr;
  check(MatNullSpaceCreate(PetscObjectComm(reinterpret_cast<PetscObject>(a)), PETSC_FALSE,
                           static_cast<PetscInt>(modes.size()), modes.data(), &space),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(a, space), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&space), "MatNullSpaceDestroy");
  for (Vec& v : modes) check(VecDestroy(&v), "VecDestroy");
}

}  // namespace hotmesh::deform::detail
