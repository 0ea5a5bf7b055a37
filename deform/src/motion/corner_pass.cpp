// hotmesh deform: the corner pass (corner_pass.hpp): the walls held at their final stage, the
// pass run as a Motion of its own, its result merged into the motion's.
#include "motion/corner_pass.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "motion/motion.hpp"
#include "motion/quality_repair.hpp"
#include "hotmesh/core/clock.hpp"

namespace hotmesh::deform::detail {
namespace {

/// Increments of the corner pass: its nodes move at most half a wall edge along their walls.
constexpr int kCornerPassIncrements = 2;

/// A wall at its fully deflected stage for every lambda: the walls of the corner pass, which
/// starts where the motion ended and moves nothing but the nodes given corners.
class FinalStage final : public geometry::BoundaryShape {
 public:
  explicit FinalStage(std::shared_ptr<const geometry::BoundaryShape> shape) : shape_(std::move(shape)) {}
  geometry::ShapePoint project(const Vec3& p, double /*lambda*/, const geometry::ShapeParameter& hint,
                               const geometry::ParameterRange& range) const override {
    return shape_->project(p, 1.0, hint, range);
  }
  geometry::ShapePoint at(const geometry::ShapeParameter& where, double /*lambda*/, const Vec3& reference) const override {
    return shape_->at(where, 1.0, reference);
  }
  std::vector<geometry::ShapeFeature> features(double min_angle) const override { return shape_->features(min_angle); }
  std::vector<std::shared_ptr<const geometry::BoundaryShape>> crease_sides(const geometry::ShapeParameter& where,
                                                                         double min_angle) const override {
    auto sides = shape_->crease_sides(where, min_angle);
    for (auto& side : sides) side = std::make_shared<const FinalStage>(std::move(side));
    return sides;
  }
  std::vector<geometry::ShapeCrease> creases(double min_angle) const override { return shape_->creases(min_angle); }
  int crease_region(int face, double min_angle) const override { return shape_->crease_region(face, min_angle); }
  geometry::CreasePoint crease_point(const geometry::ShapeCrease& crease, const Vec3& p,
                                     double /*lambda*/) const override {
    return shape_->crease_point(crease, p, 1.0);
  }

 private:
  std::shared_ptr<const geometry::BoundaryShape> shape_;
};

MotionResult with_corner_pass(const Mesh& mesh, MotionResult moved, MotionResult pass);

/// The corner pass is kept only if its worst cell, after the repair, keeps at least this share
/// of the motion's worst: holding corners must not ruin the mesh it sharpens.
constexpr double kPassKeepsQuality = 0.5;

/// Sweeps of the repair after the corner pass (quality_repair.hpp), at most.
constexpr int kRepairSweeps = 50;

/// The pass must not cost quality: where it left cells below the motion's worst cell
/// (`motion`), the interior nodes of those cells are moved to restore it (quality_repair.hpp).
void restore_worst_cell(const Mesh& mesh, const QualitySummary& motion, MotionResult& pass) {
  std::vector<char> interior(pass.node_roles.size());
  std::transform(pass.node_roles.begin(), pass.node_roles.end(), interior.begin(),
                 [](NodeRoleCode role) { return role == kInteriorNodeCode ? 1 : 0; });
  const QualityRepair r =
      repair_cells_below(mesh, pass.points, interior, motion.min_scaled_jacobian, kRepairSweeps);
  pass.corner_repair = {r.cells_below, r.nodes_moved, r.min_before, r.min_after};
  pass.quality = scaled_jacobians(mesh.cells, pass.points);
  pass.summary = summarize_quality(pass.quality);
}

}  // namespace

bool has_corners(std::span<const PatchMotion> patches) {
  return std::any_of(patches.begin(), patches.end(), [](const PatchMotion& m) {
    return m.role == BoundaryRole::sliding && m.features.enabled && m.shape &&
           (!m.shape->features(m.features.angle).empty() ||
            !m.shape->creases(m.features.angle).empty());
  });
}

MotionResult hold_corners(const Mesh& mesh, std::span<const PatchMotion> patches,
                          const StiffnessKernel& motion_kernel, const MaterialOptions& material,
                          const SolverOptions& solver, const MotionObservers& observers,
                          const parallel::RankExchange& ranks, MotionResult moved) {
  std::vector<PatchMotion> final_walls(patches.begin(), patches.end());
  for (PatchMotion& m : final_walls) {
    if (m.shape) m.shape = std::make_shared<const FinalStage>(m.shape);
  }
  const int n = std::max(solver.increments, 1);
  SolverOptions pass_options = solver;
  pass_options.increments = kCornerPassIncrements;
  // Its increments follow the motion's, N + 1 ..., at stage 1; no checkpoints (a resumed run
  // repeats the pass from the motion's last checkpoint).
  const auto as_corner_pass = [n](IncrementRecord r) {
    r.increment += n;
    r.lambda_begin = r.lambda_end = 1.0;
    r.corner_pass = true;
    return r;
  };
  MotionObservers pass_observers;
  if (observers.increment) {
    pass_observers.increment = [&](const IncrementRecord& r) { observers.increment(as_corner_pass(r)); };
  }
  if (observers.newton) {
    pass_observers.newton = [&](NewtonProgress p) {
      p.step.increment += n;
      p.step.lambda_begin = p.step.lambda_end = 1.0;
      p.increments = n + kCornerPassIncrements;
      observers.newton(p);
    };
  }
  const MotionStart from{moved.points, moved.sliding_origins};
  const auto begin = Clock::now();
  auto kernel = std::make_shared<const StiffnessKernel>(
      motion_kernel.with_lame(element_lame(mesh, moved.points, material, moving_wall_nodes(mesh, patches))));
  std::optional<Motion> motion;
  try {  // the motion's mesh as the pass's input: a node it left off its walls is no user error now
    motion.emplace(mesh, final_walls, std::move(kernel), pass_options, pass_observers, &from, ranks);
  } catch (const InputError& e) {
    moved.notes.push_back(fmt::format("the corners of the sliding walls could not be given nodes ({}); the mesh is the "
                                      "one the motion gave, whose walls may cut them",
                                      e.what()));
    return moved;
  }
  motion->set_setup_time(seconds_since(begin));
  MotionResult pass = motion->run(nullptr);

  for (const IncrementRecord& r : pass.increments) moved.increments.push_back(as_corner_pass(r));
  return with_corner_pass(mesh, std::move(moved), std::move(pass));
}

namespace {

/// The motion's result `moved` with the corner pass's `pass` after it: its times added, and,
/// if it succeeded, its mesh, quality and corners.
MotionResult with_corner_pass(const Mesh& mesh, MotionResult moved, MotionResult pass) {
  MotionTimings& t = moved.timings;
  t.setup += pass.timings.setup;
  t.assembly += pass.timings.assembly;
  t.preconditioner += pass.timings.preconditioner;
  t.solve += pass.timings.solve;
  t.projection += pass.timings.projection;
  t.quality += pass.timings.quality;
  t.total += pass.timings.total;
  if (!pass.success) {
    moved.notes.push_back("the corners of the sliding walls could not be given nodes (" + pass.message +
                          "); the mesh is the one the motion gave, whose walls may cut them");
    return moved;
  }
  for (std::string& note : pass.notes) {  // the setup's notes on the walls are the motion's too
    if (std::find(moved.notes.begin(), moved.notes.end(), note) == moved.notes.end()) {
      moved.notes.push_back(std::move(note));
    }
  }
  // The pass's walls are the fully deflected ones at every stage: a feature's turn on the
  // undeformed wall is the motion's measure.
  for (WallFeature& f : pass.features) {
    const auto same = std::find_if(moved.features.begin(), moved.features.end(), [&](const WallFeature& m) {
      return m.patch == f.patch && m.faces == f.faces && m.parameter == f.parameter;
    });
    if (same != moved.features.end()) f.angle = std::max(f.angle, same->angle);
  }
  if (pass.summary.min_scaled_jacobian < moved.summary.min_scaled_jacobian) restore_worst_cell(mesh, moved.summary, pass);
  if (pass.summary.min_scaled_jacobian < kPassKeepsQuality * moved.summary.min_scaled_jacobian) {
    moved.notes.push_back(fmt::format(
        "the corner pass was undone: holding the corners of the sliding walls would leave cell {} at a scaled "
        "Jacobian of {:.3g}, against the motion's worst {:.3g} (corners within a cell of each other: a deflection "
        "table without a node on a corner of the wall cuts it with kinks of its own; give it a node there, or take "
        "form: displacement); the mesh is the one the motion gave, whose walls may cut the corners it did not hold",
        mesh.cell_id(pass.summary.worst_cell), pass.summary.min_scaled_jacobian, moved.summary.min_scaled_jacobian));
    return moved;
  }
  moved.corner_repair = pass.corner_repair;
  moved.restart_points = std::exchange(moved.points, std::move(pass.points));
  moved.quality = std::move(pass.quality);
  moved.summary = pass.summary;
  moved.features = std::move(pass.features);
  moved.max_periodic_mismatch = pass.max_periodic_mismatch;
  moved.max_projection_distance = std::max(moved.max_projection_distance, pass.max_projection_distance);
  moved.final_projection_distance = pass.final_projection_distance;
  moved.max_normal_slip = std::max(moved.max_normal_slip, pass.max_normal_slip);
  return moved;
}

}  // namespace

}  // namespace hotmesh::deform::detail
