// hotmesh deform: the test hooks of petsc_solver.hpp: the amg solver's matrix and near-null
// space, made by one process as the solver makes them.
#include <petscksp.h>

#include <algorithm>
#include <numeric>
#include <span>
#include <vector>

#include "hotmesh/parallel/processes.hpp"
#include "storage/frame_matrix.hpp"
#include "storage/petsc_solver.hpp"

namespace hotmesh::deform::detail {
namespace {

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

/// The matrix of `cells` in `frames` as one process makes it, preallocated (for the test hooks).
struct OneProcessMatrix {
  NodeCells around;
  BlockRows rows;
  Mat a = nullptr;
  std::vector<double> compressed;  ///< d values for each block row

  OneProcessMatrix(const ElementList& cells, const NodalFrames& frames)
      : around(cells, frames.node_count()),
        rows(frames, around, std::vector<int>(cells.size(), 0), 1),
        a(create(cells, frames)),
        compressed(static_cast<std::size_t>(rows.count) * static_cast<std::size_t>(frames.dimension())) {}
  ~OneProcessMatrix() { MatDestroy(&a); }

  Mat create(const ElementList& cells, const NodalFrames& frames) const {
    parallel::start_petsc();
    return create_frame_matrix(cells, around, frames, rows, parallel::Processes{});
  }
  OneProcessMatrix(const OneProcessMatrix&) = delete;
  OneProcessMatrix& operator=(const OneProcessMatrix&) = delete;
};

}  // namespace

std::vector<std::vector<double>> assembled_near_null_space(const ElementList& cells, const NodalFrames& frames) {
  OneProcessMatrix m(cells, frames);
  const auto d = static_cast<std::size_t>(frames.dimension());
  set_near_null_space(m.a, frames, m.rows);
  MatNullSpace space = nullptr;
  check(MatGetNearNullSpace(m.a, &space), "MatGetNearNullSpace");
  PetscBool constant = PETSC_FALSE;
  PetscInt count = 0;
  const Vec* vectors = nullptr;
  check(MatNullSpaceGetVecs(space, &constant, &count, &vectors), "MatNullSpaceGetVecs");
  std::vector<std::vector<double>> modes;
  for (PetscInt k = 0; k < count; ++k) {
    copy_from(vectors[k], m.compressed);
    modes.emplace_back(frames.node_count() * d);
    m.rows.scatter(m.compressed, modes.back(), d);
  }
  return modes;
}

std::vector<double> assembled_frame_product(const ConstrainedSystem& system, const NodalFrames& frames,
                                            std::span<const double> x, bool twice) {
  const ElementList& cells = system.kernel.cells();
  OneProcessMatrix m(cells, frames);
  const auto d = static_cast<std::size_t>(frames.dimension());
  const AssemblyOrder order(system.kernel, frames);
  std::vector<CellId> all(cells.size());
  std::iota(all.begin(), all.end(), CellId{0});
  assemble_frame_matrix(m.a, {system, nullptr}, frames, m.rows, order, all, true);
  if (twice) assemble_frame_matrix(m.a, {system, nullptr}, frames, m.rows, order, all, false);
  Vec vx = nullptr, vy = nullptr;
  check(MatCreateVecs(m.a, &vx, &vy), "MatCreateVecs");
  m.rows.gather(x, m.compressed, d);
  copy_to(m.compressed, vx);
  check(MatMult(m.a, vx, vy), "MatMult");
  copy_from(vy, m.compressed);
  std::vector<double> y(x.size());
  m.rows.scatter(m.compressed, y, d);
  VecDestroy(&vx);
  VecDestroy(&vy);
  return y;
}

}  // namespace hotmesh::deform::detail
