// Tests of `hotmesh deform`, the main job, end to end on the ramp sample: outputs and
// report, a motion that fails (last valid mesh kept, exit code 1), and bad input (exit code 2,
// nothing written).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <set>

#include <fmt/format.h>

#include "hotmesh/deform/structured_mesh.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/deform/quality.hpp"
#include "deform_cases.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using test::hotmesh;
using test::kSample;
using test::RampCase;
using test::read_json;
using test::shell_quote;

TEST(DeformCommand, RampSampleCompletesWithEveryOutputAndReport) {
  test::TempDir out;
  const auto r = hotmesh("deform " + shell_quote((kSample / "ramp2d.yaml").string()) + " -o " + shell_quote(out.path().string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("increment 16/16"));
  for (const char* f : {"deformed.msh", "deformed.vtu", "deformed.png", "ramp.png", "corner_a.png", "corner_b.png",
                        "mid_ramp.png", "report.json"}) {
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  }
  EXPECT_FALSE(std::filesystem::exists(out / "failed.vtu"));
  const auto report = read_json(out / "report.json");
  EXPECT_EQ(report["status"], "success");
  EXPECT_EQ(report["increments"].size(), 16u);
  EXPECT_EQ(report["inverted_cells"], 0);
  EXPECT_GT(report["min_scaled_jacobian"].get<double>(), 0.2);
  EXPECT_GT(report["wall_seconds"].get<double>(), 0.0);
  for (const auto& inc : report["increments"]) {
    EXPECT_TRUE(inc["converged"].get<bool>());
    EXPECT_LE(inc["residual_reduction"].get<double>(), 1e-4);
    EXPECT_EQ(inc["pcg_iterations"].size(), inc["newton_iterations"].get<std::size_t>());
  }
  // The deformed mesh: the lower wall lies on the ramp, and no cell is inverted.
  const deform::Mesh moved = io::read_gmsh(out / "deformed.msh");
  for (deform::NodeId n : moved.find_patch("bottom")->nodes) {
    const double x = moved.points[static_cast<std::size_t>(n)].x;
    const double y = moved.points[static_cast<std::size_t>(n)].y;
    const double ramp = x <= 0.975 ? 0.0 : x >= 1.025 ? 0.5 : 0.5 * (x - 0.975) / 0.05;
    EXPECT_NEAR(y, ramp, 1e-9) << "x = " << x;
  }
  const auto q = deform::summarize_quality(deform::scaled_jacobians(moved.cells, moved.points));
  EXPECT_EQ(q.inverted_cells, 0u);
}

/// `linear: amg` runs PETSc inside the process, without mpirun, and leaves no MPI session
/// folder behind; the report names the solver and splits its time into phases.
TEST(DeformCommand, AmgSolverRunsWithoutMpirunAndReportsItsPhases) {
  std::string yaml = test::read_text(kSample / "ramp2d-sliding.yaml");
  yaml.replace(yaml.find("solver:\n"), 8, "solver:\n  linear: amg\n  forcing: eisenstat-walker\n");
  const RampCase ramp(yaml);
  test::TempDir tmp;
  const auto r = test::run_command("TMPDIR=" + shell_quote(tmp.path().string()) + " " + HOTMESH_EXE + " deform " + ramp.case_file());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("linear solver amg (gamg)"));
  EXPECT_THAT(r.output, HasSubstr("preconditioner"));
  EXPECT_TRUE(std::filesystem::is_empty(tmp.path()));  // Open MPI's session folder removed
  const auto report = read_json(ramp.dir / "case-out" / "report.json");
  EXPECT_EQ(report["status"], "success");
  EXPECT_EQ(report["solver"]["linear"], "amg");
  EXPECT_EQ(report["solver"]["amg"], "gamg");
  EXPECT_EQ(report["solver"]["forcing"], "eisenstat-walker");
  for (const char* phase : {"assembly", "preconditioner", "solve", "projection"}) {
    EXPECT_GT(report["seconds"][phase].get<double>(), 0.0) << phase;
  }
  EXPECT_LT(report["max_normal_slip"].get<double>(), 1e-12);
  // Inexact Newton: the tolerances given to the linear solves vary, never below pcg_tolerance.
  // The first solve of every increment stops on the Newton norm ||D^-1 r|| at pcg_tolerance;
  // the loose ones stop on ||r||.
  std::set<double> tolerances;
  std::size_t residual_norm_solves = 0;
  for (const auto& inc : report["increments"]) {
    const auto& eta = inc["linear_tolerances"];
    const auto& norms = inc["linear_norms"];
    EXPECT_EQ(eta.size(), inc["pcg_iterations"].size());
    ASSERT_EQ(norms.size(), eta.size());
    ASSERT_FALSE(norms.empty());
    EXPECT_EQ(norms[0], "newton") << inc["increment"];
    for (std::size_t i = 0; i < eta.size(); ++i) {
      tolerances.insert(eta[i].get<double>());
      if (norms[i] == "newton") EXPECT_EQ(eta[i].get<double>(), 1e-3) << inc["increment"] << " solve " << i;
      else residual_norm_solves += norms[i] == "residual";
    }
  }
  EXPECT_GT(tolerances.size(), 2u);
  EXPECT_GE(*tolerances.begin(), 1e-3);
  EXPECT_GT(residual_norm_solves, 0u);
}

TEST(DeformCommand, FailedMotionKeepsLastValidMeshAndMarksFailedCells) {
  // The ramp pushed through the top wall: cannot be done.
  RampCase ramp(
      "mesh: ramp2d.msh\nsolver: {increments: 2, max_increment_splits: 1}\n"
      "patches:\n  left: {role: fixed}\n  right: {role: slip}\n  top: {role: fixed}\n"
      "  bottom: {role: prescribed, deflection: {file: steep.csv}}\n");
  test::write_text(ramp.dir / "steep.csv", "x,y,dx,dy\n0,0,0,0\n0.9,0,0,0\n1.1,0,0,1.4\n2,0,0,1.4\n");
  const auto r = hotmesh("deform " + ramp.case_file());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("increment 1 of 2 failed"));
  const auto out = ramp.dir / "case-out";
  EXPECT_TRUE(std::filesystem::exists(out / "failed.vtu"));
  EXPECT_TRUE(std::filesystem::exists(out / "failed.png"));
  const auto report = read_json(out / "report.json");
  EXPECT_EQ(report["status"], "failed");
  EXPECT_LT(report["stage_reached"].get<double>(), 1.0);
  EXPECT_THAT(report["message"].get<std::string>(), HasSubstr("cell"));
  const deform::Mesh kept = io::read_gmsh(out / "deformed.msh");
  EXPECT_EQ(deform::summarize_quality(deform::scaled_jacobians(kept.cells, kept.points)).inverted_cells, 0u);
  EXPECT_THAT(test::read_text(out / "failed.vtu"), HasSubstr("Name=\"inverted\""));
}

TEST(DeformCommand, BadCaseIsAUserErrorAndWritesNothing) {
  RampCase ramp("mesh: ramp2d.msh\nsolver: {increments: 0}\npatches:\n  left: {role: fixed}\n");
  const auto r = hotmesh("deform " + ramp.case_file());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("case.yaml:2: solver.increments: must be an integer >= 1, got 0"));
  EXPECT_FALSE(std::filesystem::exists(ramp.dir / "case-out"));
  // With the YAML right, the case is checked against the mesh.
  test::write_text(ramp.dir / "case.yaml", "mesh: ramp2d.msh\npatches:\n  left: {role: fixed}\n");
  const auto roles = hotmesh("deform " + ramp.case_file());
  EXPECT_EQ(roles.exit_code, 2);
  EXPECT_THAT(roles.output, HasSubstr("case.yaml:2: patches: mesh patch 'right' has no role"));
  EXPECT_FALSE(std::filesystem::exists(ramp.dir / "case-out"));
}

TEST(DeformCommand, RefusesOutputFolderHoldingInputsUnlessForced) {
  RampCase ramp(
      "mesh: ramp2d.msh\nsolver: {increments: 2}\n"
      "patches:\n  left: {role: fixed}\n  right: {role: slip}\n  top: {role: fixed}\n"
      "  bottom: {role: prescribed, deflection: {file: ramp.csv}}\n");
  const std::string before = test::read_text(ramp.dir / "ramp2d.msh");
  const auto refused = hotmesh("deform " + ramp.case_file() + " -o " + shell_quote(ramp.dir.path().string()));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.output, HasSubstr("--force"));
  const auto forced = hotmesh("-q deform --force " + ramp.case_file() + " -o " + shell_quote(ramp.dir.path().string()));
  EXPECT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_EQ(test::read_text(ramp.dir / "ramp2d.msh"), before);  // inputs untouched
  EXPECT_TRUE(std::filesystem::exists(ramp.dir / "deformed.msh"));
}

}  // namespace
}  // namespace hotmesh::app

namespace hotmesh::app {
namespace {

using test::ramp_case;
using test::write_coarse_ramp;

TEST(DeformCommand, RestartFromSavedStateMatchesAStraightRun) {
  test::TempDir dir;
  write_coarse_ramp(dir.path());
  test::write_text(dir / "straight.yaml", ramp_case("full.csv", 8));
  test::write_text(dir / "first.yaml", ramp_case("half.csv", 4));
  test::write_text(dir / "second.yaml", ramp_case("full.csv", 4, "restart: first-out/restart.hmr\n"));
  for (const char* name : {"straight", "first", "second"}) {
    const auto r = hotmesh(fmt::format("-q deform {}", shell_quote((dir / (std::string(name) + ".yaml")).string())));
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.output;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "first-out" / "restart.hmr"));
  const deform::Mesh straight = io::read_gmsh(dir / "straight-out" / "deformed.msh");
  const deform::Mesh restarted = io::read_gmsh(dir / "second-out" / "deformed.msh");
  double largest = 0.0;
  for (std::size_t n = 0; n < straight.node_count(); ++n) {
    largest = std::max(largest, distance(straight.points[n], restarted.points[n]));
  }
  EXPECT_LT(largest, 1e-5);
  const auto report = read_json(dir / "second-out" / "report.json");
  EXPECT_THAT(report["restarted_from"].get<std::string>(), HasSubstr("first-out/restart.hmr"));
  EXPECT_GT(report["sliding_nodes"].get<int>(), 0);
  EXPECT_LT(report["max_normal_slip"].get<double>(), 1e-12);
}

TEST(DeformCommand, RestartRefusesAnotherMeshOrChangedRoles) {
  test::TempDir dir;
  write_coarse_ramp(dir.path());
  test::write_text(dir / "first.yaml", ramp_case("half.csv", 2));
  ASSERT_EQ(hotmesh("-q deform " + shell_quote((dir / "first.yaml").string())).exit_code, 0);
  // Another role for the top wall.
  std::string changed = ramp_case("full.csv", 2, "restart: first-out/restart.hmr\n");
  changed.replace(changed.find("top: {role: sliding}"), 20, "top: {role: fixed}  ");
  test::write_text(dir / "roles.yaml", changed);
  const auto roles = hotmesh("deform " + shell_quote((dir / "roles.yaml").string()));
  EXPECT_EQ(roles.exit_code, 2);
  EXPECT_THAT(roles.output, HasSubstr("patches.top: it was sliding in the run being restarted"));
  // Another mesh.
  io::write_gmsh(dir / "other.msh", deform::structured_quads(deform::uniform_line(0, 2, 20), deform::uniform_line(0, 1, 12),
                                                            {"left", "right", "bottom", "top"}));
  std::string other = ramp_case("full.csv", 2, "restart: first-out/restart.hmr\n");
  other.replace(other.find("ramp.msh"), 8, "other.msh");
  test::write_text(dir / "other.yaml", other);
  const auto mesh = hotmesh("deform " + shell_quote((dir / "other.yaml").string()));
  EXPECT_EQ(mesh.exit_code, 2);
  EXPECT_THAT(mesh.output, HasSubstr("this restart file was written for another mesh"));
  // Not a restart file at all.
  test::write_text(dir / "junk.hmr", "hello");
  std::string junk = ramp_case("full.csv", 2, "restart: junk.hmr\n");
  test::write_text(dir / "junk.yaml", junk);
  const auto bad = hotmesh("deform " + shell_quote((dir / "junk.yaml").string()));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.output, HasSubstr("not a hotmesh restart file"));
  // Each was refused after its output folder was made: none is left behind, empty.
  for (const char* name : {"roles-out", "other-out", "junk-out"}) EXPECT_FALSE(std::filesystem::exists(dir / name)) << name;
}

// Issue 18, item 10: an output folder that cannot be written in was found only when the
// first checkpoint was saved, after increment 1.
TEST(DeformCommand, OutputFolderThatCannotBeWrittenIsRefusedBeforeAnyWork) {
  test::TempDir dir;
  write_coarse_ramp(dir.path());
  test::write_text(dir / "case.yaml", ramp_case("full.csv", 2));
  std::filesystem::path closed = dir / "closed";
  std::filesystem::create_directories(closed);
  std::filesystem::permissions(closed, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (::geteuid() == 0) closed = "/sys";  // root writes in any folder its permissions close
  const auto r = hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " + shell_quote(closed.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(closed.string() + ": cannot write in the output folder"));
  EXPECT_THAT(r.output, Not(HasSubstr("increment 1/2")));
  std::filesystem::permissions(dir / "closed", std::filesystem::perms::owner_all);
}

// Issue 18, item 10: a run killed before its first checkpoint rename left
// checkpoint.hmc.tmp-<pid>-0, and no later run removed it.
TEST(DeformCommand, ANewRunRemovesTheTemporariesOfAKilledOne) {
  test::TempDir dir;
  write_coarse_ramp(dir.path());
  test::write_text(dir / "case.yaml", ramp_case("full.csv", 2));
  std::filesystem::create_directories(dir / "case-out");
  // The process id of a run that has ended.
  const auto ended = test::run_command("sh -c 'echo $$'");
  const std::string leftover = "checkpoint.hmc.tmp-" + ended.output.substr(0, ended.output.find('\n')) + "-0";
  test::write_text(dir / "case-out" / leftover, "half a checkpoint");
  const auto r = hotmesh("-q deform " + shell_quote((dir / "case.yaml").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "case-out" / leftover));
}

}  // namespace
}  // namespace hotmesh::app
