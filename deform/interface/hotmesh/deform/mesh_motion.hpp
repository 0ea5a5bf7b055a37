// hotmesh deform: what a run of the mesh motion (move_mesh, hotmesh/deform/move_mesh.hpp) is
// given and gives back: patch roles, records of increments, results, checkpoints. Header-only,
// so that io reads and writes them without linking the solver (and its PETSc and MPI).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/deform/boundary_role.hpp"
#include "hotmesh/deform/mesh_names.hpp"
#include "hotmesh/deform/solver_options.hpp"
#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/core/enum_names.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::deform {

/// The default of FeatureOptions::angle: 25 degrees, in radians.
inline constexpr double kDefaultFeatureAngle = 25.0 * std::numbers::pi / 180.0;

/// Which corners of a sliding patch's shape mesh nodes hold (beyond the paper, whose sliding
/// rounds them): the case file's `features: {angle: 25}` or `features: off`.
/// Whatever `enabled` says, the wall nodes that lie on a corner or on an edge where the faces
/// of a wall meet before the motion (a mesh made from CAD has them on every CAD vertex and
/// edge) hold it from the start: the wall has no tangent there for them to slide along.
struct FeatureOptions {
  /// Corners of curves (and circles of surfaces of revolution) and edges where faces meet,
  /// that no node lies on: held by the nearest wall nodes in a corner pass after the motion.
  bool enabled = true;
  double angle = kDefaultFeatureAngle;  ///< radians: corners and edges turning by at least this are held
};

/// What one mesh patch does during the motion.
struct PatchMotion {
  std::string patch;  ///< name of a patch of the mesh
  BoundaryRole role = BoundaryRole::fixed;
  /// prescribed: the boundary's undeformed and deflected shape (required).
  std::shared_ptr<const geometry::BoundaryShape> shape;
  /// periodic, on the side that declares the pair: the partner patch, and the rotation (about
  /// `axis`, radians, right-handed) that carries this patch onto it. Empty partner on the
  /// other side.
  std::string partner;
  double angle = 0.0;
  geometry::Axis axis;
  /// sliding: the corners of `shape` that nodes hold.
  FeatureOptions features;
};

/// A corner of a sliding wall and the nodes that hold it, for reports.
struct WallFeature {
  std::string patch;
  double parameter = 0.0;  ///< on the shape
  double angle = 0.0;      ///< radians the undeformed or the deflected wall turns by there
  /// On the shape at the stage reached (for a surface of revolution: in the meridional plane
  /// of its first node; the corner is the circle through it).
  Vec3 point;
  /// The nodes that hold it: sliding nodes given the corner (in 3D, one per meridional row of
  /// wall faces), then nodes of other roles that lie on it. Empty if none could.
  std::vector<NodeId> nodes;
  std::size_t given_nodes = 0;   ///< how many of `nodes` are sliding nodes given the corner
  double largest_offset = 0.0;   ///< farthest a given node was from the corner before the motion
  double distance = 0.0;         ///< farthest a holding node is from the corner at the end
  std::size_t unheld_edges = 0;  ///< wall edges across it with no node on it (the wall cuts the corner)
  /// Its nodes lay on it before the motion (a CAD vertex or edge with mesh nodes on it) and held
  /// it from the start; else the corner pass gave it nodes after the motion.
  bool from_start = false;
  /// An edge where faces of a wall meet (its nodes slide along it; those on it from the start,
  /// then, where the mesh's lines miss it, those given it): the faces' indices in the wall's
  /// shape; `parameter` is then 0. Empty for the corners of curves.
  std::vector<int> faces;
};

struct NewtonStep {
  double residual = 0.0;           ///< ||D^-1 R|| (the Newton norm) before this step's linear solve
  int pcg_iterations = 0;          ///< of the solve that followed (0 on the last entry)
  bool pcg_converged = true;
  double pcg_reduction = 0.0;      ///< ||r|| / ||r0|| reached by PCG
  double linear_tolerance = 0.0;   ///< the relative tolerance that solve was given (inexact Newton)
  double max_projection = 0.0;     ///< largest move of a sliding node back onto its boundary after the step
  bool linear_newton_norm = false; ///< that solve stopped on ||D^-1 r||, the Newton norm, not on ||r||
};

struct IncrementRecord {
  int increment = 0;          ///< 1..N: the increment of the case this attempt belongs to
  double lambda_begin = 0.0;
  double lambda_end = 0.0;
  int split_depth = 0;        ///< 0 for the increment itself, d for a 1/2^d piece of it
  std::vector<NewtonStep> newton;
  bool converged = false;     ///< the Newton cycle reached the tolerance
  bool accepted = false;      ///< converged and no cell inverted
  double residual_reduction = 0.0;  ///< final ||D^-1 R|| / ||D^-1 R0||
  double min_scaled_jacobian = 0.0;
  std::size_t inverted_cells = 0;
  CellId worst_cell = -1;
  double max_normal_slip = 0.0;     ///< largest |p . n| of a Newton step at a sliding node (eq. 19)
  double seconds = 0.0;
  std::string failure;        ///< why it was not accepted
  std::size_t smoothed_nodes = 0;  ///< node moves of the quality step (SolverOptions::quality.smoothing)
  /// An increment of the corner pass: after the motion, the nodes nearest the corners of the
  /// sliding walls move onto them (its stages are those of the pass; the walls stay at 1).
  bool corner_pass = false;
};

struct MotionTimings {
  double setup = 0.0;       ///< material, shapes, constraints
  double assembly = 0.0;    ///< element matrices (and, with amg, the matrix in nodal frames)
  double preconditioner = 0.0;  ///< nodal Jacobi blocks, or the multigrid hierarchy
  double solve = 0.0;       ///< the preconditioned CG iterations
  double projection = 0.0;  ///< sliding nodes onto their boundaries
  double quality = 0.0;
  double total = 0.0;
};

/// Where a sliding node came from: its parameter t0 on its first sliding shape in the
/// undeformed (cold) geometry. A restarted run needs it to set the node's new target.
struct SlidingOrigin {
  NodeId node = 0;
  geometry::ShapeParameter parameter;
};

/// The state a run continues from (section 4.3, re-start): the positions a previous run
/// reached, and the origins of its sliding nodes. The shapes of a restarted run go from the
/// previous run's deflected boundary (stage 0) to the new one (stage 1), in the same parameter
/// as the undeformed boundary; each sliding node's target is then moved once, beforehand, by
/// the slide it made in the previous runs: x_F = P(x1 + c_1(t0) - c_0(t0)), the node's
/// position plus the change of deflection at its material point, projected on the new
/// boundary (P).
struct MotionStart {
  std::vector<Vec3> points;
  std::vector<SlidingOrigin> sliding;
};

/// How far a prescribed or sliding patch's nodes lay from its undeformed wall (stage 0 of its
/// shape: the CAD curve or faces, or the wall through the FEM nodes) when the run began: the
/// motion puts them on it, so this is how much the mesh's own wall is changed besides the
/// deflection.
struct WallGap {
  std::string patch;
  double distance = 0.0;  ///< the largest, mesh units
  NodeId node = -1;       ///< the node that far (-1: the patch has no node of its role)
};

/// What a failed run's last attempt ran into, and where.
struct MotionFailure {
  enum class Kind { none, inverted_cells, newton_stalled, newton_diverged, linear_breakdown, quality_limits };
  Kind kind = Kind::none;
  /// The nodes where the attempt's last Newton residual ||D^-1 R|| (a length: each node's force
  /// divided by its stiffness) is largest, largest first: where Newton did not converge.
  struct ResidualNode {
    NodeId node = 0;
    double residual = 0.0;
  };
  std::vector<ResidualNode> largest_residuals;
  /// That residual at every node (empty when the linear solver broke down: it had none).
  std::vector<double> residual;
};

struct MotionResult {
  bool success = false;
  std::string message;                 ///< on failure: what failed, naming cell and increment
  double lambda_reached = 0.0;         ///< stage of `points`
  std::vector<Vec3> points;            ///< the last valid mesh (the final one on success)
  std::vector<double> quality;         ///< scaled Jacobian per cell of `points`
  QualitySummary summary;              ///< of `points`
  std::vector<Vec3> failed_points;     ///< the rejected attempt on failure, else empty
  std::vector<double> failed_quality;
  std::vector<IncrementRecord> increments;  ///< every attempt, accepted or not, in order
  std::vector<NodeRoleCode> node_roles;
  std::size_t sliding_nodes = 0;
  std::size_t passive_nodes = 0;
  std::size_t periodic_pairs = 0;
  /// The diagonal of the undeformed mesh's bounding box: the length the relative forms of the
  /// lengths below are taken of (report.json's `_relative` keys).
  double length_scale = 1.0;
  // Lengths, in mesh units. The maxima run over every Newton step of the accepted attempts: a
  // rejected attempt's moves were undone, so they say nothing about the mesh that was kept.
  /// Largest distance between a master node turned by the sector angle and its slave, at the end.
  double max_periodic_mismatch = 0.0;
  /// Largest distance a sliding node was moved back onto its wall after a Newton step.
  double max_projection_distance = 0.0;
  /// The same after the last Newton step of the last accepted attempt: how settled the final
  /// mesh is.
  double final_projection_distance = 0.0;
  /// Largest |p . n| of a Newton step p at a sliding node with normal n (eq. 19).
  double max_normal_slip = 0.0;
  std::vector<SlidingOrigin> sliding_origins;  ///< for restarting from this result
  /// Where a run restarted from this one starts (MotionStart::points): the mesh before the
  /// corner pass, so that a chain of restarted runs makes the moves of one straight run (eq.
  /// 22) and each ends with its own pass. Empty when there was no pass: then `points`.
  std::vector<Vec3> restart_points;
  std::vector<WallFeature> features;           ///< the corners of the sliding walls, by patch
  /// Where the corner pass left cells below the motion's worst cell: the interior nodes moved
  /// to restore it (deform/src/motion/quality_repair.hpp). Zero counts when it did not.
  struct CornerRepair {
    std::size_t cells_below = 0;  ///< cells the pass left below the motion's worst cell
    std::size_t nodes_moved = 0;
    double min_before = 0.0;      ///< worst scaled Jacobian after the pass, before the repair
    double min_after = 0.0;
  } corner_repair;
  std::vector<std::string> notes;      ///< things worth a warning (set-up conflicts, ...)
  std::vector<WallGap> wall_gaps;      ///< per prescribed patch, then per sliding patch
  MotionFailure failure;               ///< on failure
  MotionTimings timings;
};

/// One step of the run still to do: increment `increment` of N from stage lambda_begin to
/// lambda_end; split_depth d > 0 for a 1/2^d piece of a split increment.
struct MotionStep {
  int increment = 0;
  double lambda_begin = 0.0;
  double lambda_end = 0.0;
  int split_depth = 0;
};

/// What a sliding node carries from one increment to the next: its target x_F on the fully
/// deflected boundary (section 4.3, moved by every slide) and the parameters of its last
/// projections on its shapes (warm starts of the next ones).
struct SlidingState {
  NodeId node = 0;
  Vec3 target;
  std::array<geometry::ShapeParameter, 3> hints{};
};

/// Where a run stands after an accepted step: everything needed to continue it and make
/// exactly the moves the uninterrupted run would make (resume after a crash or a kill).
/// Prescribed and passive motions are not in it: they follow from the set-up, which a resumed
/// run repeats.
/// Its size does not depend on N: the steps left are the pieces of a split increment still to
/// do (at most max_increment_splits + 1, all of increment finished_increments + 1), then the
/// whole increments after it, which need no record.
struct MotionCheckpoint {
  int increments = 0;                ///< N of the run
  int finished_increments = 0;       ///< increments 1..k done (all their pieces accepted)
  double lambda = 0.0;               ///< stage of `points`
  std::vector<MotionStep> split_pieces;  ///< pieces of increment finished_increments + 1 left, in order
  std::vector<Vec3> points;          ///< the mesh at stage `lambda`
  /// The mesh at the start of the last accepted step, at stage `previous_lambda` (the
  /// predictor's secant, SolverOptions::predictor); empty before the first.
  std::vector<Vec3> previous_points;
  double previous_lambda = 0.0;
  std::vector<SlidingState> sliding;  ///< in the order of the set-up
  std::vector<IncrementRecord> records;  ///< every attempt so far, as MotionResult::increments
  MotionTimings timings;             ///< spent so far
};

/// A Newton step done (its linear solve and the projection of the sliding nodes), for
/// progress output.
struct NewtonProgress {
  MotionStep step;                 ///< the increment (or piece) being solved
  int increments = 0;              ///< N
  int iteration = 0;               ///< 1, 2, ...: Newton steps done in this attempt
  double residual_reduction = 0.0;  ///< ||D^-1 R|| / ||D^-1 R0|| after the step
  int pcg_iterations = 0;          ///< of the step's linear solve
  bool pcg_converged = true;
  bool newton_norm = false;        ///< the solve stopped on ||D^-1 r|| (NewtonStep::linear_newton_norm)
  double max_projection = 0.0;     ///< largest move of a sliding node back onto its boundary
  double seconds = 0.0;            ///< since the attempt started
};

using IncrementObserver = std::function<void(const IncrementRecord&)>;
using NewtonObserver = std::function<void(const NewtonProgress&)>;
using CheckpointObserver = std::function<void(const MotionCheckpoint&)>;

/// Callbacks of a run; any may be empty. An exception thrown by one ends the run (it
/// propagates out of move_mesh).
struct MotionObservers {
  IncrementObserver increment;    ///< after every attempt, accepted or not
  NewtonObserver newton;          ///< after every Newton step
  CheckpointObserver checkpoint;  ///< after every accepted attempt, with the state to resume from
};

/// The patch roles leave the mesh free to move as a rigid body: no fixed or prescribed node,
/// slip or sliding normal, or periodic pair resists some translation or rotation, so the
/// mesh's position is not determined. what() names the free motions; a caller with a case file
/// may place the error at its `patches:`.
class FreeRigidMotion : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace hotmesh::deform
