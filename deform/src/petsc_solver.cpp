// hotmesh deform: the assembled linear solver on PETSc (SolverOptions::linear = amg).
//
// Per Newton step, in one pass over the cells (update()): every K_e is computed at the current
// points (not stored), K_e u_e added to the Newton residual, and K~_e = T_e^T K_e T_e in the
// nodal frames of the current normals (nodal_frames.hpp) added into a matrix of block size d
// whose sparsity was preallocated once from the node graph, slaves merged into their masters
// (MAT_NEW_NONZERO_LOCATION_ERR guards it). Then (solve()) the right-hand side is r~ = T^T r,
// CG (KSPCG, stopping on the unpreconditioned residual as the matrix-free PCG does) with
// algebraic multigrid solves K~ p~ = r~ from p~ = 0, and p = T p~. PCGAMG gets the
// translations written in the frames as near-null space.
//
// The multigrid hierarchy is built at the first Newton step of an increment and kept for
// the later steps of the increment (KSPSetReusePreconditioner): K changes little between
// them, the old hierarchy stays a symmetric positive definite preconditioner, and rebuilding
// it costs more than the few extra CG iterations (docs/performance.md). PETSC_OPTIONS
// `-hotmesh_amg_reuse none|interpolation|preconditioner` changes that (interpolation: GAMG
// keeps its aggregates and prolongators and recomputes the Galerkin operators); any option
// of the KSP and PC can be given with the prefix `hotmesh_`, e.g.
// PETSC_OPTIONS="-hotmesh_pc_gamg_threshold 0.05 -hotmesh_ksp_view".
//
// With several processes (mpirun, hotmesh/deform/processes.hpp) every rank keeps the whole
// mesh, but the matrix and the element work are distributed: PETSc's partitioner (PT-Scotch)
// splits the cells along their faces, each node's block row goes to the lowest rank among its
// cells (rows numbered rank by rank, so each rank owns a contiguous range), each rank computes
// the K_e of its cells and adds them with MatSetValuesBlocked (PETSc sends the rows owned
// elsewhere; later assemblies add straight into the values of the rank's own rows), the
// residual is summed over the ranks, CG and the multigrid run on the distributed matrix, and
// the solution is gathered on every rank. With one process the same code runs on
// PETSC_COMM_SELF.
#include "petsc_solver.hpp"

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "parallel.hpp"
#include "rank_exchange.hpp"

namespace hotmesh::deform::detail {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc failed in ") + what + " (error code " + std::to_string(code) + ")");
}

void default_option(const char* name, const char* value) {
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
  if (!set) check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
}

// --- The matrix K~ in nodal frames -------------------------------------------------------

/// The cells around each node (CSR).
struct NodeCells {
  std::vector<std::int64_t> start;
  std::vector<CellId> cells;

  NodeCells(const ElementList& list, std::size_t nodes) : start(nodes + 1, 0) {
    for (NodeId n : list.all_nodes()) ++start[static_cast<std::size_t>(n) + 1];
    for (std::size_t i = 1; i <= nodes; ++i) start[i] += start[i - 1];
    std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
    cells.resize(static_cast<std::size_t>(start.back()));
    for (std::size_t c = 0; c < list.size(); ++c) {
      for (NodeId n : list.nodes(c)) cells[static_cast<std::size_t>(fill[static_cast<std::size_t>(n)]++)] = static_cast<CellId>(c);
    }
  }
  std::span<const CellId> of(std::size_t node) const {
    return {cells.data() + start[node], static_cast<std::size_t>(start[node + 1] - start[node])};
  }
};

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

/// The rank that does each cell's element work. With several processes: PETSc's partitioner
/// (PT-Scotch by default, -hotmesh_mat_partitioning_type to change) on the graph of cells
/// that share a face (d nodes or more), each rank giving the edges of its share of the cells.
std::vector<int> partition_cells(const ElementList& list, const NodeCells& around, int d, const Processes& job) {
  std::vector<int> rank_of(list.size(), 0);
  if (job.count == 1) return rank_of;
  const Share mine = share_of(list.size(), job.rank, job.count);
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

/// The block rows of the matrix: one per node with at least one unknown (free or sliding);
/// a slave shares its master's. Fixed nodes (and slaves of fixed masters) have none and are
/// left out: as rows holding only a diagonal they would be isolated vertices of the matrix
/// graph, which PCGAMG makes aggregates of one node (whose d rows cannot carry the rigid-body
/// rotations, see AmgSolver::rotations_), and work for nothing. The set does not change
/// during a run: sliding nodes keep at least one tangential direction. A node's row belongs
/// to the lowest rank among its cells; rows are numbered rank by rank, nodes in order within
/// a rank (with one process: in node order).
struct BlockRows {
  std::vector<PetscInt> of_node;  ///< block row of each node's unknowns (a slave: its master's), -1 for none
  std::vector<NodeId> node_of;    ///< the node each block row belongs to
  std::vector<PetscInt> first;    ///< rank r owns the block rows [first[r], first[r + 1])
  PetscInt count = 0;

  BlockRows(const NodalFrames& frames, const NodeCells& around, std::span<const int> rank_of_cell, int ranks)
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
  PetscInt operator[](NodeId n) const { return of_node[static_cast<std::size_t>(n)]; }
  PetscInt begin(int rank) const { return first[static_cast<std::size_t>(rank)]; }
  PetscInt end(int rank) const { return first[static_cast<std::size_t>(rank) + 1]; }

  /// A full vector (d entries per node) at the block rows, and back (zero elsewhere).
  void gather(std::span<const double> full, std::span<double> rows, std::size_t d) const {
    for (std::size_t r = 0; r < node_of.size(); ++r) {
      const auto n = static_cast<std::size_t>(node_of[r]);
      for (std::size_t i = 0; i < d; ++i) rows[r * d + i] = full[n * d + i];
    }
  }
  void scatter(std::span<const double> rows, std::span<double> full, std::size_t d) const {
    std::fill(full.begin(), full.end(), 0.0);
    for (std::size_t r = 0; r < node_of.size(); ++r) {
      const auto n = static_cast<std::size_t>(node_of[r]);
      for (std::size_t i = 0; i < d; ++i) full[n * d + i] = rows[r * d + i];
    }
  }
};

/// A square matrix of block size d over the block rows, the rows of `rank` stored by it,
/// preallocated from the node graph with slaves merged into their masters.
Mat create_frame_matrix(const ElementList& cells, const NodeCells& around, const NodalFrames& frames,
                        const BlockRows& rows, const Processes& job) {
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

/// The order cells are assembled in: the colours of the stiffness operator (no two cells of
/// a colour share a node, so threads may add into the matrix side by side), without the
/// cells that hold a periodic slave, which write into their masters' rows and come last, one
/// after another.
struct AssemblyOrder {
  std::vector<std::vector<CellId>> colours;
  std::vector<CellId> with_slaves;

  AssemblyOrder(const StiffnessOperator& k, const NodalFrames& frames) {
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
};

/// Where an element pass takes K_e from: the stored matrices, or element_stiffness at the
/// system's points (no storage: 4.6 kB per hex saved, the matrices computed once per pass).
/// With `u` given, the pass also adds K_e u_e into `r` (the Newton residual, before folding).
struct ElementPass {
  const ConstrainedSystem& s;
  std::span<const double> u;
  std::span<double> r;

  const double* matrix(CellId c, std::span<double> scratch) const {
    if (s.stiffness.stores_matrices()) return s.stiffness.element_matrix(c).data();
    s.stiffness.element_matrix_at(c, s.points, scratch);
    return scratch.data();
  }
  void residual(std::span<const NodeId> nodes, const double* ke, std::size_t n, std::size_t d) const {
    if (u.empty()) return;
    std::array<double, 24> ue{};
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      for (std::size_t i = 0; i < d; ++i) ue[a * d + i] = u[static_cast<std::size_t>(nodes[a]) * d + i];
    }
    for (std::size_t row = 0; row < n; ++row) {
      double sum = 0.0;
      for (std::size_t j = 0; j < n; ++j) sum += ke[row * n + j] * ue[j];
      r[static_cast<std::size_t>(nodes[row / d]) * d + row % d] += sum;
    }
  }
};

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

/// K~ into the preallocated `a`, from the K_e of this rank's cells `local` (and their part of
/// the residual, see ElementPass). The first assembly goes through MatSetValuesBlocked and
/// fixes the sparsity; later ones add each block straight into the AIJ values of this rank's
/// rows (diagonal part and, when the matrix is distributed, off-diagonal part, whose columns
/// PETSc numbers in the sorted order of `garray`), and only the blocks of rows owned by
/// other ranks go through MatSetValuesBlocked. With one process the cells of a colour are
/// added in parallel.
void assemble_frame_matrix(Mat a, const ElementPass& pass, const NodalFrames& frames, const BlockRows& rows,
                           const AssemblyOrder& order, std::span<const CellId> local, bool first) {
  const ConstrainedSystem& s = pass.s;
  const ElementList& cells = s.stiffness.cells();
  const auto d = static_cast<std::size_t>(frames.dimension());
  const auto bs = static_cast<PetscInt>(d);
  const auto n = static_cast<std::size_t>(s.stiffness.element_size());
  const std::size_t corners = n / d;
  if (first) {
    std::array<double, 24 * 24> scratch{}, values{};
    std::array<std::int32_t, 8> owners{};
    for (const CellId cell : local) {
      const auto c = static_cast<std::size_t>(cell);
      const double* ke = pass.matrix(cell, {scratch.data(), n * n});
      pass.residual(cells.nodes(c), ke, n, d);
      frames.transform_element(cells.nodes(c), {ke, n * n}, {values.data(), n * n}, {owners.data(), corners});
      std::array<PetscInt, 8> index{};  // negative for a fixed node: PETSc skips it
      for (std::size_t k = 0; k < corners; ++k) index[k] = rows[owners[k]];
      check(MatSetValuesBlocked(a, static_cast<PetscInt>(corners), index.data(), static_cast<PetscInt>(corners), index.data(),
                                values.data(), ADD_VALUES),
            "MatSetValuesBlocked");
    }
    check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    check(MatSetOption(a, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
    return;
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
      std::array<double, 24 * 24> scratch{}, values{};
      std::array<std::int32_t, 8> owners{};
      std::array<PetscInt, 8> index{};
      const auto nodes = cells.nodes(static_cast<std::size_t>(cell));
      const double* ke = pass.matrix(cell, {scratch.data(), n * n});
      pass.residual(nodes, ke, n, d);
      frames.transform_element(nodes, {ke, n * n}, {values.data(), n * n}, {owners.data(), corners});
      for (std::size_t k = 0; k < corners; ++k) index[k] = rows[owners[k]];
      for (std::size_t p = 0; p < corners; ++p) {
        const PetscInt row = index[p];
        if (row < 0) continue;
        const double* block_row = values.data() + p * d * n;
        if (row < first_row || row >= end_row) {  // another rank's row: PETSc sends it
          if (!may_send) throw std::logic_error("assemble_frame_matrix: a row of another rank in a parallel loop");
          check(MatSetValuesBlocked(a, 1, &row, static_cast<PetscInt>(corners), index.data(), block_row, ADD_VALUES),
                "MatSetValuesBlocked");
          continue;
        }
        for (std::size_t q = 0; q < corners; ++q) {
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
    if (distributed) {
      for (const CellId cell : local) add(cell, true);
    } else {
      for (const auto& colour : order.colours) {
        const auto count = static_cast<std::ptrdiff_t>(colour.size());
#pragma omp parallel for schedule(static) if (count >= kParallelCells)
        for (std::ptrdiff_t k = 0; k < count; ++k) add(colour[static_cast<std::size_t>(k)], false);
      }
      for (const CellId cell : order.with_slaves) add(cell, false);
    }
  }  // the values are given back before PETSc adds the rows other ranks sent
  if (distributed) {
    check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
}

/// The part of `full` (every row) that this rank owns of `to`.
void copy_to(std::span<const double> full, Vec to) {
  PetscInt lo = 0, hi = 0;
  check(VecGetOwnershipRange(to, &lo, &hi), "VecGetOwnershipRange");
  PetscScalar* x = nullptr;
  check(VecGetArrayWrite(to, &x), "VecGetArrayWrite");
  std::copy(full.begin() + lo, full.begin() + hi, x);
  check(VecRestoreArrayWrite(to, &x), "VecRestoreArrayWrite");
}

void copy_from(Vec from, std::span<double> to) {
  const PetscScalar* x = nullptr;
  check(VecGetArrayRead(from, &x), "VecGetArrayRead");
  std::copy(x, x + to.size(), to.begin());
  check(VecRestoreArrayRead(from, &x), "VecRestoreArrayRead");
}

/// The rigid-body modes in the frames as the matrix's near-null space (PCGAMG's aggregates
/// interpolate them exactly).
void set_near_null_space(Mat a, const NodalFrames& frames, const BlockRows& rows, std::span<const Vec3> points,
                         bool rotations) {
  const auto modes = frames.near_null_space(points, rotations);
  const auto d = static_cast<std::size_t>(frames.dimension());
  std::vector<double> compressed(static_cast<std::size_t>(rows.count) * d);
  std::vector<Vec> vectors(modes.size(), nullptr);
  for (std::size_t k = 0; k < modes.size(); ++k) {
    check(MatCreateVecs(a, &vectors[k], nullptr), "MatCreateVecs");
    rows.gather(modes[k], compressed, d);  // the modes vanish on the nodes left out: still orthonormal
    copy_to(compressed, vectors[k]);
  }
  MatNullSpace space = nullptr;
  check(MatNullSpaceCreate(PetscObjectComm(reinterpret_cast<PetscObject>(a)), PETSC_FALSE, static_cast<PetscInt>(vectors.size()), vectors.data(), &space),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(a, space), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&space), "MatNullSpaceDestroy");
  for (Vec& v : vectors) check(VecDestroy(&v), "VecDestroy");
}

// --- The solver ---------------------------------------------------------------------------

enum class Reuse { none, interpolation, preconditioner };

class AmgSolver final : public LinearSolver {
 public:
  explicit AmgSolver(const SolverOptions& options) : options_(options), job_(processes()) {
    start_petsc();
    if (options_.amg == AmgPackage::gamg) {
      // One symmetric Gauss-Seidel sweep as smoother on every level. The default Chebyshev/
      // Jacobi smoother made the preconditioner indefinite on the ramp: its eigenvalue
      // estimates miss the top of the spectrum of these boundary-layer matrices.
      default_option("-hotmesh_mg_levels_ksp_type", "richardson");
      default_option("-hotmesh_mg_levels_pc_type", "sor");
    } else {
      // BoomerAMG for elasticity: the d components of a node coarsened together.
      default_option("-hotmesh_pc_hypre_boomeramg_nodal_coarsen", "6");
      default_option("-hotmesh_pc_hypre_boomeramg_strong_threshold", "0.5");
    }
    // BoomerAMG kept across Newton steps needed 20 times the iterations on the ramp; its
    // set-up is cheap, so hypre rebuilds every step.
    std::array<char, 32> reuse{};
    std::strcpy(reuse.data(), options_.amg == AmgPackage::hypre ? "none" : "preconditioner");
    PetscBool set = PETSC_FALSE;
    check(PetscOptionsGetString(nullptr, "hotmesh_", "-amg_reuse", reuse.data(), reuse.size(), &set), "PetscOptionsGetString");
    const std::string r = reuse.data();
    reuse_ = r == "none" ? Reuse::none : r == "preconditioner" ? Reuse::preconditioner : Reuse::interpolation;
    if (options_.amg == AmgPackage::hypre && reuse_ == Reuse::interpolation) reuse_ = Reuse::none;  // GAMG only
    check(PetscOptionsGetBool(nullptr, "hotmesh_", "-amg_rotations", &rotations_, &set), "PetscOptionsGetBool");
  }

  ~AmgSolver() override {
    if (ksp_) KSPDestroy(&ksp_);
    if (to_all_) VecScatterDestroy(&to_all_);
    if (all_) VecDestroy(&all_);
    if (b_) VecDestroy(&b_);
    if (x_) VecDestroy(&x_);
    if (a_) MatDestroy(&a_);
  }
  AmgSolver(const AmgSolver&) = delete;
  AmgSolver& operator=(const AmgSolver&) = delete;

  void begin_increment() override { fresh_ = true; }

  /// Without stored element matrices: one pass computes every K_e, adds its part of the
  /// residual and assembles K~ (the matrix is then ready for solve()).
  void update(StiffnessOperator& k, const ConstrainedSystem& s, std::span<const double> u, std::span<double> r,
              MotionTimings& timings) override {
    if (k.stores_matrices()) {
      LinearSolver::update(k, s, u, r, timings);
      return;
    }
    const auto t = Clock::now();
    std::fill(r.begin(), r.end(), 0.0);
    assemble(s, u, r);
    sum_over_processes(r);  // each rank added its cells' part
    s.periodic.fold(r);
    s.constraints.project(r);
    timings.assembly += seconds_since(t);
  }

  LinearSolveResult solve(const ConstrainedSystem& s, std::span<const double> rhs, std::span<double> p, double tolerance,
                          MotionTimings& timings) override {
    auto t = Clock::now();
    if (!assembled_) assemble(s, {}, {});  // from the stored element matrices
    assembled_ = false;
    timings.assembly += seconds_since(t);
    const auto d = static_cast<std::size_t>(s.stiffness.dofs_per_node());
    frames_->to_frames(rhs, full_);
    rows_->gather(full_, rhs_, d);
    LinearSolveResult result;
    const double initial = norm2(rhs_);
    if (!(initial > 0.0)) {
      std::fill(p.begin(), p.end(), 0.0);
      result.converged = true;
      return result;
    }
    t = Clock::now();
    const bool rebuild = fresh_ || reuse_ == Reuse::none;
    if (rebuild) set_near_null_space(a_, *frames_, *rows_, s.points, rotations_);
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    if (reuse_ == Reuse::interpolation) check(PCGAMGSetReuseInterpolation(pc, fresh_ ? PETSC_FALSE : PETSC_TRUE), "PCGAMGSetReuseInterpolation");
    check(KSPSetReusePreconditioner(ksp_, reuse_ == Reuse::preconditioner && !fresh_ ? PETSC_TRUE : PETSC_FALSE),
          "KSPSetReusePreconditioner");
    check(KSPSetOperators(ksp_, a_, a_), "KSPSetOperators");
    check(KSPSetTolerances(ksp_, tolerance, 1e-300, PETSC_DEFAULT, options_.max_pcg_iterations), "KSPSetTolerances");
    check(KSPSetUp(ksp_), "KSPSetUp");
    timings.preconditioner += seconds_since(t);

    t = Clock::now();
    copy_to(rhs_, b_);
    check(KSPSolve(ksp_, b_, x_), "KSPSolve");
    PetscInt iterations = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    PetscReal residual = 0.0;
    check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
    check(KSPGetResidualNorm(ksp_, &residual), "KSPGetResidualNorm");
    gather_solution();
    rows_->scatter(solution_, full_, d);
    frames_->from_frames(full_, p);
    timings.solve += seconds_since(t);
    fresh_ = false;

    result.iterations = static_cast<int>(iterations);
    result.converged = reason > 0;
    result.breakdown = reason == KSP_DIVERGED_INDEFINITE_MAT || reason == KSP_DIVERGED_INDEFINITE_PC ||
                       reason == KSP_DIVERGED_BREAKDOWN || reason == KSP_DIVERGED_NANORINF ||
                       reason == KSP_DIVERGED_PC_FAILED;
    result.reduction = residual / initial;
    return result;
  }

 private:
  /// K~ of the system at its points, with the frames of its current normals.
  void assemble(const ConstrainedSystem& s, std::span<const double> u, std::span<double> r) {
    if (!a_) create(s);
    frames_->update(s.constraints, s.periodic);
    assemble_frame_matrix(a_, {s, u, r}, *frames_, *rows_, *order_, local_cells_, !pattern_);
    pattern_ = true;
    assembled_ = true;
  }

  void create(const ConstrainedSystem& s) {
    const int d = s.stiffness.dofs_per_node();
    const std::size_t nodes = s.stiffness.size() / static_cast<std::size_t>(d);
    frames_.emplace(nodes, d);
    frames_->update(s.constraints, s.periodic);
    const ElementList& cells = s.stiffness.cells();
    const NodeCells around(cells, nodes);
    const std::vector<int> rank_of_cell = partition_cells(cells, around, d, job_);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (rank_of_cell[c] == job_.rank) local_cells_.push_back(static_cast<CellId>(c));
    }
    rows_.emplace(*frames_, around, rank_of_cell, job_.count);
    order_.emplace(s.stiffness, *frames_);
    a_ = create_frame_matrix(cells, around, *frames_, *rows_, job_);
    check(MatCreateVecs(a_, &x_, &b_), "MatCreateVecs");
    if (job_.count > 1) check(VecScatterCreateToAll(x_, &to_all_, &all_), "VecScatterCreateToAll");
    full_.assign(s.stiffness.size(), 0.0);
    rhs_.assign(static_cast<std::size_t>(rows_->count) * static_cast<std::size_t>(d), 0.0);
    solution_.assign(rhs_.size(), 0.0);

    check(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(a_)), &ksp_), "KSPCreate");
    check(KSPSetOptionsPrefix(ksp_, "hotmesh_"), "KSPSetOptionsPrefix");
    check(KSPSetType(ksp_, KSPCG), "KSPSetType");
    // Stop on ||b - A x|| <= tol ||b||, as the matrix-free PCG does.
    check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    if (options_.amg == AmgPackage::gamg) {
      check(PCSetType(pc, PCGAMG), "PCSetType");
      check(PCGAMGSetType(pc, PCGAMGAGG), "PCGAMGSetType");
      check(PCGAMGSetNSmooths(pc, 1), "PCGAMGSetNSmooths");  // smoothed aggregation
      PetscReal threshold[] = {0.02};
      check(PCGAMGSetThreshold(pc, threshold, 1), "PCGAMGSetThreshold");
    } else {
      check(PCSetType(pc, PCHYPRE), "PCSetType");
      check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    }
    check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  }

  /// The solution on every rank (the whole vector: each keeps the whole mesh).
  void gather_solution() {
    if (!to_all_) {
      copy_from(x_, solution_);
      return;
    }
    check(VecScatterBegin(to_all_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(to_all_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    copy_from(all_, solution_);
  }

  SolverOptions options_;
  Processes job_;
  std::vector<CellId> local_cells_;  ///< the cells whose element work this rank does
  Reuse reuse_ = Reuse::preconditioner;
  /// Rotations in the near-null space (-hotmesh_amg_rotations). Off: PCGAMG of PETSc 3.18
  /// makes aggregates of one node here and there, whose d rows cannot carry 3 (2D) or 6 (3D)
  /// modes; their prolongator columns vanish, the coarse matrices get zero rows and the
  /// smoother fails (the sliding ramp, the stator well). With the d translations alone every
  /// aggregate has enough rows.
  PetscBool rotations_ = PETSC_FALSE;
  std::optional<NodalFrames> frames_;
  std::optional<BlockRows> rows_;
  std::optional<AssemblyOrder> order_;
  Mat a_ = nullptr;
  KSP ksp_ = nullptr;
  Vec b_ = nullptr;
  Vec x_ = nullptr;
  VecScatter to_all_ = nullptr;  ///< x_ to all_ on every rank (several processes)
  Vec all_ = nullptr;
  bool fresh_ = true;
  bool pattern_ = false;    ///< the sparsity is fixed (after the first assembly)
  bool assembled_ = false;  ///< update() assembled K~ for the coming solve()
  std::vector<double> full_;             ///< d per node, in the frames
  std::vector<double> rhs_, solution_;  ///< d per block row
};

}  // namespace

std::unique_ptr<LinearSolver> make_amg_solver(const SolverOptions& options) { return std::make_unique<AmgSolver>(options); }

std::vector<double> assembled_frame_product(const ConstrainedSystem& system, const NodalFrames& frames,
                                            std::span<const double> x, bool twice) {
  start_petsc();
  const ElementList& cells = system.stiffness.cells();
  const NodeCells around(cells, frames.node_count());
  const Processes one;
  const std::vector<int> rank_of_cell(cells.size(), 0);
  const BlockRows rows(frames, around, rank_of_cell, one.count);
  const auto d = static_cast<std::size_t>(frames.dimension());
  const AssemblyOrder order(system.stiffness, frames);
  std::vector<CellId> all(cells.size());
  std::iota(all.begin(), all.end(), CellId{0});
  Mat a = create_frame_matrix(cells, around, frames, rows, one);
  assemble_frame_matrix(a, {system, {}, {}}, frames, rows, order, all, true);
  if (twice) assemble_frame_matrix(a, {system, {}, {}}, frames, rows, order, all, false);
  Vec vx = nullptr, vy = nullptr;
  check(MatCreateVecs(a, &vx, &vy), "MatCreateVecs");
  std::vector<double> compressed(static_cast<std::size_t>(rows.count) * d);
  rows.gather(x, compressed, d);
  copy_to(compressed, vx);
  check(MatMult(a, vx, vy), "MatMult");
  copy_from(vy, compressed);
  std::vector<double> y(x.size());
  rows.scatter(compressed, y, d);
  VecDestroy(&vx);
  VecDestroy(&vy);
  MatDestroy(&a);
  return y;
}

}  // namespace hotmesh::deform::detail
