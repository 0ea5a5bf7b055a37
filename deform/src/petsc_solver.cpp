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
// MPI: this backend runs on PETSC_COMM_SELF today; every process solves the whole system.
// The distributed version (the item 3) keeps this structure: node ownership ranges
// for the block rows, MatXAIJSetPreallocation with diagonal and off-diagonal counts, the same
// MatSetValuesBlocked (PETSc stashes rows owned elsewhere) and vectors with ghosts.
#include "petsc_solver.hpp"

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "parallel.hpp"

namespace hotmesh::deform::detail {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc failed in ") + what + " (error code " + std::to_string(code) + ")");
}

// --- The PETSc session: initialised on the first amg solve, finalised at exit -------------

std::filesystem::path g_session_dir;  ///< Open MPI's session directory of a singleton run
bool g_initialised_here = false;

void finalize_petsc() {
  if (g_initialised_here) PetscFinalize();
  if (!g_session_dir.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(g_session_dir, ec);
  }
}

/// A process not started by mpirun is an MPI singleton. Open MPI then starts a daemon and
/// probes every network transport, 0.3-0.4 s here; a run that needs no other process needs
/// neither (0.04 s). Concurrent singletons of one user also share, and race to create and
/// remove, one session directory under /tmp: each gets its own. Values the user set win.
void configure_singleton() {
  if (std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK")) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  if (!std::getenv("OMPI_MCA_orte_tmpdir_base")) {
    std::error_code ec;
    std::string pattern = (std::filesystem::temp_directory_path(ec) / "hotmesh-mpi-XXXXXX").string();
    if (!ec && mkdtemp(pattern.data())) {
      g_session_dir = pattern;
      setenv("OMPI_MCA_orte_tmpdir_base", pattern.c_str(), 1);
    }
  }
}

void start_petsc() {
  static std::once_flag once;
  std::call_once(once, [] {
    PetscBool initialised = PETSC_FALSE;
    check(PetscInitialized(&initialised), "PetscInitialized");
    if (initialised) return;  // an embedding program runs PETSc already
    configure_singleton();
    // No PETSc signal handlers: crashes stay the program's (and the sanitizers') business.
    static char name[] = "hotmesh", no_handler[] = "-no_signal_handler";
    static char* arguments[] = {name, no_handler, nullptr};
    int argc = 2;
    char** argv = arguments;
    check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
    g_initialised_here = true;
    std::atexit(finalize_petsc);
  });
}

void default_option(const char* name, const char* value) {
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
  if (!set) check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
}

// --- The matrix K~ in nodal frames -------------------------------------------------------

/// The block rows of the matrix: one per node with at least one unknown (free or sliding);
/// a slave shares its master's. Fixed nodes (and slaves of fixed masters) have none and are
/// left out: as rows holding only a diagonal they would be isolated vertices of the matrix
/// graph, which PCGAMG makes aggregates of one node (whose d rows cannot carry the rigid-body
/// rotations, see AmgSolver::rotations_), and work for nothing. The set does not change
/// during a run: sliding nodes keep at least one tangential direction.
struct BlockRows {
  std::vector<PetscInt> of_node;  ///< block row of each node's unknowns (a slave: its master's), -1 for none
  std::vector<NodeId> node_of;    ///< the node each block row belongs to
  PetscInt count = 0;

  explicit BlockRows(const NodalFrames& frames) : of_node(frames.node_count(), -1) {
    const int d = frames.dimension();
    for (std::size_t n = 0; n < of_node.size(); ++n) {
      const auto node = static_cast<NodeId>(n);
      if (frames.is_slave(node) || frames.constrained(node) == d) continue;
      of_node[n] = count++;
      node_of.push_back(node);
    }
    for (std::size_t n = 0; n < of_node.size(); ++n) {
      const auto node = static_cast<NodeId>(n);
      if (frames.is_slave(node)) of_node[n] = of_node[static_cast<std::size_t>(frames.owner(node))];
    }
  }
  PetscInt operator[](NodeId n) const { return of_node[static_cast<std::size_t>(n)]; }

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

/// A square matrix of block size d over the block rows, preallocated from the node graph
/// with slaves merged into their masters.
Mat create_frame_matrix(const ElementList& cells, const NodalFrames& frames, const BlockRows& rows) {
  const std::size_t nodes = frames.node_count();
  const int d = frames.dimension();
  // node -> cells (CSR)
  std::vector<std::int64_t> start(nodes + 1, 0);
  for (NodeId n : cells.all_nodes()) ++start[static_cast<std::size_t>(n) + 1];
  for (std::size_t i = 1; i <= nodes; ++i) start[i] += start[i - 1];
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  std::vector<CellId> adjacent(static_cast<std::size_t>(start.back()));
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (NodeId n : cells.nodes(c)) adjacent[static_cast<std::size_t>(fill[static_cast<std::size_t>(n)]++)] = static_cast<CellId>(c);
  }
  // Every node adds the blocks of its cells' nodes to its own block row (a master's row thus
  // gathers its slaves' neighbours too).
  std::vector<std::vector<NodeId>> members(static_cast<std::size_t>(rows.count));
  for (std::size_t n = 0; n < nodes; ++n) {
    const PetscInt row = rows[static_cast<NodeId>(n)];
    if (row >= 0) members[static_cast<std::size_t>(row)].push_back(static_cast<NodeId>(n));
  }
  std::vector<PetscInt> blocks_per_row(static_cast<std::size_t>(rows.count), 0);
  std::vector<PetscInt> mark(static_cast<std::size_t>(rows.count), -1);
  for (PetscInt row = 0; row < rows.count; ++row) {
    PetscInt count = 0;
    for (const NodeId member : members[static_cast<std::size_t>(row)]) {
      const auto m = static_cast<std::size_t>(member);
      for (auto k = start[m]; k < start[m + 1]; ++k) {
        for (NodeId n : cells.nodes(static_cast<std::size_t>(adjacent[static_cast<std::size_t>(k)]))) {
          const PetscInt column = rows[n];
          if (column >= 0 && mark[static_cast<std::size_t>(column)] != row) {
            mark[static_cast<std::size_t>(column)] = row;
            ++count;
          }
        }
      }
    }
    blocks_per_row[static_cast<std::size_t>(row)] = count;
  }
  const PetscInt size = rows.count * d;
  Mat a = nullptr;
  check(MatCreate(PETSC_COMM_SELF, &a), "MatCreate");
  check(MatSetSizes(a, size, size, size, size), "MatSetSizes");
  check(MatSetBlockSize(a, d), "MatSetBlockSize");
  check(MatSetType(a, MATAIJ), "MatSetType");
  check(MatSetOptionsPrefix(a, "hotmesh_"), "MatSetOptionsPrefix");
  check(MatSetFromOptions(a), "MatSetFromOptions");
  check(MatXAIJSetPreallocation(a, d, blocks_per_row.data(), nullptr, nullptr, nullptr), "MatXAIJSetPreallocation");
  check(MatSetOption(a, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(a, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
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

/// K~ into the preallocated `a`, from every cell's K_e (and the residual, see ElementPass).
/// The first assembly goes through MatSetValuesBlocked and fixes the sparsity; later ones add
/// each K~_e straight into the AIJ values, cells of a colour in parallel.
void assemble_frame_matrix(Mat a, const ElementPass& pass, const NodalFrames& frames, const BlockRows& rows,
                           const AssemblyOrder& order, bool first) {
  const ConstrainedSystem& s = pass.s;
  const ElementList& cells = s.stiffness.cells();
  const auto d = static_cast<std::size_t>(frames.dimension());
  const auto n = static_cast<std::size_t>(s.stiffness.element_size());
  const std::size_t corners = n / d;
  PetscBool aij = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(a), MATSEQAIJ, &aij), "PetscObjectTypeCompare");
  if (first || !aij) {  // MatSetValuesBlocked: any matrix type (and, later, rows owned by other processes)
    if (!first) check(MatZeroEntries(a), "MatZeroEntries");
    std::array<double, 24 * 24> scratch{}, values{};
    std::array<std::int32_t, 8> owners{};
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const double* ke = pass.matrix(static_cast<CellId>(c), {scratch.data(), n * n});
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
    if (first) check(MatSetOption(a, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
    return;
  }
  PetscInt size = 0;
  const PetscInt* ia = nullptr;
  const PetscInt* ja = nullptr;
  PetscBool done = PETSC_FALSE;
  check(MatGetRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &size, &ia, &ja, &done), "MatGetRowIJ");
  if (!done) throw std::runtime_error("PETSc: MatGetRowIJ gave no row structure");
  PetscScalar* v = nullptr;
  check(MatSeqAIJGetArray(a, &v), "MatSeqAIJGetArray");
  std::fill(v, v + ia[size], 0.0);
  const auto add = [&](CellId cell) {
    std::array<double, 24 * 24> scratch{}, values{};
    std::array<std::int32_t, 8> owners{};
    const auto nodes = cells.nodes(static_cast<std::size_t>(cell));
    const double* ke = pass.matrix(cell, {scratch.data(), n * n});
    pass.residual(nodes, ke, n, d);
    frames.transform_element(nodes, {ke, n * n}, {values.data(), n * n}, {owners.data(), corners});
    for (std::size_t p = 0; p < corners; ++p) {
      const PetscInt row = rows[owners[p]];
      if (row < 0) continue;
      const PetscInt* begin = ja + ia[row * static_cast<PetscInt>(d)];
      const PetscInt* end = ja + ia[row * static_cast<PetscInt>(d) + 1];
      for (std::size_t q = 0; q < corners; ++q) {
        const PetscInt column = rows[owners[q]];
        if (column < 0) continue;
        // The block's first column in the row; the d rows of a block row share their pattern.
        const auto k = std::lower_bound(begin, end, column * static_cast<PetscInt>(d)) - begin;
        for (std::size_t i = 0; i < d; ++i) {
          PetscScalar* out = v + ia[row * static_cast<PetscInt>(d) + static_cast<PetscInt>(i)] + k;
          const double* in = values.data() + (p * d + i) * n + q * d;
          for (std::size_t j = 0; j < d; ++j) out[j] += in[j];
        }
      }
    }
  };
  for (const auto& colour : order.colours) {
    const auto count = static_cast<std::ptrdiff_t>(colour.size());
#pragma omp parallel for schedule(static) if (count >= kParallelCells)
    for (std::ptrdiff_t k = 0; k < count; ++k) add(colour[static_cast<std::size_t>(k)]);
  }
  for (const CellId cell : order.with_slaves) add(cell);
  check(MatSeqAIJRestoreArray(a, &v), "MatSeqAIJRestoreArray");  // marks the values changed
  check(MatRestoreRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &size, &ia, &ja, &done), "MatRestoreRowIJ");
}

void copy_to(std::span<const double> from, Vec to) {
  PetscScalar* x = nullptr;
  check(VecGetArrayWrite(to, &x), "VecGetArrayWrite");
  std::copy(from.begin(), from.end(), x);
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
  check(MatNullSpaceCreate(PETSC_COMM_SELF, PETSC_FALSE, static_cast<PetscInt>(vectors.size()), vectors.data(), &space),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(a, space), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&space), "MatNullSpaceDestroy");
  for (Vec& v : vectors) check(VecDestroy(&v), "VecDestroy");
}

// --- The solver ---------------------------------------------------------------------------

enum class Reuse { none, interpolation, preconditioner };

class AmgSolver final : public LinearSolver {
 public:
  explicit AmgSolver(const SolverOptions& options) : options_(options) {
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
    copy_from(x_, solution_);
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
    assemble_frame_matrix(a_, {s, u, r}, *frames_, *rows_, *order_, !pattern_);
    pattern_ = true;
    assembled_ = true;
  }

  void create(const ConstrainedSystem& s) {
    const int d = s.stiffness.dofs_per_node();
    const std::size_t nodes = s.stiffness.size() / static_cast<std::size_t>(d);
    frames_.emplace(nodes, d);
    frames_->update(s.constraints, s.periodic);
    rows_.emplace(*frames_);
    order_.emplace(s.stiffness, *frames_);
    a_ = create_frame_matrix(s.stiffness.cells(), *frames_, *rows_);
    check(MatCreateVecs(a_, &x_, &b_), "MatCreateVecs");
    full_.assign(s.stiffness.size(), 0.0);
    rhs_.assign(static_cast<std::size_t>(rows_->count) * static_cast<std::size_t>(d), 0.0);
    solution_.assign(rhs_.size(), 0.0);

    check(KSPCreate(PETSC_COMM_SELF, &ksp_), "KSPCreate");
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

  SolverOptions options_;
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
  const BlockRows rows(frames);
  const auto d = static_cast<std::size_t>(frames.dimension());
  const AssemblyOrder order(system.stiffness, frames);
  Mat a = create_frame_matrix(system.stiffness.cells(), frames, rows);
  assemble_frame_matrix(a, {system, {}, {}}, frames, rows, order, true);
  if (twice) assemble_frame_matrix(a, {system, {}, {}}, frames, rows, order, false);
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
