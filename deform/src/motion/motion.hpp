// hotmesh deform (internal, motion/ only): one run of the mesh motion (move_mesh.hpp), the
// increment scheduler: increments k = 1..N from stage (k-1)/N to k/N, a failed one split into
// halves, each solved by the Newton solver (newton.hpp) on the increment's system
// (increment_system.hpp), checked, and handed out as a checkpoint. Its work by job:
//   increments.cpp     the schedule (run, advance) and one attempt at an increment
//   predictor.cpp      the displacements an increment starts from, and the predictor
//   quality_checks.cpp whether a converged increment is accepted (inverted cells, quality limits)
//   checkpoints.cpp    the state handed out after each accepted step, and the resume from it
//   motion_report.cpp  what the result reports: corners, maxima, and where and why a run failed
// The corner pass (corner_pass.hpp) runs a second Motion after the first.
#pragma once

#include <algorithm>
#include <cstddef>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "constraints/boundary_conditions.hpp"
#include "constraints/sliding.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"
#include "motion/quality_step.hpp"
#include "storage/linear_solver.hpp"

namespace hotmesh::deform::detail {

struct NewtonResult;  // newton.hpp

/// The nodes of the walls that move: the patches that follow a shape, prescribed and sliding
/// (for the stiffening by distance to them, MaterialOptions::wall_distance_exponent).
std::vector<NodeId> moving_wall_nodes(const Mesh& mesh, std::span<const PatchMotion> patches);  // move_mesh.cpp

class Motion {
 public:
  Motion(const Mesh& mesh, std::span<const PatchMotion> patches, std::shared_ptr<const StiffnessKernel> kernel,
         const SolverOptions& solver, const MotionObservers& observers, const MotionStart* start,
         const parallel::RankExchange& ranks);

  MotionResult run(const MotionCheckpoint* resume);

  void set_setup_time(double s);

 private:
  int increments() const { return std::max(solver_.increments, 1); }

  // increments.cpp
  bool advance(const MotionStep& step, std::deque<MotionStep>& pieces);
  double round_off_residual(std::size_t dofs) const;
  std::vector<Vec3> attempt(const MotionStep& piece, IncrementRecord& record);
  void report_step(const MotionStep& step, const NewtonResult& newton, int it, double seconds) const;

  // predictor.cpp
  std::vector<double> initial_displacements(double a, double b);
  std::vector<double> predict(double a, double b, std::vector<double>& u);

  // quality_checks.cpp
  void smooth_for_solver(std::vector<Vec3>& trial, IncrementRecord& record);
  void accept_if_valid(const std::vector<Vec3>& trial, std::span<const double> u, IncrementRecord& record);
  std::string broken_limits(const std::vector<Vec3>& trial, std::span<const double> jacobians,
                            const QualitySummary& summary);

  // checkpoints.cpp
  MotionCheckpoint checkpoint(const std::deque<MotionStep>& pieces, double seconds) const;
  void restore(const MotionCheckpoint& c);

  // motion_report.cpp
  void report_corners();
  void measure_accepted_steps();
  void note_failure(MotionFailure::Kind kind, std::span<const double> r = {}, std::span<const double> k = {});
  std::string where_it_failed() const;
  std::string role_of(NodeId n) const;

  const Mesh& mesh_;
  SolverOptions solver_;
  const MotionObservers& observers_;
  BoundarySetup setup_;
  SlidingNodes sliding_;
  const parallel::RankExchange& ranks_;
  std::shared_ptr<const StiffnessKernel> kernel_;  ///< K_e of any cell (eq. 35 and the Q1 element)
  std::optional<StiffnessOperator> blocks_;         ///< K of each Newton step in node blocks (jacobi-pcg)
  std::unique_ptr<LinearSolver> linear_;
  std::size_t dim_;
  double size_;
  int finished_increments_ = 0;
  double setup_seconds_ = 0.0;    ///< of this run
  double earlier_seconds_ = 0.0;  ///< total of the interrupted run this one resumes
  std::vector<Vec3> previous_points_;  ///< the mesh at the start of the last accepted step (predict())
  double previous_stage_ = 0.0;        ///< its stage
  MotionFailure failure_;              ///< of the last attempt that failed
  std::vector<MovableNode> movable_;  ///< the nodes the quality step may move, found at its first use
  MotionResult result_;
};

}  // namespace hotmesh::deform::detail
