// hotmesh deform: the state a run hands out after each accepted step (MotionCheckpoint), and a
// run resumed from it (motion.hpp).
#include <fmt/format.h>

#include <string>
#include <tuple>

#include "hotmesh/core/input_error.hpp"
#include "motion/motion.hpp"

namespace hotmesh::deform::detail {

static_assert(std::tuple_size_v<decltype(SlidingState::hints)> == SlidingNode::kMaxShapes);

/// The state to resume from after an accepted step, `pieces` those of a split increment left.
MotionCheckpoint Motion::checkpoint(const std::deque<MotionStep>& pieces, double seconds) const {
  MotionCheckpoint c;
  c.increments = increments();
  c.finished_increments = finished_increments_;
  c.lambda = result_.lambda_reached;
  c.split_pieces.assign(pieces.begin(), pieces.end());
  c.points = result_.points;
  c.previous_points = previous_points_;
  c.previous_lambda = previous_stage_;
  c.sliding.reserve(setup_.sliding.size());
  for (const SlidingNode& s : setup_.sliding) c.sliding.push_back({s.node, s.target, s.hints});
  c.records = result_.increments;
  c.timings = result_.timings;
  c.timings.total = seconds + setup_seconds_ + earlier_seconds_;
  return c;
}

/// Takes up an interrupted run where its checkpoint left it.
void Motion::restore(const MotionCheckpoint& c) {
  const auto refuse = [](const std::string& what) {
    throw InputError("the checkpoint does not fit this run: " + what);
  };
  if (c.increments != increments()) {
    refuse(fmt::format("it was written for {} increments, this run has {}", c.increments, solver_.increments));
  }
  if (c.points.size() != mesh_.node_count()) {
    refuse(fmt::format("it holds {} nodes, the mesh {}", c.points.size(), mesh_.node_count()));
  }
  if (c.sliding.size() != setup_.sliding.size()) {
    refuse(fmt::format("it holds {} sliding nodes, this set-up {}", c.sliding.size(), setup_.sliding.size()));
  }
  for (std::size_t i = 0; i < c.sliding.size(); ++i) {
    SlidingNode& s = setup_.sliding[i];
    if (c.sliding[i].node != s.node) refuse(fmt::format("sliding node {} differs", mesh_.node_id(s.node)));
    s.target = c.sliding[i].target;
    s.hints = c.sliding[i].hints;
  }
  if (c.finished_increments < 0 || c.finished_increments > c.increments) refuse("its increments done are damaged");
  for (const MotionStep& step : c.split_pieces) {
    if (!(step.lambda_begin >= 0.0 && step.lambda_begin < step.lambda_end && step.lambda_end <= 1.0) ||
        step.increment != c.finished_increments + 1 || step.split_depth < 1) {
      refuse("its steps left are damaged");
    }
  }
  if (!c.previous_points.empty() &&
      (c.previous_points.size() != c.points.size() || !(c.previous_lambda >= 0.0 && c.previous_lambda < c.lambda))) {
    refuse("its previous mesh is damaged");
  }
  result_.points = c.points;
  previous_points_ = c.previous_points;
  previous_stage_ = c.previous_lambda;
  result_.lambda_reached = c.lambda;
  result_.increments = c.records;
  finished_increments_ = c.finished_increments;
  result_.timings = c.timings;  // the interrupted run's, this run's added as they come
  result_.timings.setup += setup_seconds_;
  earlier_seconds_ = c.timings.total;
}

}  // namespace hotmesh::deform::detail
