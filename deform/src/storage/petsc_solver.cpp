// hotmesh deform: the assembled linear solvers on PETSc (SolverOptions::linear = amg, direct or icc).
//
// Per Newton step, in one pass over the cells (ElementAssembler::assemble, which the Newton
// loop's newton_residual() calls): every K_e is computed at the current points (not stored),
// handed to the Newton residual (ResidualPass), and K~_e = T_e^T K_e T_e in the
// nodal frames of the current normals (nodal_frames.hpp) added into a matrix of block size d
// whose sparsity was preallocated once from the node graph, slaves merged into their masters
// (MAT_NEW_NONZERO_LOCATION_ERR guards it). Then (solve()) the right-hand side is r~ = T^T r,
// hotmesh's CG (pcg.hpp, as Jacobi-PCG) preconditioned by PETSc's algebraic multigrid solves
// K~ p~ = r~ from p~ = 0 on each rank's rows, stopping on the norm the system asks for, and
// p = T p~. PCGAMG gets the translations written in the frames as near-null space.
//
// `icc` runs the same CG with incomplete Cholesky factors of K~, ICC(icc_levels()), made anew at
// every Newton step (milliseconds on the 2D meshes it is for), in the rows' order: the nodes'
// own numbers (ICC on each rank's rows, block Jacobi between ranks, with several processes).
// Structured and extruded 2D meshes number a boundary layer line by line, and ICC in that
// order holds the strong coupling across the layer's thin cells that nodal Jacobi or a
// multigrid's aggregates miss: 3 to 6 CG iterations a solve on the ramps, where reverse Cuthill-McKee took 15 to 800
// (docs/performance.md). A numbering that does not follow the layer makes ICC slow, so its CG
// stops after kIccMostIterations iterations; a solve not converged by then goes over to
// `direct` for the rest of the run, is solved again, and the report says so (notes()).
//
// `direct` runs the same CG with a sparse Cholesky factorization of K~ as its preconditioner
// (CHOLMOD in one process, MUMPS on several), factorized at every Newton step: exact, so CG
// stops after one iteration. Each increment's first step orders the fixed sparsity and makes
// the symbolic factorization (a new PC, as for the multigrid); its later steps factorize only
// the numbers again. A factorization
// kept for later steps was a poor preconditioner (50 to 350 CG iterations a solve on the
// sliding ramp, against 1). On 2D meshes the factors stay small (nested dissection: about
// 45 per row on the ramp's 4 670 rows), in 3D they grow as N^4/3 and their cost as N^2:
// `linear: auto` weighs that (choose_linear_solver()).
//
// The multigrid hierarchy is kept from one Newton step to the next and from one increment to
// the next (PCSetReusePreconditioner) while it serves: K changes little between them, an old
// hierarchy stays a symmetric positive definite preconditioner, and it is rebuilt once the
// first solve of an increment takes kAmgSlowdown times the CG iterations it took fresh, or a
// solve with it fails (docs/method.md, "Algebraic multigrid", gives the measurements). The case file's `amg_reuse`
// changes that (SolverOptions::amg_reuse); any option of the PC can be given in PETSC_OPTIONS
// with the prefix `hotmesh_`, e.g. PETSC_OPTIONS="-hotmesh_pc_gamg_threshold 0.05 -hotmesh_pc_view".
//
// With several processes (mpirun, hotmesh/parallel/processes.hpp) every rank keeps the whole
// mesh, but the matrix and the element work are distributed: PETSc's partitioner (PT-Scotch)
// splits the cells along their faces, each node's block row goes to the lowest rank among its
// cells (rows numbered rank by rank, so each rank owns a contiguous range), each rank computes
// the K_e of its cells and adds them with MatSetValuesBlocked (PETSc sends the rows owned
// elsewhere; later assemblies add straight into the values of the rank's own rows), the
// residual is summed over the ranks, CG and the multigrid run on the distributed matrix, and
// the solution is gathered on every rank. With one process the same code runs on
// PETSC_COMM_SELF.
#include "storage/petsc_solver.hpp"

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/deform/pcg.hpp"
#include "storage/frame_matrix.hpp"
#include "storage/petsc_preconditioner.hpp"
#include "support/free_memory.hpp"
#include "hotmesh/core/clock.hpp"

namespace hotmesh::deform::detail {
namespace {

/// A PETSc operator on this rank's rows as pcg() sees its operators: the matrix (MatMult) or
/// the multigrid's V-cycle (PCApply), the spans lent to two Vecs of the matrix's layout.
template <class Object, PetscErrorCode (*Apply)(Object, Vec, Vec)>
class RowsOperator final : public LinearOperator {
 public:
  RowsOperator(Object object, Vec in, Vec out, std::size_t rows) : object_(object), in_(in), out_(out), rows_(rows) {}
  std::size_t size() const override { return rows_; }
  void apply(std::span<const double> x, std::span<double> y) const override {
    check(VecPlaceArray(in_, x.data()), "VecPlaceArray");
    check(VecPlaceArray(out_, y.data()), "VecPlaceArray");
    check(Apply(object_, in_, out_), "apply");
    check(VecResetArray(in_), "VecResetArray");
    check(VecResetArray(out_), "VecResetArray");
  }

 private:
  Object object_;
  Vec in_, out_;
  std::size_t rows_;
};

// --- The solver ---------------------------------------------------------------------------

class AssembledSolver final : public LinearSolver, public ElementAssembler {
 public:
  AssembledSolver(const SolverOptions& options, const parallel::RankExchange& ranks)
      : options_(options), job_{ranks.rank(), ranks.ranks()}, preconditioner_(preconditioner_of(options.linear)) {
    parallel::start_petsc();
    if (factors()) {
      reuse_ = AmgReuse::none;  // a fresh factorization at every Newton step (above)
      return;
    }
    const MultigridDefaults defaults = set_multigrid_defaults(options_.amg);
    one_sided_sweeps_ = defaults.one_sided_sweeps;
    smoother_given_ = defaults.smoother_given;
    // BoomerAMG kept across Newton steps needed 20 times the iterations on the ramp; its
    // set-up is cheap, so hypre rebuilds every step.
    reuse_ = options_.amg_reuse;  // `automatic` resolved with the mesh's size (create())
    if (options_.amg == AmgPackage::hypre && reuse_ == AmgReuse::interpolation) reuse_ = AmgReuse::none;  // gamg only
  }

  ~AssembledSolver() override {
    if (pc_) PCDestroy(&pc_);
    if (to_all_) VecScatterDestroy(&to_all_);
    for (Vec* v : {&all_, &x_, &in_, &out_}) {
      if (*v) VecDestroy(v);
    }
    if (a_) MatDestroy(&a_);
  }
  AssembledSolver(const AssembledSolver&) = delete;
  AssembledSolver& operator=(const AssembledSolver&) = delete;

  void begin_increment() override { first_step_ = true; }

  /// One pass computes every K_e, gives it to the residual and assembles K~ (the matrix is
  /// then ready for solve()); or, without `matrix`, gives them to the residual alone.
  void assemble(const ConstrainedSystem& s, const ResidualPass& residual, bool matrix) override {
    if (matrix) {
      assemble_matrix(s, &residual);
    } else {
      if (!a_) create(s);
      residual_pass({s, &residual}, *order_, local_cells_, job_.count > 1);
      assembled_ = false;
    }
  }
  ElementAssembler* assembler() override { return this; }
  std::vector<std::string> notes() const override { return notes_; }

  LinearSolveResult solve(const ConstrainedSystem& s, std::span<const double> rhs, std::span<double> p,
                          const LinearTarget& target, MotionTimings& timings) override {
    auto t = Clock::now();
    if (!assembled_) assemble_matrix(s, nullptr);  // a solve without the Newton loop's pass
    assembled_ = false;
    timings.assembly += seconds_since(t);
    const auto d = static_cast<std::size_t>(s.kernel.dofs_per_node());
    frames_->to_frames(rhs, p);  // p as scratch: r~ at the nodes
    rows_->gather(p, rhs_, d, static_cast<PetscInt>(first_row_ / d));
    LinearSolveResult result;
    // CG in the norm the Newton loop asks for: the Newton norm ||D^-1 r~|| with the node
    // stiffness D (the frames are orthonormal per node, so it equals ||D^-1 r||), else ||r~||.
    PcgOptions cg{.relative_tolerance = target.tolerance, .max_iterations = most_iterations(),
                  .record_history = false, .sum = [this](double local) { return sum_over_ranks(local); }};
    if (target.newton_norm) {
      set_newton_weights(s.node_stiffness, d);
      cg.norm = [this](std::span<const double> r) { return newton_norm(r); };
    }
    const std::span<const double> b = rhs_;
    const double initial = cg.norm ? cg.norm(b) : std::sqrt(sum_over_ranks(dot(b, b)));
    if (!(initial > 0.0)) {
      std::fill(p.begin(), p.end(), 0.0);
      result.converged = true;
      return result;
    }
    bool rebuild = must_rebuild();
    if (!set_up(rebuild, timings)) {  // no factorization: K~ is not positive definite
      std::fill(p.begin(), p.end(), 0.0);
      result.breakdown = true;
      return result;
    }
    PcgResult last;
    for (;;) {
      t = Clock::now();
      last = cg_on_rows(b, cg);
      timings.solve += seconds_since(t);
      result.iterations += last.iterations;
      result.converged = last.converged;
      result.breakdown = last.breakdown || !std::isfinite(last.final_residual);
      if (result.breakdown && one_sided_sweeps_) {  // the V-cycle is indefinite: symmetric sweeps from now on
        one_sided_sweeps_ = false;
        make_sweeps_symmetric(pc_);
        continue;
      }
      // A hierarchy kept from an earlier increment that no longer serves is rebuilt and the
      // system solved again, rather than the increment failed.
      if (!result.converged && !rebuild && reuse_ == AmgReuse::adaptive) {
        rebuild = true;
        set_up(rebuild, timings);
        continue;
      }
      if (preconditioner_ == Preconditioner::incomplete_cholesky && !result.converged && !result.breakdown) {
        go_over_to_cholesky();
        cg.max_iterations = most_iterations();
        if (!set_up(true, timings)) {
          std::fill(p.begin(), p.end(), 0.0);
          result.breakdown = true;
          return result;
        }
        continue;
      }
      note_iterations(last.iterations, rebuild);
      break;
    }
    t = Clock::now();
    solution_to_nodes(p, d);
    frames_->from_frames(p, p);
    timings.solve += seconds_since(t);
    first_step_ = false;
    result.reduction = last.final_residual / initial;
    return result;
  }

 private:
  /// Factors of K~ (complete or incomplete), made at every Newton step, rather than a multigrid.
  bool factors() const { return preconditioner_ != Preconditioner::multigrid; }

  /// Whether this solve builds the multigrid anew (SolverOptions::amg_reuse).
  bool must_rebuild() const {
    if (!pc_) return true;
    switch (reuse_) {
      case AmgReuse::adaptive: return slow_;
      case AmgReuse::none: return true;
      default: return first_step_;
    }
  }

  /// The multigrid of this step's matrix: rebuilt, or kept (PCSetReusePreconditioner; with
  /// `interpolation` GAMG's aggregates and prolongators only); or its Cholesky factors (false
  /// if the factorization failed: factorize()).
  bool set_up(bool rebuild, MotionTimings& timings) {
    const auto t = Clock::now();
    // A hierarchy built for an increment comes from a new PC, as in a new process: PCGAMG
    // carries state from one set-up into the next, and a run resumed from a checkpoint would
    // otherwise take other CG iterations than the uninterrupted run.
    if (!pc_ || (rebuild && (first_step_ || reuse_ == AmgReuse::adaptive) && reuse_ != AmgReuse::interpolation)) create_pc();
    if (rebuild && !factors()) set_near_null_space(a_, *frames_, *rows_);
    if (reuse_ == AmgReuse::interpolation) {
      check(PCGAMGSetReuseInterpolation(pc_, first_step_ ? PETSC_FALSE : PETSC_TRUE), "PCGAMGSetReuseInterpolation");
    }
    const bool keep = !rebuild && (reuse_ == AmgReuse::preconditioner || reuse_ == AmgReuse::adaptive);
    check(PCSetReusePreconditioner(pc_, keep ? PETSC_TRUE : PETSC_FALSE), "PCSetReusePreconditioner");
    check(PCSetOperators(pc_, a_, a_), "PCSetOperators");
    // The old hierarchy's pages, before the new set-up's peak: else that peak sits on them (at
    // 2.7 million cells it rose by 0.2-0.4 GiB per increment, the history of docs/performance.md).
    if (rebuild) release_free_memory();
    bool factorized = true;
    if (factors()) {
      factorized = factorize();
    } else {
      check(PCSetUp(pc_), "PCSetUp");
      // The hierarchy holds what it took from the modes: their d vectors go (24 bytes a row,
      // 0.1 GB a process at the paper's size).
      if (rebuild) check(MatSetNearNullSpace(a_, nullptr), "MatSetNearNullSpace");
    }
    if (rebuild) {
      release_free_memory();  // the set-up's work space
      check(PCViewFromOptions(pc_, nullptr, "-pc_view"), "PCViewFromOptions");
    }
    if (rebuild && !factors() && options_.amg == AmgPackage::gamg && !one_sided_sweeps_ && !smoother_given_) {
      make_sweeps_symmetric(pc_);
    }
    timings.preconditioner += seconds_since(t);
    return factorized;
  }

  /// CG's limit: kIccMostIterations for `icc`, which then goes over to `direct`.
  int most_iterations() const {
    return preconditioner_ == Preconditioner::incomplete_cholesky ? std::min(options_.max_pcg_iterations, kIccMostIterations)
                                                                  : options_.max_pcg_iterations;
  }

  /// `icc` no longer serves (kIccMostIterations): `direct` from this solve on; the PC goes, so
  /// that the next set_up() makes the Cholesky one.
  void go_over_to_cholesky() {
    notes_.push_back(fmt::format(
        "linear: icc did not converge in {} CG iterations (the mesh's node numbering does not follow its "
        "boundary layers, or the mesh is larger than icc is made for); the run went on with linear: direct",
        kIccMostIterations));
    preconditioner_ = Preconditioner::cholesky;
    check(PCDestroy(&pc_), "PCDestroy");
  }

  /// PCSetUp of the Cholesky factorization (factorize_here); false on every rank if it failed on
  /// any (a pivot that is not positive: K~ is not positive definite).
  bool factorize() { return sum_over_ranks(factorize_here(pc_) ? 0.0 : 1.0) == 0.0; }

  /// `adaptive`: the CG iterations of an increment's first solve (at pcg_tolerance in the
  /// Newton norm, whatever the forcing) against those with a fresh hierarchy.
  void note_iterations(int iterations, bool rebuilt) {
    if (rebuilt) {
      fresh_iterations_ = first_step_ ? std::max(iterations, 1) : 0;  // 0: the next first solve's count
      slow_ = false;
    } else if (first_step_ && fresh_iterations_ == 0) {
      fresh_iterations_ = std::max(iterations, 1);
    } else if (first_step_) {
      slow_ = iterations > kAmgSlowdown * fresh_iterations_;
    }
  }

  /// K~ of the system at its points, with the frames of its current normals.
  void assemble_matrix(const ConstrainedSystem& s, const ResidualPass* residual) {
    if (!a_) create(s);
    frames_->update(s.constraints, s.periodic);
    assemble_frame_matrix(a_, {s, residual}, *frames_, *rows_, *order_, local_cells_, !pattern_);
    pattern_ = true;
    assembled_ = true;
  }

  void create(const ConstrainedSystem& s) {
    const int d = s.kernel.dofs_per_node();
    dimension_ = d;
    const std::size_t nodes = s.kernel.size() / static_cast<std::size_t>(d);
    frames_.emplace(nodes, d);
    frames_->update(s.constraints, s.periodic);
    const ElementList& cells = s.kernel.cells();
    // In 2D the one-sided sweeps doubled GAMG's CG iterations on the ramps' boundary layers
    // (sliding ramp 3 268 -> 7 274, and 25 % more time); in 3D they took as many as symmetric
    // sweeps (the sectors). So 2D keeps symmetric sweeps on both sides.
    if (d == 2) one_sided_sweeps_ = false;
    if (reuse_ == AmgReuse::automatic) {
      reuse_ = options_.amg == AmgPackage::hypre ? AmgReuse::none
               : cells.size() >= kAdaptiveReuseCells ? AmgReuse::adaptive
                                                      : AmgReuse::preconditioner;
    }
    const NodeCells around(cells, nodes);
    const std::vector<int> rank_of_cell = partition_cells(cells, around, d, job_);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (rank_of_cell[c] == job_.rank) local_cells_.push_back(static_cast<CellId>(c));
    }
    rows_.emplace(*frames_, around, rank_of_cell, job_.count);
    order_.emplace(s.kernel, *frames_);
    a_ = create_frame_matrix(cells, around, *frames_, *rows_, job_);  // symmetric: the factorizations read one triangle
    check(MatCreateVecs(a_, &x_, nullptr), "MatCreateVecs");
    if (job_.count > 1) {
      // all_ without an array of its own: the gathered rows are held only while they are read
      // (solution_to_nodes). Kept, they would sit through every multigrid set-up, the peak of a
      // run's memory (65 MB a process at the paper's size).
      Vec made = nullptr;
      check(VecScatterCreateToAll(x_, &to_all_, &made), "VecScatterCreateToAll");
      PetscInt all_rows = 0;
      check(VecGetSize(made, &all_rows), "VecGetSize");
      check(VecDestroy(&made), "VecDestroy");
      check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, all_rows, nullptr, &all_), "VecCreateSeqWithArray");
    }
    PetscInt lo = 0, hi = 0;
    check(VecGetOwnershipRange(x_, &lo, &hi), "VecGetOwnershipRange");
    first_row_ = static_cast<std::size_t>(lo);
    local_rows_ = static_cast<std::size_t>(hi - lo);
    for (Vec* v : {&in_, &out_}) {  // without arrays of their own: CG's spans are lent to them
      if (job_.count > 1) {
        check(VecCreateMPIWithArray(PETSC_COMM_WORLD, 1, hi - lo, PETSC_DECIDE, nullptr, v), "VecCreateMPIWithArray");
      } else {
        check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, hi - lo, nullptr, v), "VecCreateSeqWithArray");
      }
    }
    rhs_.assign(local_rows_, 0.0);
  }

  /// D^-1 at this rank's rows, for the Newton norm.
  void set_newton_weights(std::span<const double> node_stiffness, std::size_t d) {
    weight_.resize(local_rows_);
    for (std::size_t i = 0; i < local_rows_; ++i) {
      const double k = node_stiffness[static_cast<std::size_t>(rows_->node_of[(first_row_ + i) / d])];
      weight_[i] = k > 0.0 ? 1.0 / k : 0.0;  // as scaled_residual_norm, which skips such nodes
    }
  }

  /// ||D^-1 r~|| over every rank's rows, r~ being this rank's.
  double newton_norm(std::span<const double> r) const {
    double sum = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double scaled = weight_[i] * r[i];
      sum += scaled * scaled;
    }
    return std::sqrt(sum_over_ranks(sum));
  }

  double sum_over_ranks(double local) const {
    if (job_.count > 1 &&
        MPI_Allreduce(MPI_IN_PLACE, &local, 1, MPI_DOUBLE, MPI_SUM, PetscObjectComm(reinterpret_cast<PetscObject>(a_))) != MPI_SUCCESS) {
      throw std::runtime_error("MPI_Allreduce failed");
    }
    return local;
  }

  /// CG from p~ = 0 on this rank's rows of K~ p~ = r~ (b), preconditioned by the multigrid;
  /// p~ is left in x_. Each iteration takes one product and one V-cycle: PETSc's KSPCG would
  /// need a second product for the Newton norm, whose residual it keeps to itself.
  PcgResult cg_on_rows(std::span<const double> b, const PcgOptions& options) {
    PetscScalar* x = nullptr;
    check(VecGetArrayWrite(x_, &x), "VecGetArrayWrite");
    const std::span<double> p(x, local_rows_);
    std::fill(p.begin(), p.end(), 0.0);
    const RowsOperator<Mat, MatMult> k(a_, in_, out_, local_rows_);
    const RowsOperator<PC, PCApply> v_cycle(pc_, in_, out_, local_rows_);
    const PcgResult result = pcg(k, v_cycle, b, p, options);
    check(VecRestoreArrayWrite(x_, &x), "VecRestoreArrayWrite");
    return result;
  }

  /// The multigrid preconditioner or the Cholesky factorization (create_preconditioner).
  void create_pc() {
    if (pc_) check(PCDestroy(&pc_), "PCDestroy");
    pc_ = create_preconditioner(a_, preconditioner_, options_.amg, job_.count, dimension_);
  }

  /// The solution p~ of every rank's rows (each keeps the whole mesh) at the nodes: from x_
  /// with one process, else gathered into all_ first.
  void solution_to_nodes(std::span<double> full, std::size_t d) {
    const auto rows = static_cast<std::size_t>(rows_->count) * d;
    if (!to_all_) {
      const PetscScalar* x = nullptr;
      check(VecGetArrayRead(x_, &x), "VecGetArrayRead");
      rows_->scatter({x, rows}, full, d);
      check(VecRestoreArrayRead(x_, &x), "VecRestoreArrayRead");
      return;
    }
    std::vector<double> gathered(rows);
    check(VecPlaceArray(all_, gathered.data()), "VecPlaceArray");
    check(VecScatterBegin(to_all_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(to_all_, x_, all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    check(VecResetArray(all_), "VecResetArray");
    rows_->scatter(gathered, full, d);
  }

  SolverOptions options_;
  parallel::Processes job_;  ///< this rank, of how many
  Preconditioner preconditioner_;  ///< by `linear`; `icc` may go over to `direct` (go_over_to_cholesky)
  std::vector<std::string> notes_;  ///< for MotionResult::notes
  int dimension_ = 0;               ///< of the mesh (create())
  std::vector<CellId> local_cells_;  ///< the cells whose element work this rank does
  AmgReuse reuse_ = AmgReuse::automatic;  ///< resolved by create()
  std::optional<NodalFrames> frames_;
  std::optional<BlockRows> rows_;
  std::optional<AssemblyOrder> order_;
  Mat a_ = nullptr;
  PC pc_ = nullptr;
  Vec x_ = nullptr;  ///< p~ at this rank's rows
  Vec in_ = nullptr, out_ = nullptr;  ///< this rank's rows, lent CG's vectors for the products
  std::size_t first_row_ = 0, local_rows_ = 0;  ///< this rank's rows of K~
  VecScatter to_all_ = nullptr;  ///< x_ to all_ on every rank (several processes)
  Vec all_ = nullptr;            ///< every rank's rows, its array lent by solution_to_nodes
  bool first_step_ = true;  ///< the coming solve is the first of an increment
  bool one_sided_sweeps_ = false;  ///< gamg's default smoother, forward down and backward up (false once CG broke down)
  bool smoother_given_ = false;    ///< the user chose the smoother in PETSC_OPTIONS
  bool slow_ = false;       ///< adaptive: the hierarchy is to be rebuilt
  int fresh_iterations_ = 0;  ///< adaptive: of the first solve of an increment with a fresh hierarchy (0: none yet)
  bool pattern_ = false;    ///< the sparsity is fixed (after the first assembly)
  bool assembled_ = false;  ///< the element pass assembled K~ for the coming solve()
  std::vector<double> rhs_;              ///< r~ at this rank's rows
  std::vector<double> weight_;           ///< D^-1 at this rank's rows (the Newton norm)
};

}  // namespace

std::unique_ptr<LinearSolver> make_assembled_solver(const SolverOptions& options, const parallel::RankExchange& ranks) {
  return std::make_unique<AssembledSolver>(options, ranks);
}

}  // namespace hotmesh::deform::detail
