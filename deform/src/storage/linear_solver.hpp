// hotmesh deform (internal): the linear solve of a Newton step (eq. 8), as a strategy the
// Newton loop calls once per iteration:
//     K(n) p = -R(n)  on the admissible subspace: fixed and prescribed nodes still, sliding
//                      nodes tangential (eq. 16), periodic slaves following their masters,
// from p = 0. Two implementations, chosen by SolverOptions::linear:
//  - jacobi-pcg: the paper's PCG on P T^T K T P with nodal Jacobi (section 3), K in node
//    blocks (stiffness_operator.hpp);
//  - amg: the same operator assembled in nodal frames (nodal_frames.hpp) into a PETSc matrix,
//    solved by CG with algebraic multigrid (petsc_solver.cpp);
//  - direct: that matrix's sparse Cholesky factors as CG's preconditioner (petsc_solver.cpp);
//  - icc: its incomplete Cholesky factors in the nodes' order (petsc_solver.cpp).
// All see the same system and give the same p to the solver tolerance (tests/deform).
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "constraints/periodic.hpp"
#include "hotmesh/deform/constraints.hpp"
#include "hotmesh/deform/linear_algebra.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/deform/solver_options.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"

namespace hotmesh::deform::detail {

/// The system of one Newton step: K(n) at the current geometry (the element kernel; the node
/// blocks of K, where a solver uses them, were made with it), the directions nodes may not
/// move in (with the current normals of sliding nodes), periodic pairs, the current points (the
/// AMG near-null space is built from them) and each node's stiffness D as newton_residual()
/// wrote it (the Newton loop's norm ||D^-1 R||).
struct ConstrainedSystem {
  const StiffnessKernel& kernel;
  const NodeConstraints& constraints;
  const PeriodicCoupling& periodic;
  std::span<const Vec3> points;
  std::span<const double> node_stiffness;  ///< may be empty if no solve asks for the Newton norm
};

/// What the linear solve of a Newton step must reach.
struct LinearTarget {
  double tolerance = 0.0;     ///< the relative reduction of the residual
  bool newton_norm = false;   ///< measured as ||D^-1 r||, the Newton loop's norm, not as ||r||
};

struct LinearSolveResult {
  int iterations = 0;
  bool converged = false;
  bool breakdown = false;    ///< the operator or preconditioner is not SPD on the subspace
  double reduction = 0.0;    ///< ||r|| / ||r0|| reached
};

/// The Newton loop's part of a pass over the element matrices: R = K(n) u (before folding and
/// projection) and each node's stiffness (add_node_stiffness), from each K_e as it comes.
struct ResidualPass {
  std::span<const double> u;
  std::span<double> r;
  std::span<double> node_stiffness;
  std::size_t d = 3;  ///< dofs per node: 2 (quad4 cells) or 3 (hex8)
  /// A second displacement and its product K(n) u_start with the same element matrices, when
  /// not empty (the reference residual of a predicted increment, ReferenceResidual).
  std::span<const double> u_start;
  std::span<double> r_start;
  /// Adds K_e u_e (element_product) and the corners' stiffness of the cell with `nodes`.
  void add(std::span<const NodeId> nodes, std::span<const double> ke) const;
};

/// A solver that computes the element matrices itself, into a matrix of its own (amg): one
/// pass over this rank's cells gives every K_e at s.points, once per Newton step, to its
/// matrix and to the Newton loop's `residual`. Without `matrix` the pass gives them to the
/// residual only, for a residual that will likely end the Newton loop; the next solve()
/// then assembles the matrix itself.
class ElementAssembler {
 public:
  virtual ~ElementAssembler() = default;
  virtual void assemble(const ConstrainedSystem& s, const ResidualPass& residual, bool matrix) = 0;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Solves the system for p from p = 0 to ||r|| <= target.tolerance ||rhs||, r = rhs - K p,
  /// or, with target.newton_norm, to ||D^-1 r|| <= target.tolerance ||D^-1 rhs||: the norm the
  /// Newton loop converges in (scaled_residual_norm, Forcing). `rhs` lies in the
  /// admissible subspace (projected, folded); so does p, with p = 0 at slaves (the Newton loop
  /// expands u afterwards). `p` may be `rhs` itself (the Newton loop solves in place). Adds its
  /// times to timings.assembly (what it assembles beyond the element matrices), .preconditioner
  /// and .solve.
  virtual LinearSolveResult solve(const ConstrainedSystem& system, std::span<const double> rhs, std::span<double> p,
                                  const LinearTarget& target, MotionTimings& timings) = 0;
  /// A new increment (or piece of one) starts: preconditioners kept for reuse are dropped.
  virtual void begin_increment() {}
  /// The solver's element pass, if it computes the element matrices itself; null when it
  /// solves with the node blocks of K.
  virtual ElementAssembler* assembler() { return nullptr; }
  /// What the run's report should say about the solves (a change of method on the way).
  virtual std::vector<std::string> notes() const { return {}; }
};

/// ||D^-1 R||: the Newton residual with each node's force divided by the node's stiffness,
/// i.e. the displacement a Jacobi sweep would still move each node by (in the mesh's length
/// unit). Unlike ||R|| it is not dominated by a few very stiff nodes (the smallest, most
/// distorted cells of eq. (35)), so a Newton step that only settles those does not pass for
/// convergence of the whole mesh. Nodes without stiffness (periodic slaves) carry no residual
/// and are skipped.
double scaled_residual_norm(std::span<const double> r, std::span<const double> node_stiffness, std::size_t d);

/// The solver SolverOptions::linear names, for the processes of `ranks`, with K in the node
/// blocks of `k` (which jacobi-pcg needs: std::invalid_argument without; amg, direct and icc
/// assemble their own matrix and ignore it). They initialise PETSc (and MPI) on first use.
std::unique_ptr<LinearSolver> make_linear_solver(const SolverOptions& options, const parallel::RankExchange& ranks,
                                                 const StiffnessOperator* k);
/// Whether that solver works on K in node blocks (jacobi-pcg) or assembles the element matrices
/// into a matrix of its own (amg, direct, icc).
bool solves_with_node_blocks(const SolverOptions& options);

/// P T^T K T P: the stiffness restricted to the admissible subspace — periodic slaves expanded
/// from their masters before the element loop and folded back after it (periodic.hpp), the
/// normal component at sliding nodes removed (eq. 16), fixed nodes zeroed.
class ConstrainedOperator final : public LinearOperator {
 public:
  ConstrainedOperator(const StiffnessOperator& k, const NodeConstraints& c, const PeriodicCoupling& periodic)
      : k_(k), c_(c), periodic_(periodic), expanded_(periodic.empty() ? 0 : k.size()) {}
  std::size_t size() const override { return k_.size(); }
  void apply(std::span<const double> x, std::span<double> y) const override;

 private:
  const StiffnessOperator& k_;
  const NodeConstraints& c_;
  const PeriodicCoupling& periodic_;
  mutable std::vector<double> expanded_;  ///< work space (an operator is used by one thread)
};

}  // namespace hotmesh::deform::detail
