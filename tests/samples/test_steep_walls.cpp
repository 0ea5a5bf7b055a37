// The steep 2D samples run as their case files say, and how closely the deformed lower wall
// follows the exact deflected wall: the bump with two shoulders (samples/step2d: four corners
// between mesh nodes) and the paper's ramp (samples/ramp2d). Without features no mesh node is
// made to sit on a corner, so every corner is cut; the bounds below are today's distances with
// some margin. The distance is the Hausdorff distance of wall_distance.hpp, the one
// samples/tools/wall_metrics gives the results pages. Issue 20 holds the corners with nodes
// (`features:` on a sliding patch, on by default): the wall within 0.002 h of the exact wall.
#include <gtest/gtest.h>
#include <omp.h>

#include <filesystem>
#include <string>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "test_support.hpp"
#include "wall_distance.hpp"

namespace hotmesh::samples {
namespace {

namespace fs = std::filesystem;
const fs::path kSamples = fs::path(HOTMESH_SOURCE_DIR) / "samples";
constexpr double kH = 1.0;  ///< the channel height of both samples

struct WallRun {
  deform::MotionResult result;
  double wall_distance = 0.0;  ///< Hausdorff distance, lower wall to exact deflected wall
};

/// Runs a case in-process as `hotmesh deform` does (its own solver settings, one thread) and
/// measures its deformed lower wall `bottom` against the polyline of `table`.
WallRun run_case(const fs::path& case_file, const fs::path& table) {
  omp_set_num_threads(1);  // tests run side by side; a busy machine makes thread teams crawl
  const io::Case c = io::read_case(case_file);
  const io::LoadedMesh loaded = io::read_mesh(c.mesh);
  io::check_case_against_mesh(c, loaded.mesh);
  const setup::CaseSetup setup = setup::set_up_case(c, loaded.mesh);
  WallRun run{deform::move_mesh(loaded.mesh, setup.motions, c.material, c.solver), 0.0};
  const auto* bottom = loaded.mesh.find_patch("bottom");
  EXPECT_NE(bottom, nullptr);
  if (run.result.success && bottom) {
    run.wall_distance =
        test::hausdorff_distance(test::wall_segments(run.result.points, *bottom), test::exact_wall_segments(table));
  }
  return run;
}

/// The run reached the deflected walls and inverted no cell.
::testing::AssertionResult valid(const WallRun& run) {
  if (!run.result.success) return ::testing::AssertionFailure() << run.result.message;
  if (run.result.summary.inverted_cells != 0) {
    return ::testing::AssertionFailure() << run.result.summary.inverted_cells << " inverted cells";
  }
  return ::testing::AssertionSuccess();
}

const fs::path kStep = kSamples / "step2d";
const fs::path kBump = kStep / "bump.csv";
const fs::path kRamp = kSamples / "ramp2d";

// Measured (Release, jacobi-pcg, 16 increments): prescribed min scaled Jacobian 0.560, wall
// 0.0160 h from the exact bump, at the shoulders B and C (the feet: 0.0122 h); sliding 0.617
// and 0.0081 h, again at the shoulders (the feet: 0.0076 h).
TEST(StepSample, PrescribedBumpStaysValidAndCutsItsCornersByUnder0018h) {
  const auto run = run_case(kStep / "step2d.yaml", kBump);
  ASSERT_TRUE(valid(run));
  EXPECT_GT(run.result.summary.min_scaled_jacobian, 0.50);
  EXPECT_LT(run.wall_distance, 0.018 * kH);
}

TEST(StepSample, SlidingBumpStaysValidAndCutsItsCornersByUnder001h) {
  if (test::under_sanitizers()) GTEST_SKIP() << "4 s in the Release build, far longer here; run there";
  const auto run = run_case(kStep / "step2d-sliding-nofeatures.yaml", kBump);
  ASSERT_TRUE(valid(run));
  EXPECT_GT(run.result.summary.min_scaled_jacobian, 0.55);
  EXPECT_LT(run.wall_distance, 0.010 * kH);
}

// The ramp's published distance (docs/results/ramp2d.md, 0.0250 h without sliding), measured
// here as in the tests above: both corners cut, A and B fall between the wall's nodes.
TEST(RampSample, PrescribedRampCutsItsCornersBy0025h) {
  const auto run = run_case(kRamp / "ramp2d.yaml", kRamp / "ramp.csv");
  ASSERT_TRUE(valid(run));
  EXPECT_NEAR(run.wall_distance, 0.025 * kH, 0.002 * kH);
}

// Issue 20's targets with features (the sample cases, whose sliding walls hold their corners by
// default): the wall within 0.002 h of the exact wall, no inverted cell, and a worst cell no
// worse than sliding without features gives (bump 0.61690; the ramp's below). The corner pass
// alone leaves 0.512 on the ramp (the node that takes corner A moves a whole foot cell, 0.037 h,
// and the mesh line above it shears) and 0.610 on the bump; the repair of the cells it left
// below the motion's worst cell restores them (deform/src/motion/quality_repair.hpp).
TEST(StepSample, SlidingBumpWithFeaturesFollowsTheExactWallWithin0002h) {
  if (test::under_sanitizers()) GTEST_SKIP() << "seconds in the Release build, far longer here; run there";
  const auto run = run_case(kStep / "step2d-sliding.yaml", kBump);
  ASSERT_TRUE(valid(run));
  EXPECT_GE(run.result.summary.min_scaled_jacobian, 0.6169);
  EXPECT_LE(run.wall_distance, 0.002 * kH);
}

// The ramp's worst cell is compared with the run without features by the same linear solver
// (`auto` takes the exact factorization there: 0.521324 against 0.521299; amg's inexact steps
// gave 0.52133 without features).
TEST(RampSample, SlidingRampWithFeaturesFollowsTheExactWallWithin0002h) {
  if (test::under_sanitizers()) GTEST_SKIP() << "seconds in the Release build, far longer here; run there";
  const auto paper = run_case(kRamp / "ramp2d-sliding-nofeatures.yaml", kRamp / "ramp.csv");
  const auto run = run_case(kRamp / "ramp2d-sliding.yaml", kRamp / "ramp.csv");
  ASSERT_TRUE(valid(paper));
  ASSERT_TRUE(valid(run));
  EXPECT_GE(run.result.summary.min_scaled_jacobian, paper.result.summary.min_scaled_jacobian);
  EXPECT_GT(run.result.summary.min_scaled_jacobian, 0.52);
  EXPECT_LE(run.wall_distance, 0.002 * kH);
}

}  // namespace
}  // namespace hotmesh::samples
