// The two linear solvers on the samples: `linear: amg` (assembled in nodal frames, algebraic
// multigrid) and the paper's Jacobi-PCG move every sample's mesh to the same place
// when both solve tightly — ramp2d with and without sliding, shear2d with and without sliding,
// and the stator-well sector (sliding, passive and periodic patches) — and the AMG runs keep
// sliding nodes on their walls (u . n = 0 per step) and the periodic faces matched. The
// predictor moves the sector where the paper's start does, in fewer Newton steps.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::samples {
namespace {

namespace fs = std::filesystem;
const fs::path kSamples = fs::path(HOTMESH_SOURCE_DIR) / "samples";

struct Outcome {
  deform::MotionResult result;
  double size = 0.0;  ///< diagonal of the mesh's bounding box
};

/// Runs a sample's case in-process as `hotmesh deform` does, with the given linear solver
/// and tolerances, and `change` made to the solver's other options.
Outcome run_case(const fs::path& case_file, deform::LinearSolverKind linear, double pcg_tolerance,
                 double newton_tolerance, int increments = 0,
                 const std::function<void(deform::SolverOptions&)>& change = {}) {
  omp_set_num_threads(1);  // tests run side by side; a busy machine makes thread teams crawl
  io::Case c = io::read_case(case_file);
  const io::LoadedMesh loaded = io::read_mesh(c.mesh);
  io::check_case_against_mesh(c, loaded.mesh);
  const setup::CaseSetup setup = setup::set_up_case(c, loaded.mesh);
  c.solver.linear = linear;
  c.solver.pcg_tolerance = pcg_tolerance;
  c.solver.newton_tolerance = newton_tolerance;
  c.solver.max_newton_iterations = 60;
  c.solver.max_pcg_iterations = 100000;
  if (increments > 0) c.solver.increments = increments;
  if (change) change(c.solver);
  Outcome o{deform::move_mesh(loaded.mesh, setup.motions, c.material, c.solver), 0.0};
  geometry::Vec3 lo = loaded.mesh.points.front(), hi = lo;
  for (const auto& p : loaded.mesh.points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  o.size = norm(hi - lo);
  return o;
}

double largest_distance(const Outcome& a, const Outcome& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.result.points.size(); ++i) d = std::max(d, distance(a.result.points[i], b.result.points[i]));
  return d / a.size;
}

int linear_iterations(const deform::MotionResult& r) {
  int total = 0;
  for (const auto& increment : r.increments) {
    for (const auto& step : increment.newton) total += step.pcg_iterations;
  }
  return total;
}

int newton_steps(const deform::MotionResult& r) {
  int total = 0;
  for (const auto& increment : r.increments) total += static_cast<int>(increment.newton.size()) - 1;
  return total;
}

/// Both solvers to 1e-6 per linear solve and 1e-6 on the (stiffness-scaled) Newton residual.
/// The meshes agree to 1e-6 of the domain (measured: ramp 4e-8, sliding ramp 9e-8, shear2d
/// 4e-11, sliding shear 1.6e-9, the stator sector 4e-12), while the ramp at the default
/// tolerances is 9.3e-6 from them. AMG needs far fewer linear iterations.
void expect_same_mesh(const fs::path& case_file, int increments = 0) {
  const auto jacobi = run_case(case_file, deform::LinearSolverKind::jacobi_pcg, 1e-6, 1e-6, increments);
  const auto amg = run_case(case_file, deform::LinearSolverKind::amg, 1e-6, 1e-6, increments);
  ASSERT_TRUE(jacobi.result.success) << jacobi.result.message;
  ASSERT_TRUE(amg.result.success) << amg.result.message;
  EXPECT_LT(largest_distance(jacobi, amg), 1e-6);
  EXPECT_EQ(amg.result.summary.inverted_cells, 0u);
  EXPECT_NEAR(amg.result.summary.min_scaled_jacobian, jacobi.result.summary.min_scaled_jacobian, 1e-4);
  EXPECT_LT(linear_iterations(amg.result), linear_iterations(jacobi.result) / 3);
  // Sliding nodes kept to their walls, periodic faces matched, with amg as with jacobi-pcg.
  EXPECT_LT(amg.result.max_normal_slip, 1e-12 * amg.size);
  EXPECT_LT(amg.result.final_projection_distance / amg.result.length_scale, 1e-8);
  EXPECT_LT(amg.result.max_periodic_mismatch / amg.result.length_scale, 1e-12);
}

TEST(LinearSolvers, AmgAndJacobiPcgGiveTheSameRamp) {
  const fs::path ramp = kSamples / "ramp2d" / "ramp2d.yaml";
  expect_same_mesh(ramp);
  // The comparison can fail: at the default tolerances the mesh is elsewhere by more (9.3e-6).
  // And the defaults are close: the Newton residual scaled by each node's stiffness is not
  // satisfied by settling the boundary layer's stiff cells alone (the plain norm left the
  // default run 3.5e-4 from the converged mesh).
  const auto tight = run_case(ramp, deform::LinearSolverKind::amg, 1e-6, 1e-6);
  const auto loose = run_case(ramp, deform::LinearSolverKind::amg, 1e-3, 1e-4);
  EXPECT_GT(largest_distance(loose, tight), 3e-6);
  EXPECT_LT(largest_distance(loose, tight), 3e-5);
}

// The paper's sliding (features off): with features, the repair after the corner pass
// (quality_repair.hpp) is a search that stops once the worst cell is restored, so meshes that
// differ by 1e-7 can end up to 1e-3 apart in the few nodes it moves; both solvers are
// compared on the motion itself. (The corner pass with amg: WallCorners.*Amg*.)
TEST(LinearSolvers, AmgAndJacobiPcgGiveTheSameSlidingRamp) {
  if (test::under_sanitizers()) GTEST_SKIP() << "a minute in the Release build; run there";
  expect_same_mesh(kSamples / "ramp2d" / "ramp2d-sliding-nofeatures.yaml");
}

TEST(LinearSolvers, AmgAndJacobiPcgGiveTheSameShear) { expect_same_mesh(kSamples / "shear2d" / "shear2d.yaml"); }

TEST(LinearSolvers, AmgAndJacobiPcgGiveTheSameSlidingShear) {
  expect_same_mesh(kSamples / "shear2d" / "shear2d-sliding.yaml");
}

/// The stator-well sector of about 2 000 cells (the generator writes mesh, CAD, tables and
/// case files): sliding disc walls, passive inlet and outlet, periodic faces; 8 increments.
TEST(LinearSolvers, AmgAndJacobiPcgGiveTheSameStatorWellSector) {
  if (test::under_sanitizers()) GTEST_SKIP() << "a minute in the Release build; run there";
  test::TempDir dir;
  const auto generate = test::run_command(std::string(HOTMESH_MAKE_STATOR_WELL) + " --cells 2000 " +
                                          test::shell_quote(dir.path().string()));
  ASSERT_EQ(generate.exit_code, 0) << generate.output;
  expect_same_mesh(dir / "case_small.yaml", 8);
}

/// The predictor (a case file's default) starts each increment after the first along the
/// secant of the last accepted step. On the sector of about 2 000 cells in the paper's 16
/// increments, with the amg solver and Eisenstat-Walker forcing as at the paper's size: solved
/// tightly, both starts end on the same mesh (1.6e-9 of the domain apart); at the test's
/// tolerances (1e-3, 1e-4) the predicted run ends 1.3e-5 of the domain from that mesh (the
/// paper's start 4.4e-6) in 18 Newton steps and 52 CG iterations against 48 and 231, every
/// increment after the first in one step (the paper's start: three). The chord from the
/// undeformed mesh (the predictor before the secant) took two steps from increment 6 on.
/// With the reference of the Newton tolerance taken at the predicted start instead of the
/// paper's, the predicted run took 31 Newton steps on 8 increments: this test fails.
TEST(LinearSolvers, PredictorMovesTheSectorAsThePapersStartInFewerSteps) {
  if (test::under_sanitizers()) GTEST_SKIP() << "half a minute in the Release build; run there";
  test::TempDir dir;
  const auto generate = test::run_command(std::string(HOTMESH_MAKE_STATOR_WELL) + " --cells 2000 " +
                                          test::shell_quote(dir.path().string()));
  ASSERT_EQ(generate.exit_code, 0) << generate.output;
  const auto run = [&](bool predictor, double pcg_tolerance, double newton_tolerance) {
    return run_case(dir / "case_small.yaml", deform::LinearSolverKind::amg, pcg_tolerance, newton_tolerance, 16,
                    [predictor](deform::SolverOptions& s) {
                      s.predictor = predictor;
                      s.forcing = deform::ForcingTerm::eisenstat_walker;
                    });
  };
  const auto tight_paper = run(false, 1e-8, 1e-8), tight_predicted = run(true, 1e-8, 1e-8);
  ASSERT_TRUE(tight_paper.result.success) << tight_paper.result.message;
  ASSERT_TRUE(tight_predicted.result.success) << tight_predicted.result.message;
  EXPECT_LT(largest_distance(tight_paper, tight_predicted), 1e-8);
  const auto paper = run(false, 1e-3, 1e-4), predicted = run(true, 1e-3, 1e-4);
  ASSERT_TRUE(paper.result.success) << paper.result.message;
  ASSERT_TRUE(predicted.result.success) << predicted.result.message;
  EXPECT_LT(largest_distance(predicted, tight_paper), 3e-5);  // 1.3e-5; the paper's start 4.4e-6
  EXPECT_LT(newton_steps(predicted.result), newton_steps(paper.result) * 3 / 4);
  EXPECT_LT(linear_iterations(predicted.result), linear_iterations(paper.result));
  EXPECT_NEAR(predicted.result.summary.min_scaled_jacobian, paper.result.summary.min_scaled_jacobian, 1e-3);
  // The first increment has nothing to predict from: it is the paper's.
  EXPECT_EQ(predicted.result.increments.front().newton.size(), paper.result.increments.front().newton.size());
  for (std::size_t k = 1; k < predicted.result.increments.size(); ++k) {
    EXPECT_EQ(predicted.result.increments[k].newton.size() - 1, 1u) << "Newton steps of increment " << k + 1;
  }
}

}  // namespace
}  // namespace hotmesh::samples
