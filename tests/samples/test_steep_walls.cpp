// The steep 2D samples run as their case files say, and how closely the deformed lower wall
// follows the exact deflected wall: the bump with two shoulders (samples/step2d: four corners
// between mesh nodes) and the paper's ramp (samples/ramp2d). Without features no mesh node is
// made to sit on a corner, so every corner is cut; the bounds below are today's distances with
// some margin. The distance is the Hausdorff distance of wall_distance.hpp, the one
// samples/tools/wall_metrics gives the results pages. Issue 20 holds the corners with nodes
// (`features:` on a sliding patch); its target, wall within 0.002 h of the exact wall with no
// loss of cell quality, is written here as DISABLED_ tests, to be enabled when the case file
// accepts `features:`.
#include <gtest/gtest.h>
#include <omp.h>

#include <filesystem>
#include <string>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/case_setup.hpp"
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
  const io::CaseSetup setup = io::set_up_case(c, loaded.mesh);
  WallRun run{deform::move_mesh(loaded.mesh, setup.motions, c.material, c.solver), 0.0};
  const auto* bottom = loaded.mesh.find_patch("bottom");
  EXPECT_NE(bottom, nullptr);
  if (run.result.success && bottom) {
    run.wall_distance =
        test::hausdorff_distance(test::wall_segments(run.result.points, *bottom), test::exact_wall_segments(table));
  }
  return run;
}

/// `text` with its first `from` replaced by `to`; fails the test if there is none.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the case";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// A copy of a sample's sliding case in `dir` whose lower wall holds its corners with nodes
/// (issue 20's `features:`, angle 25 degrees), the mesh and table named by absolute paths.
fs::path with_features(const test::TempDir& dir, const fs::path& sliding_case, const std::string& mesh,
                       const std::string& table) {
  const fs::path sample = sliding_case.parent_path();
  std::string text = test::read_text(sliding_case);
  text = replaced(text, "mesh: " + mesh, "mesh: " + (sample / mesh).string());
  text = replaced(text, "bottom: {role: sliding, deflection: {file: " + table,
                  "bottom: {role: sliding, features: {angle: 25}, deflection: {file: " + (sample / table).string());
  const fs::path out = dir.path() / sliding_case.filename();
  test::write_text(out, text);
  return out;
}

const fs::path kStep = kSamples / "step2d";
const fs::path kBump = kStep / "bump.csv";
const fs::path kRamp = kSamples / "ramp2d";

// Measured (Release, jacobi-pcg, 16 increments): prescribed min scaled Jacobian 0.560, wall
// 0.0160 h from the exact bump, at the shoulders B and C (the feet: 0.0122 h); sliding 0.617
// and 0.0081 h, again at the shoulders (the feet: 0.0076 h).
TEST(StepSample, PrescribedBumpStaysValidAndCutsItsCornersByUnder0018h) {
  const auto run = run_case(kStep / "step2d.yaml", kBump);
  ASSERT_TRUE(run.result.success) << run.result.message;
  EXPECT_EQ(run.result.summary.inverted_cells, 0u);
  EXPECT_GT(run.result.summary.min_scaled_jacobian, 0.50);
  EXPECT_LT(run.wall_distance, 0.018 * kH);
}

TEST(StepSample, SlidingBumpStaysValidAndCutsItsCornersByUnder001h) {
  if (test::under_sanitizers()) GTEST_SKIP() << "4 s in the Release build, far longer here; run there";
  const auto run = run_case(kStep / "step2d-sliding.yaml", kBump);
  ASSERT_TRUE(run.result.success) << run.result.message;
  EXPECT_EQ(run.result.summary.inverted_cells, 0u);
  EXPECT_GT(run.result.summary.min_scaled_jacobian, 0.55);
  EXPECT_LT(run.wall_distance, 0.010 * kH);
}

// The ramp's published distance (docs/results/ramp2d.md, 0.0250 h without sliding), measured
// here as in the tests above: both corners cut, A and B fall between the wall's nodes.
TEST(RampSample, PrescribedRampCutsItsCornersBy0025h) {
  const auto run = run_case(kRamp / "ramp2d.yaml", kRamp / "ramp.csv");
  ASSERT_TRUE(run.result.success) << run.result.message;
  EXPECT_EQ(run.result.summary.inverted_cells, 0u);
  EXPECT_NEAR(run.wall_distance, 0.025 * kH, 0.002 * kH);
}

// Issue 20's targets with features: the wall within 0.002 h of the exact wall, no inverted
// cell, and a worst cell no worse than sliding without features gives today (bump 0.617,
// ramp 0.521). Enable these when the case file accepts `features:` (hotmesh rejects the key
// until then).
TEST(StepSample, DISABLED_SlidingBumpWithFeaturesFollowsTheExactWallWithin0002h) {
  if (test::under_sanitizers()) GTEST_SKIP() << "seconds in the Release build, far longer here; run there";
  test::TempDir dir;
  const auto run = run_case(with_features(dir, kStep / "step2d-sliding.yaml", "step2d.msh", "bump.csv"), kBump);
  ASSERT_TRUE(run.result.success) << run.result.message;
  EXPECT_EQ(run.result.summary.inverted_cells, 0u);
  EXPECT_GE(run.result.summary.min_scaled_jacobian, 0.61);
  EXPECT_LE(run.wall_distance, 0.002 * kH);
}

TEST(RampSample, DISABLED_SlidingRampWithFeaturesFollowsTheExactWallWithin0002h) {
  if (test::under_sanitizers()) GTEST_SKIP() << "seconds in the Release build, far longer here; run there";
  test::TempDir dir;
  const auto run =
      run_case(with_features(dir, kRamp / "ramp2d-sliding.yaml", "ramp2d.msh", "ramp.csv"), kRamp / "ramp.csv");
  ASSERT_TRUE(run.result.success) << run.result.message;
  EXPECT_EQ(run.result.summary.inverted_cells, 0u);
  EXPECT_GE(run.result.summary.min_scaled_jacobian, 0.52);
  EXPECT_LE(run.wall_distance, 0.002 * kH);
}

}  // namespace
}  // namespace hotmesh::samples
