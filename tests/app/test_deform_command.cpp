// Tests of `hotmesh deform`, the main job, end to end on the ramp sample: outputs and
// report, a motion that fails (last valid mesh kept, exit code 1), and bad input (exit code 2,
// nothing written).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <elf.h>
#include <sched.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <set>

#include <fmt/format.h>

#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/parallel/threads.hpp"
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
  const mesh::Mesh moved = io::read_gmsh(out / "deformed.msh");
  for (mesh::NodeId n : moved.find_patch("bottom")->nodes) {
    const double x = moved.points[static_cast<std::size_t>(n)].x;
    const double y = moved.points[static_cast<std::size_t>(n)].y;
    const double ramp = x <= 0.975 ? 0.0 : x >= 1.025 ? 0.5 : 0.5 * (x - 0.975) / 0.05;
    EXPECT_NEAR(y, ramp, 1e-9) << "x = " << x;
  }
  const auto q = mesh::summarize_quality(mesh::scaled_jacobians(moved.cells, moved.points));
  EXPECT_EQ(q.inverted_cells, 0u);

  // ... but its faces do not: no node lands on corner A (0.975, 0), and the edge between the
  // last node before it and the first after it cuts it (issue 20). The report names the corner.
  ASSERT_EQ(report["wall_deviations"].size(), 1u);
  const auto& wall = report["wall_deviations"][0];
  EXPECT_EQ(wall["patch"], "bottom");
  EXPECT_EQ(wall["role"], "prescribed");
  EXPECT_EQ(wall["stage"], 1.0);
  EXPECT_EQ(wall["edges"], 57);
  std::vector<geometry::Vec3> wall_nodes;
  for (mesh::NodeId n : moved.find_patch("bottom")->nodes) wall_nodes.push_back(moved.points[static_cast<std::size_t>(n)]);
  std::sort(wall_nodes.begin(), wall_nodes.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
  const auto after = std::find_if(wall_nodes.begin(), wall_nodes.end(), [](const auto& p) { return p.x > 0.975; });
  const geometry::Vec3 a = *(after - 1), b = *after, corner{0.975, 0.0, 0.0};
  const double cut = std::abs((b.x - a.x) * (corner.y - a.y) - (b.y - a.y) * (corner.x - a.x)) / distance(a, b);
  EXPECT_NEAR(wall["hausdorff"].get<double>(), cut, 1e-9);
  EXPECT_GT(cut, 0.02);
  EXPECT_EQ(wall["worst"], "shape_to_mesh");
  EXPECT_NEAR(wall["worst_point"][0].get<double>(), 0.975, 1e-9);
  EXPECT_NEAR(wall["worst_point"][1].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(wall["shape_to_mesh"]["distance"], wall["hausdorff"]);
  EXPECT_LT(wall["mesh_to_shape"]["distance"].get<double>(), cut);
  EXPECT_EQ(wall["hausdorff_relative"].get<double>(), wall["hausdorff"].get<double>() / report["length_scale"].get<double>());
}

/// A hybrid mesh (quads on the lower wall, triangles above) through the whole command with
/// each linear solver: the same motion, quality per cell type in the report, the cell types
/// kept in the deformed mesh.
TEST(DeformCommand, HybridMeshMovesWithEitherSolverAndReportsQualityPerCellType) {
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  const mesh::Mesh quads = mesh::structured_quads(mesh::uniform_line(0.0, 2.0, 21), mesh::stretched_line(0.0, 1.0, 12, 0.004),
                                                  {"left", "right", "bottom", "top"});
  std::vector<mesh::CellSplit> split(quads.cell_count(), mesh::CellSplit::triangles);
  std::fill(split.begin(), split.begin() + 21 * 3, mesh::CellSplit::keep);  // three rows of quads on the wall
  const mesh::Mesh hybrid = mesh::split_cells(quads, split);
  io::write_gmsh(dir / "ramp.msh", hybrid);
  std::vector<std::vector<geometry::Vec3>> results;
  for (const std::string linear : {"jacobi-pcg", "amg", "direct", "icc"}) {
    SCOPED_TRACE(linear);
    std::string yaml = test::ramp_case("full.csv", 4);
    yaml.replace(yaml.find("solver: {"), 9, "solver: {linear: " + linear + ", ");
    test::write_text(dir / "case.yaml", yaml);
    const auto out = dir / ("out-" + linear);
    const auto r = hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " + shell_quote(out.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto report = read_json(out / "report.json");
    const auto& by_type = report["quality"]["by_type"];
    ASSERT_EQ(by_type.size(), 2u) << by_type;
    EXPECT_EQ(by_type["quad4"]["cells"], 63);
    EXPECT_EQ(by_type["tri3"]["cells"], 2 * (21 * 12 - 63));
    EXPECT_EQ(by_type["tri3"]["inverted_cells"], 0);
    const double worst = std::min(by_type["quad4"]["min_scaled_jacobian"].get<double>(),
                                  by_type["tri3"]["min_scaled_jacobian"].get<double>());
    EXPECT_EQ(report["quality"]["min_scaled_jacobian"].get<double>(), worst);
    const mesh::Mesh moved = io::read_gmsh(out / "deformed.msh");
    EXPECT_EQ(moved.cells.types().size(), hybrid.cells.types().size());
    EXPECT_TRUE(std::equal(moved.cells.types().begin(), moved.cells.types().end(), hybrid.cells.types().begin()));
    for (mesh::NodeId n : moved.find_patch("bottom")->nodes) {
      const geometry::Vec3& p = moved.points[static_cast<std::size_t>(n)];
      const double ramp = p.x <= 0.975 ? 0.0 : p.x >= 1.025 ? 0.5 : 0.5 * (p.x - 0.975) / 0.05;
      EXPECT_NEAR(p.y, ramp, 1e-6) << "x = " << p.x;
    }
    results.push_back(moved.points);
  }
  for (std::size_t k = 1; k < results.size(); ++k) {
    double largest = 0.0;
    for (std::size_t n = 0; n < results[0].size(); ++n) largest = std::max(largest, distance(results[0][n], results[k][n]));
    EXPECT_LT(largest, 1e-4) << k;  // each solves every Newton step to 1e-6
  }
}

/// `linear: auto`, a case file's default, picks icc for a small 2D mesh, with a sliding wall or
/// without (deform::choose_linear_solver); the log and report.json say which and why.
/// The ramp samples leave the choice to it; the runs are on the coarse ramp channel, since the
/// choice depends on the dimension, the walls and the size only.
TEST(DeformCommand, LinearAutoPicksTheSolverAndSaysWhy) {
  for (const char* sample : {"ramp2d-sliding.yaml", "ramp2d.yaml"}) {
    EXPECT_EQ(test::read_text(kSample / sample).find("linear:"), std::string::npos) << sample;  // the default
  }
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  test::write_text(dir / "sliding.yaml", test::ramp_case("full.csv", 2));
  test::write_text(dir / "prescribed.yaml", test::prescribed_ramp_case("full.csv", "increments: 2"));
  const std::array<std::array<std::string, 3>, 2> runs{{{"sliding", "icc", "auto: a 2D mesh of at most 40 000 cells"},
                                                       {"prescribed", "icc", "auto: a 2D mesh of at most 40 000 cells"}}};
  for (const auto& [name, linear, why] : runs) {
    SCOPED_TRACE(name);
    const auto r = hotmesh("deform " + shell_quote((dir / (name + ".yaml")).string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("linear solver " + linear));
    EXPECT_THAT(r.output, HasSubstr(why));
    const auto report = read_json(dir / (name + "-out") / "report.json");
    EXPECT_EQ(report["solver"]["linear"], linear);
    EXPECT_EQ(report["solver"]["linear_chosen_by"], why);
  }
}

/// The threads a run takes and why, in one log line and in report.json: hotmesh's own choice
/// (one thread below the size where threads pay), the user's count from each place it comes
/// from, as given, and how waiting threads wait: passively unless the user says otherwise,
/// which libgomp itself reports (GOMP_SPINCOUNT 0) (issue 52). Nothing timed.
TEST(DeformCommand, SaysOnHowManyThreadsItRunsAndWhy) {
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  std::string yaml = test::ramp_case("full.csv", 2);
  test::write_text(dir / "case.yaml", yaml);
  yaml.replace(yaml.find("solver: {"), 9, "solver: {threads: 1, ");
  test::write_text(dir / "threads.yaml", yaml);
  // hotmesh's own reason: the mesh's size, unless the process may use one core only
  const std::string small = parallel::machine_cores() == 1
                                ? std::string("the process may use 1 core")
                                : fmt::format("a mesh of 286 nodes: threads pay from {}", parallel::kThreadsPayNodes2d);
  struct Run {
    std::string environment, case_name, options, line, chosen_by;
    int threads;
  };
  const std::vector<Run> runs{
      {"", "case", "", "on 1 thread (" + small + ")", "hotmesh", 1},
      {"-u OMP_WAIT_POLICY", "case", "--threads 2", "on 2 threads (--threads 2); waiting threads: ", "the user", 2},
      {"OMP_WAIT_POLICY=active", "case", "--threads 2",
       "on 2 threads (--threads 2); waiting threads: OMP_WAIT_POLICY=active (set by the user)", "the user", 2},
      {"OMP_NUM_THREADS=2", "case", "", "on 2 threads (OMP_NUM_THREADS=2)", "the user", 2},
      {"", "threads", "", "on 1 thread (solver.threads: 1)", "the user", 1},
      {"", "threads", "--threads 0", "on 1 thread (" + small + ")", "hotmesh", 1}};
  for (const Run& run : runs) {
    SCOPED_TRACE(run.environment + " " + run.case_name + " " + run.options);
    const auto out = dir / "out";
    const auto r = test::run_command(fmt::format("env -u OMP_NUM_THREADS {} {} deform {} -o {} --force {}", run.environment,
                                                 HOTMESH_EXE, shell_quote((dir / (run.case_name + ".yaml")).string()),
                                                 shell_quote(out.string()), run.options));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr(run.line));
    const auto report = read_json(out / "report.json");
    const auto& threads = report["threads"];
    EXPECT_EQ(threads["count"], run.threads);
    EXPECT_EQ(threads["chosen_by"], run.chosen_by);
    EXPECT_TRUE(threads["other_load"].is_null());  // the size or the user decided: the load was not looked at
    EXPECT_GE(threads["cores"].get<int>(), 1);
  }
}

/// The dynamic loader named in the program headers of the executable at `path` (PT_INTERP),
/// empty if it names none.
std::string interpreter_of(const std::filesystem::path& path) {
  const std::string elf = test::read_text(path);
  Elf64_Ehdr header{};
  if (elf.size() < sizeof header) return {};
  std::memcpy(&header, elf.data(), sizeof header);
  for (std::size_t i = 0; i < header.e_phnum; ++i) {
    Elf64_Phdr segment{};
    const std::size_t at = header.e_phoff + i * header.e_phentsize;
    if (at + sizeof segment > elf.size()) return {};
    std::memcpy(&segment, elf.data() + at, sizeof segment);
    if (segment.p_type == PT_INTERP && segment.p_offset + segment.p_filesz <= elf.size()) {
      return std::string(elf.data() + segment.p_offset);  // NUL-terminated within the segment
    }
  }
  return {};
}

/// Whether this process may run on one core only (its affinity).
bool on_one_core() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  return sched_getaffinity(0, sizeof allowed, &allowed) == 0 && CPU_COUNT(&allowed) == 1;
}

/// Waiting threads sleep unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT, as libgomp
/// itself says it read them (OMP_DISPLAY_ENV), and as the log and report.json say: the program
/// starts itself again once with OMP_WAIT_POLICY=passive before libgomp starts, so libgomp
/// starts once, with the user's arguments (names with spaces) and environment (OMP_STACKSIZE)
/// passed through. Not where it would gain nothing (one thread; one core, where libgomp hardly
/// spins), nor run by the dynamic loader, where it cannot; each says why (issue 52). Nothing
/// timed.
TEST(DeformCommand, WaitsPassivelyUnlessTheUserSetAPolicy) {
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  test::write_text(dir / "a case.yaml", test::ramp_case("full.csv", 2));
  const std::string hotmesh_exe = shell_quote(HOTMESH_EXE);
  const std::string loader = interpreter_of(HOTMESH_EXE);
  const std::string not_passive = "libgomp's default, a waiting thread spins a while (hotmesh did not make it passive: ";
  const std::string one_core = not_passive + "the process may use 1 core, where libgomp spins at most 100 turns)";
  struct Run {
    std::string environment, program, options, policy, spin_count, wait_policy;
  };
  std::vector<Run> runs{
      {"", hotmesh_exe, "--threads 2", "PASSIVE", "0", "passive (hotmesh's default)"},
      {"OMP_WAIT_POLICY=active", hotmesh_exe, "--threads 2", "ACTIVE", "30000000000",
       "OMP_WAIT_POLICY=active (set by the user)"},
      {"GOMP_SPINCOUNT=1000", hotmesh_exe, "--threads 2", "", "1000", "GOMP_SPINCOUNT=1000 (set by the user)"},
      {"", hotmesh_exe, "--threads 1", "", "300000", not_passive + "one thread (--threads 1): no thread waits)"},
      {"OMP_NUM_THREADS=1", hotmesh_exe, "", "", "300000", not_passive + "one thread (OMP_NUM_THREADS=1): no thread waits)"},
      {"", "taskset -c 0 " + hotmesh_exe, "--threads 2", "", "300000", one_core}};
  if (on_one_core()) runs.front() = {"", hotmesh_exe, "--threads 2", "", "300000", one_core};
  if (!loader.empty()) {
    runs.push_back({"", shell_quote(loader) + " " + hotmesh_exe, "--threads 2", "", "300000",
                    on_one_core() ? one_core : not_passive + "started by the dynamic loader)"});
  }
  for (const Run& run : runs) {
    SCOPED_TRACE(run.environment + " " + run.program + " " + run.options);
    const auto out = dir / "the out";
    const auto r = test::run_command(fmt::format(
        "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u HOTMESH_DEFAULT_WAIT_POLICY -u OMP_NUM_THREADS "
        "OMP_DISPLAY_ENV=VERBOSE OMP_STACKSIZE=3M {} {} deform {} -o {} --force {}",
        run.environment, run.program, shell_quote((dir / "a case.yaml").string()), shell_quote(out.string()),
        run.options));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // libgomp started once, and read the environment as passed through.
    std::size_t displays = 0;
    for (std::size_t at = 0; (at = r.output.find("OPENMP DISPLAY ENVIRONMENT BEGIN", at)) != std::string::npos; ++at) {
      ++displays;
    }
    EXPECT_EQ(displays, 1u);
    EXPECT_THAT(r.output, HasSubstr("OMP_STACKSIZE = '3145728'"));
    if (!run.policy.empty()) {
      EXPECT_THAT(r.output, HasSubstr(fmt::format("OMP_WAIT_POLICY = '{}'", run.policy)));
    }
    EXPECT_THAT(r.output, HasSubstr(fmt::format("GOMP_SPINCOUNT = '{}'", run.spin_count)));
    const auto report = read_json(out / "report.json");
    EXPECT_EQ(report["threads"]["wait_policy"], run.wait_policy);
    if (report["threads"]["count"] == 2) {  // the log says how threads wait where some may
      EXPECT_THAT(r.output, HasSubstr("on 2 threads (--threads 2); waiting threads: " + run.wait_policy));
    }
  }
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
  EXPECT_THAT(r.output, HasSubstr("linear solver amg with gamg (the case file)"));
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
  // The first solve of every increment stops on the Newton norm ||D^-1 r||, at pcg_tolerance
  // or, after a predicted start, as far as the Newton tolerance needs (at most 0.1); a later
  // solve in that norm (after a step without sufficient decrease) at pcg_tolerance; the loose
  // ones stop on ||r||.
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
      if (norms[i] == "newton" && i == 0) {
        EXPECT_GE(eta[i].get<double>(), 1e-3) << inc["increment"];
        EXPECT_LE(eta[i].get<double>(), 0.1) << inc["increment"];
        if (inc["increment"] == 1) {
          EXPECT_EQ(eta[i].get<double>(), 1e-3);  // nothing to predict from
        }
      } else if (norms[i] == "newton") {
        EXPECT_EQ(eta[i].get<double>(), 1e-3) << inc["increment"] << " solve " << i;
      } else {
        residual_norm_solves += norms[i] == "residual";
      }
    }
  }
  EXPECT_GT(tolerances.size(), 2u);
  EXPECT_GE(*tolerances.begin(), 1e-3);
  EXPECT_GT(residual_norm_solves, 0u);
}

TEST(DeformCommand, FailedMotionKeepsLastValidMeshAndMarksFailedCells) {
  // The coarse ramp channel's floor pushed through its top wall: cannot be done.
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  test::write_text(dir / "case.yaml", test::prescribed_ramp_case("steep.csv", "increments: 2, max_increment_splits: 1"));
  test::write_text(dir / "steep.csv", "x,y,dx,dy\n0,0,0,0\n0.9,0,0,0\n1.1,0,0,1.4\n2,0,0,1.4\n");
  const auto r = hotmesh("deform " + shell_quote((dir / "case.yaml").string()));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("increment 1 of 2 failed"));
  const auto out = dir / "case-out";
  EXPECT_TRUE(std::filesystem::exists(out / "failed.vtu"));
  EXPECT_TRUE(std::filesystem::exists(out / "failed.png"));
  const auto report = read_json(out / "report.json");
  EXPECT_EQ(report["status"], "failed");
  EXPECT_LT(report["stage_reached"].get<double>(), 1.0);
  EXPECT_THAT(report["message"].get<std::string>(), HasSubstr("cell"));
  const mesh::Mesh kept = io::read_gmsh(out / "deformed.msh");
  EXPECT_EQ(mesh::summarize_quality(mesh::scaled_jacobians(kept.cells, kept.points)).inverted_cells, 0u);
  EXPECT_THAT(test::read_text(out / "failed.vtu"), HasSubstr("Name=\"inverted\""));
  // Newton fails long before a cell inverts here, and the messages say so (issue 45 item 4).
  EXPECT_EQ(report["failure"]["kind"], "newton_stalled");
  EXPECT_THAT(r.output, HasSubstr("failed.vtu holds the failed attempt (Newton did not converge; no cell inverted"));
  EXPECT_THAT(r.output, HasSubstr("Try more increments"));
}

TEST(DeformCommand, HowFarAWallWasFromItsUndeformedShapeIsReported) {
  // Issue 45 item 2: a table whose floor lies 1e-4 above the mesh's (an FEM wall that does not
  // quite match the CFD one): the sliding floor's nodes are put on it, and the log and
  // report.json say by how much they moved for it, besides the deflection.
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  test::write_text(dir / "raised.csv", "x,y,dx,dy\n0,0.0001,0,0\n0.975,0.0001,0,0\n1.025,0.0001,0,0.1\n2,0.0001,0,0.1\n");
  test::write_text(dir / "case.yaml", test::ramp_case("raised.csv", 2));
  const auto r = hotmesh("deform " + shell_quote((dir / "case.yaml").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("patch bottom: its nodes lay within 0.0001 of its undeformed wall before the motion "
                                  "put them on it"));
  const auto report = read_json(dir / "case-out" / "report.json");
  bool found = false;
  for (const auto& patch : report["patches"]) {
    if (patch["name"] != "bottom") continue;
    found = true;
    EXPECT_NEAR(patch["undeformed_gap"].get<double>(), 1e-4, 1e-12);
    EXPECT_GT(patch["undeformed_gap_node"].get<int>(), 0);
  }
  EXPECT_TRUE(found);
}

TEST(DeformCommand, AFailedNewtonCycleSaysWhereAndThatNoCellInverted) {
  // Issue 45 item 4: one Newton step allowed, a tolerance it cannot reach, no splits: the run
  // fails with every cell valid. The message names the nodes where the residual is largest,
  // with their places and roles, and what to try; failed.vtu and failed.png say that Newton did
  // not converge and no cell inverted, and failed.vtu holds the residual.
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  test::write_text(dir / "case.yaml",
                   "mesh: ramp.msh\nsolver: {increments: 4, max_newton_iterations: 1, newton_tolerance: 1.0e-12, "
                   "max_increment_splits: 0}\npatches:\n  left: {role: fixed}\n  right: {role: slip}\n"
                   "  top: {role: sliding}\n  bottom: {role: sliding, deflection: {file: full.csv}}\n");
  const auto r = hotmesh("deform " + shell_quote((dir / "case.yaml").string()));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("did not converge in 1 iterations"));
  EXPECT_THAT(r.output, HasSubstr("no cell inverted, the worst at the failed stage is cell"));
  EXPECT_THAT(r.output, HasSubstr("the residual is largest at node"));
  EXPECT_THAT(r.output, ::testing::ContainsRegex("node [0-9]+ at \\([-0-9.e]+, [-0-9.e]+, 0\\), (interior|sliding on 'bottom')"));
  EXPECT_THAT(r.output, HasSubstr("failed.vtu holds the failed attempt (Newton did not converge; no cell inverted; its "
                                  "point data newton_residual shows where)"));
  const auto out = dir / "case-out";
  const auto report = read_json(out / "report.json");
  EXPECT_EQ(report["failure"]["kind"], "newton_stalled");
  ASSERT_FALSE(report["failure"]["largest_residuals"].empty());
  double previous = std::numeric_limits<double>::infinity();
  for (const auto& node : report["failure"]["largest_residuals"]) {  // largest first
    EXPECT_LE(node["residual"].get<double>(), previous);
    EXPECT_GT(node["residual"].get<double>(), 0.0);
    previous = node["residual"].get<double>();
  }
  const std::string vtu = test::read_text(out / "failed.vtu");
  EXPECT_THAT(vtu, HasSubstr("Name=\"newton_residual\""));
  EXPECT_TRUE(std::filesystem::exists(out / "failed.png"));
  // The bottom wall's nodes lay on its undeformed wall (the table's flat floor) before the motion.
  for (const auto& patch : report["patches"]) {
    if (patch["name"] == "bottom") {
      EXPECT_LT(patch["undeformed_gap"].get<double>(), 1e-12);
    }
  }
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

// Issue 18, item 7: a FIFO as the case, mesh, table or CAD file blocked hotmesh forever.
TEST(DeformCommand, NamedPipesAsInputsAreRefusedWithoutWaiting) {
  const std::string yaml =
      "mesh: ramp2d.msh\npatches:\n  left: {role: fixed}\n  right: {role: slip}\n  top: {role: sliding}\n"
      "  bottom: {role: sliding, deflection: {file: ramp.csv}}\n";
  for (const char* name : {"case.yaml", "ramp2d.msh", "ramp.csv"}) {
    RampCase ramp(yaml);
    std::filesystem::remove(ramp.dir / name);
    ASSERT_EQ(::mkfifo((ramp.dir / name).c_str(), 0600), 0);
    // `timeout` ends the test, not hotmesh's bug, if a read blocks again.
    const auto r = test::run_command("timeout 60 " + std::string(HOTMESH_EXE) + " deform " + ramp.case_file());
    EXPECT_EQ(r.exit_code, 2) << name << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("is a named pipe (FIFO), not a regular file")) << name;
  }
  RampCase ramp(yaml + "cad: part.step\n");
  ASSERT_EQ(::mkfifo((ramp.dir / "part.step").c_str(), 0600), 0);
  const auto r = test::run_command("timeout 60 " + std::string(HOTMESH_EXE) + " deform " + ramp.case_file());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("case.yaml:7: cad: " + (ramp.dir / "part.step").string() + " is a named pipe"));
}

// Issue 18, item 9: a damaged `cad:` file that no patch uses was accepted, one that a patch
// used was blamed on the patch's table; a NUL byte cut the message short and a 2 MB value was
// echoed whole.
TEST(DeformCommand, EveryNamedFileIsCheckedAndMessagesStayReadable) {
  const std::string yaml =
      "mesh: ramp2d.msh\npatches:\n  left: {role: fixed}\n  right: {role: slip}\n  top: {role: sliding}\n"
      "  bottom: {role: sliding, deflection: {file: ramp.csv}}\n";
  RampCase ramp(yaml + "cad: part.step\n");
  const std::string step = test::read_text(std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples" / "stator_well" /
                                           "stator_well.step");
  test::write_text(ramp.dir / "part.step", step.substr(0, step.size() / 3));  // truncated
  const auto truncated = hotmesh("deform " + ramp.case_file());
  EXPECT_EQ(truncated.exit_code, 2) << truncated.output;
  EXPECT_THAT(truncated.output, HasSubstr((ramp.dir / "part.step").string() + ": cannot be read as STEP"));
  EXPECT_THAT(truncated.output, Not(HasSubstr("ramp.csv")));
  EXPECT_THAT(truncated.output, Not(HasSubstr("mesh ")));  // refused before the mesh is read
  EXPECT_FALSE(std::filesystem::exists(ramp.dir / "case-out"));

  test::write_text(ramp.dir / "case.yaml", yaml);
  constexpr char kNul[] = "x,y,d\0x,dy\n0,0,0,0\n";
  test::write_text(ramp.dir / "ramp.csv", std::string(kNul, sizeof kNul - 1));
  const auto nul = hotmesh("deform " + ramp.case_file());
  EXPECT_EQ(nul.exit_code, 2);
  EXPECT_THAT(nul.output, HasSubstr("ramp.csv:1: unknown column 'd\\x00x'; expected x,y,dx,dy"));

  test::write_text(ramp.dir / "case.yaml", "mesh: " + std::string(2'000'000, 'm') + ".msh\npatches: {left: {role: fixed}}\n");
  const auto wide = hotmesh("deform " + ramp.case_file());
  EXPECT_EQ(wide.exit_code, 2);
  EXPECT_THAT(wide.output, HasSubstr("more bytes)"));
  EXPECT_LT(wide.output.size(), 20'000u);
}

TEST(DeformCommand, HugeIncrementCountIsRefusedAtOnce) {
  // Issue 18: `increments: 1000000000` took more than 13 GB before increment 1. Refused as the
  // case is read, in a process limited to 1 GB of address space (not under AddressSanitizer,
  // which reserves terabytes).
  RampCase ramp(
      "mesh: ramp2d.msh\nsolver: {increments: 1000000000}\n"
      "patches:\n  left: {role: fixed}\n  right: {role: slip}\n  top: {role: fixed}\n"
      "  bottom: {role: prescribed, deflection: {file: ramp.csv}}\n");
  const std::string limit = test::under_sanitizers() ? "" : "ulimit -v 1000000 && ";
  const auto r = test::run_command(limit + HOTMESH_EXE + " deform " + ramp.case_file());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("case.yaml:2: solver.increments: must be at most 10000, got 1000000000: the "
                                  "paper's cases take 16"));
  EXPECT_FALSE(std::filesystem::exists(ramp.dir / "case-out"));
}

TEST(DeformCommand, RefusesOutputFolderHoldingInputsUnlessForced) {
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  test::write_text(dir / "case.yaml", test::ramp_case("full.csv", 2));
  const std::string case_file = shell_quote((dir / "case.yaml").string());
  const std::string before = test::read_text(dir / "ramp.msh");
  const auto refused = hotmesh("deform " + case_file + " -o " + shell_quote(dir.path().string()));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.output, HasSubstr("--force"));
  const auto forced = hotmesh("-q deform --force " + case_file + " -o " + shell_quote(dir.path().string()));
  EXPECT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_EQ(test::read_text(dir / "ramp.msh"), before);  // inputs untouched
  EXPECT_TRUE(std::filesystem::exists(dir / "deformed.msh"));
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
  const mesh::Mesh straight = io::read_gmsh(dir / "straight-out" / "deformed.msh");
  const mesh::Mesh restarted = io::read_gmsh(dir / "second-out" / "deformed.msh");
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

/// The largest number of `values` (a JSON array), 0 if empty.
double largest_of(const nlohmann::json& values) {
  double largest = 0.0;
  for (const auto& v : values) largest = std::max(largest, v.get<double>());
  return largest;
}

TEST(DeformCommand, ReportGivesEveryLengthAbsoluteAndRelativeAndRealMaxima) {
  // Issue 18: max_sliding_projection_distance was the last Newton step's, and relative, while
  // increments[].max_projection_distance was absolute; periodic_max_mismatch was relative,
  // max_normal_slip absolute; a rejected attempt's unchecked quality read 0. The coarse
  // sliding ramp in one increment of at most 6 Newton steps: attempts that do not converge are
  // rejected and split, their pieces accepted.
  test::TempDir dir;
  write_coarse_ramp(dir.path());
  std::string yaml = ramp_case("full.csv", 1);
  yaml.replace(yaml.find("newton_tolerance: 1.0e-6"), 24, "newton_tolerance: 1.0e-4, max_newton_iterations: 6");
  test::write_text(dir / "case.yaml", yaml);
  const auto r = hotmesh("-q deform " + shell_quote((dir / "case.yaml").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto report = read_json(dir / "case-out" / "report.json");
  const double scale = report["length_scale"].get<double>();
  EXPECT_DOUBLE_EQ(scale, std::sqrt(5.0));  // the diagonal of the undeformed channel, 2 x 1
  const auto expect_relative = [scale](const nlohmann::json& object, const std::string& key) {
    ASSERT_TRUE(object.contains(key) && object.contains(key + "_relative")) << key;
    EXPECT_EQ(object[key + "_relative"].get<double>(), object[key].get<double>() / scale) << key;
  };
  for (const char* key : {"max_projection_distance", "final_projection_distance", "max_normal_slip", "max_periodic_mismatch"}) {
    expect_relative(report, key);
  }
  ASSERT_EQ(report["deflections"].size(), 1u);
  expect_relative(report["deflections"][0], "max_node_distance_to_cad");
  expect_relative(report["deflections"][0], "max_node_residual");

  double largest = 0.0, last = 0.0, slip = 0.0, rejected_largest = 0.0;
  std::size_t rejected = 0;
  for (const auto& attempt : report["increments"]) {
    expect_relative(attempt, "max_normal_slip");
    const auto& steps = attempt["max_projection_distance"];
    ASSERT_EQ(steps.size(), attempt["newton_iterations"].get<std::size_t>());
    ASSERT_EQ(attempt["max_projection_distance_relative"].size(), steps.size());
    for (std::size_t i = 0; i < steps.size(); ++i) {
      EXPECT_EQ(attempt["max_projection_distance_relative"][i].get<double>(), steps[i].get<double>() / scale);
    }
    if (!attempt["converged"].get<bool>()) {  // quality never checked: unknown, not 0
      ++rejected;
      EXPECT_TRUE(attempt["min_scaled_jacobian"].is_null()) << attempt["stage"];
      EXPECT_TRUE(attempt["inverted_cells"].is_null()) << attempt["stage"];
      rejected_largest = std::max(rejected_largest, largest_of(steps));
      continue;
    }
    EXPECT_GT(attempt["min_scaled_jacobian"].get<double>(), 0.0);
    EXPECT_EQ(attempt["inverted_cells"], 0);
    largest = std::max(largest, largest_of(steps));
    last = steps.back().get<double>();
    slip = std::max(slip, attempt["max_normal_slip"].get<double>());
  }
  ASSERT_GT(rejected, 0u) << "the test needs attempts that do not converge";
  // The maxima run over every Newton step of the accepted attempts, the rejected ones left out.
  EXPECT_EQ(report["max_projection_distance"].get<double>(), largest);
  EXPECT_GT(largest, last);  // not the last step's
  EXPECT_GT(rejected_largest, largest);  // the rejected attempts' moves were undone
  EXPECT_EQ(report["final_projection_distance"].get<double>(), last);
  EXPECT_EQ(report["max_normal_slip"].get<double>(), slip);
  EXPECT_EQ(report["max_periodic_mismatch"], 0.0);  // no periodic pairs
  // The deprecated keys keep their old meaning for one version (docs/report-json.md).
  EXPECT_EQ(report["max_sliding_projection_distance"], report["final_projection_distance_relative"]);
  EXPECT_EQ(report["periodic_max_mismatch"], report["max_periodic_mismatch_relative"]);
  EXPECT_GT(report["min_scaled_jacobian"].get<double>(), 0.0);  // of the final mesh
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
  io::write_gmsh(dir / "other.msh", mesh::structured_quads(mesh::uniform_line(0, 2, 20), mesh::uniform_line(0, 1, 12),
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
