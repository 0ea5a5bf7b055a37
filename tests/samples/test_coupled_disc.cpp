// Tests of the coupled_disc sample (samples/coupled_disc): its run_loop.sh, on a stator well of
// about 5 000 cells, runs the real ccx and hotmesh for two coupling iterations; both meshes are
// valid, every rotor wall lies on its wall deflected by ccx's results (hotmesh check from the
// case file), the second iteration restarts from the first and ends where a run straight from
// the undeformed sector ends; coupled_loop.py, the loop in Python, moves the sector as it does;
// a surface put on the wrong CAD faces is refused with exit code 2.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include <nlohmann/json.hpp>

#include "calculix_runs.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "run_command.hpp"
#include "sample_folder.hpp"
#include "test_support.hpp"

namespace hotmesh::samples {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using test::shell_quote;

const fs::path kSample = fs::path(HOTMESH_SOURCE_DIR) / "samples" / "coupled_disc";

/// The stator well (5 000 cells) and the coupled_disc sample beside it, in a temporary folder.
struct CoupledDisc : SampleFolder {
  CoupledDisc() : SampleFolder("coupled_disc") {
    const auto well = test::run_command(std::string(HOTMESH_MAKE_STATOR_WELL) + " --cells 5000 " +
                                        shell_quote((dir / "stator_well").string()));
    EXPECT_EQ(well.exit_code, 0) << well.output;
    const auto disc = test::run_command(std::string(HOTMESH_MAKE_COUPLED_DISC) + " " + shell_quote(folder.string()));
    EXPECT_EQ(disc.exit_code, 0) << disc.output;
    fs::copy_file(kSample / "run_loop.sh", folder / "run_loop.sh");
  }
};

TEST(CoupledDiscRun, TwoIterationsFromCcxAreValidOnTheDeflectedRotorAndTheRestartContinues) {
  if (test::under_sanitizers()) GTEST_SKIP() << "three 3D runs: a minute in the Release build, far longer here; run there";
  if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
  const CoupledDisc sample;
  const auto loop = sample.run_script("run_loop.sh");
  ASSERT_EQ(loop.exit_code, 0) << loop.output;
  // hotmesh fem listed the deck's surfaces; hotmesh check found every wall, rotor ones from
  // ccx's .frd included, on its deflected CAD wall, in both iterations.
  EXPECT_THAT(loop.output, ::testing::ContainsRegex("surface +DISC_BASE +[0-9]+ nodes"));
  EXPECT_EQ(occurrences(loop.output, "10 of 10 patches within the tolerance"), 2u) << loop.output;
  for (const std::string run : {"case_1", "case_2"}) {
    const nlohmann::json report = sample.report(run);
    EXPECT_EQ(report["status"], "success") << run;
    EXPECT_EQ(report["inverted_cells"], 0) << run;
    EXPECT_GT(report["min_scaled_jacobian"].get<double>(), 0.5) << run;
    EXPECT_GT(report["sliding_nodes"].get<int>(), 100) << run;
    EXPECT_LT(report["final_projection_distance_relative"].get<double>(), 1e-9) << run;
  }
  EXPECT_THAT(sample.report("case_2")["restarted_from"].get<std::string>(), HasSubstr("case_1-out/restart.hmr"));

  // Restart continuity: iteration 2 run straight from the undeformed sector ends close to the
  // restarted run (the walls' slides carried over, eq. 22), within a small part of the
  // largest wall deflection (about 1.8 mm).
  std::string straight = test::read_text(sample.folder / "case_2.yaml");
  straight = std::regex_replace(straight, std::regex("\nrestart: [^\n]*"), "");
  test::write_text(sample.folder / "straight_2.yaml", straight);
  const auto direct = test::run_command(std::string(HOTMESH_EXE) + " -q deform " +
                                        shell_quote((sample.folder / "straight_2.yaml").string()));
  ASSERT_EQ(direct.exit_code, 0) << direct.output;
  const mesh::Mesh restarted = sample.deformed("case_2");
  const mesh::Mesh fresh = sample.deformed("straight_2");
  const mesh::Mesh first = sample.deformed("case_1");
  double apart = 0.0, moved = 0.0;
  for (std::size_t n = 0; n < restarted.node_count(); ++n) {
    apart = std::max(apart, distance(restarted.points[n], fresh.points[n]));
    moved = std::max(moved, distance(restarted.points[n], first.points[n]));
  }
  std::printf("iteration 2: restarted vs straight %.3g m apart at most; moved %.3g m from iteration 1\n", apart, moved);
  EXPECT_GT(moved, 1e-5);  // the hotter disc moved the mesh on
  EXPECT_LT(apart, 0.05 * moved);
}

#ifdef HOTMESH_PYTHON_MODULE_DIR
// coupled_loop.py, the same loop in Python with the mesh moved in memory (the second iteration
// from the first one's result, no restart file), writes the meshes run_loop.sh writes.
TEST(CoupledDiscRun, ThePythonLoopMovesTheSectorInMemoryAsTheCommandsLoopDoes) {
  if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
  const CoupledDisc sample;
  const auto loop = sample.run_script("run_loop.sh");
  ASSERT_EQ(loop.exit_code, 0) << loop.output;
  for (const std::string i : {"1", "2"}) fs::rename(sample.folder / ("case_" + i + "-out"), sample.folder / ("command_" + i + "-out"));
  fs::copy_file(kSample / "coupled_loop.py", sample.folder / "coupled_loop.py");
  const auto python = test::run_command("PYTHONPATH=" + shell_quote(HOTMESH_PYTHON_MODULE_DIR) + " " +
                                        shell_quote(HOTMESH_PYTHON_EXECUTABLE) + " " +
                                        shell_quote((sample.folder / "coupled_loop.py").string()) + " " +
                                        shell_quote(sample.folder.string()) + " 2>&1");
  ASSERT_EQ(python.exit_code, 0) << python.output;
  EXPECT_THAT(python.output, ::testing::ContainsRegex("iteration 2: [0-9]+ nodes, min scaled Jacobian 0\\.[5-9][0-9]+; "
                                                      "10 of 10 walls on their deflected walls"));
  for (const std::string i : {"1", "2"}) {
    const std::string in_memory = test::read_text(sample.folder / ("case_" + i + "-out") / "deformed.msh");
    EXPECT_FALSE(in_memory.empty());
    EXPECT_TRUE(in_memory == test::read_text(sample.folder / ("command_" + i + "-out") / "deformed.msh"))
        << "iteration " << i << ": the Python loop's deformed.msh differs from run_loop.sh's";
  }
  EXPECT_FALSE(sample.report("case_2").contains("restarted_from"));  // in memory, from no file
}
#endif

TEST(CoupledDiscRun, ASurfaceOnTheWrongCadFacesIsRefusedNamingItsDeckLine) {
  if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
  const CoupledDisc sample;
  ASSERT_EQ(test::run_ccx(sample.folder, "disc_1").exit_code, 0);
  // The drum's nodes given to the downstream disc's faces: they are far from them.
  std::string yaml = test::read_text(sample.folder / "case_1.yaml");
  yaml = std::regex_replace(yaml, std::regex("set: DISC_DOWN"), "set: DISC_BASE");
  test::write_text(sample.folder / "wrong.yaml", yaml);
  const auto r = test::run_command(std::string(HOTMESH_EXE) + " -q deform " + shell_quote((sample.folder / "wrong.yaml").string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, ::testing::ContainsRegex("disc_mesh\\.inp:[0-9]+ \\(set DISC_BASE, displacements from .*disc_1\\.frd\\): "
                                                 "[0-9]+ of [0-9]+ FEM nodes are farther than"));
}

}  // namespace
}  // namespace hotmesh::samples
