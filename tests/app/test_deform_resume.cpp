// Tests of long runs of `hotmesh deform`: a run killed after an increment (with SIGKILL, by the
// test library right after a checkpoint, faults.hpp, and from outside at a moment the run does
// not choose) resumes with --resume and writes the very outputs of an uninterrupted run (with
// either linear solver), a restarted run's too; a resume with a changed case or table, or
// without a checkpoint, is refused; a fresh run does not destroy a checkpoint; running out of
// memory (an allocation the test library fails) exits with code 4 naming the phase and keeps
// the checkpoint; progress lines per Newton step.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "deform_cases.hpp"
#include "faults.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::Not;
using test::expect_same_outputs;
using test::hotmesh;
using test::read_json;
using test::shell_quote;

/// The exit code /bin/sh reports for a command killed by SIGKILL.
constexpr int kKilled = 128 + SIGKILL;

/// The test library kills the run with SIGKILL right after its checkpoint of `increments` (the
/// runs here split no increment, so that is the one with `increments` done).
test::Faults killed_after(int increments) { return {.kill_after_checkpoint = increments}; }

/// The coarse sliding ramp (both walls sliding) in a temporary folder, run in 6 increments.
struct SlidingRamp {
  test::TempDir dir;
  SlidingRamp() {
    test::write_coarse_ramp(dir.path());
    test::write_text(dir / "case.yaml", test::ramp_case("full.csv", 6));
  }
  std::string deform(const std::string& out, const std::string& options = "") const {
    return fmt::format("deform {} -o {} {}", shell_quote((dir / "case.yaml").string()), shell_quote((dir / out).string()),
                       options);
  }
};

TEST(DeformResume, RunStoppedAfterAnIncrementResumesToTheSameOutputs) {
  SlidingRamp ramp;
  ASSERT_EQ(hotmesh("-q " + ramp.deform("straight")).exit_code, 0);
  const auto killed = hotmesh(ramp.deform("out"), killed_after(2));
  EXPECT_EQ(killed.exit_code, kKilled) << "not killed by SIGKILL: " << killed.output;
  EXPECT_THAT(killed.output, HasSubstr("increment 2/6"));
  EXPECT_THAT(killed.output, Not(HasSubstr("increment 3/6")));
  EXPECT_FALSE(std::filesystem::exists(ramp.dir / "out" / "deformed.msh"));
  const io::CheckpointInfo info = io::read_checkpoint_info(ramp.dir / "out" / io::kCheckpointName);
  EXPECT_EQ(info.finished_increments, 2);
  EXPECT_EQ(info.increments, 6);

  const auto resumed = hotmesh(ramp.deform("out", "--resume"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_THAT(resumed.output, HasSubstr("2 of 6 increments done"));
  EXPECT_THAT(resumed.output, Not(HasSubstr("increment 2/6")));  // not done again
  EXPECT_THAT(resumed.output, HasSubstr("increment 3/6"));
  expect_same_outputs(ramp.dir / "straight", ramp.dir / "out");
  const auto report = read_json(ramp.dir / "out" / "report.json");
  EXPECT_EQ(report["resumed_from"]["finished_increments"], 2);
  EXPECT_EQ(report["checkpoints"]["written"], 4);  // increments 3 to 6
}

TEST(DeformResume, CheckpointOfFormatOneResumesToAConvergedMeshOfItsOwn) {
  // A checkpoint as hotmesh wrote it before issue 18 (format 1: every step left listed, the
  // run's maxima in the header) still resumes. It lacks the mesh at the start of the last
  // increment (format 4), so the resumed run predicts its first increment from the undeformed
  // mesh: other Newton iterates, and a converged mesh of its own (as the adaptive amg's resume).
  SlidingRamp ramp;
  ASSERT_EQ(hotmesh("-q " + ramp.deform("straight")).exit_code, 0);
  ASSERT_EQ(hotmesh(ramp.deform("out"), killed_after(2)).exit_code, kKilled);
  test::rewrite_as_checkpoint_format_1(ramp.dir / "out" / io::kCheckpointName);
  ASSERT_THAT(test::read_text(ramp.dir / "out" / io::kCheckpointName), HasSubstr("\"remaining\":[[3,0.3333"));
  const auto resumed = hotmesh(ramp.deform("out", "--resume"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_THAT(resumed.output, HasSubstr("2 of 6 increments done"));
  const auto straight = read_json(ramp.dir / "straight" / "report.json"), out = read_json(ramp.dir / "out" / "report.json");
  ASSERT_EQ(out["increments"].size(), straight["increments"].size());
  EXPECT_EQ(out["status"], "success");
  EXPECT_EQ(out["inverted_cells"], 0);
  EXPECT_EQ(out["increments"][1]["residuals"], straight["increments"][1]["residuals"]);  // before the kill
  EXPECT_NE(out["increments"][2]["residuals"], straight["increments"][2]["residuals"]);  // predicted otherwise
  EXPECT_NEAR(out["min_scaled_jacobian"].get<double>(), straight["min_scaled_jacobian"].get<double>(), 0.02);
}

TEST(DeformResume, CheckpointAfterTheFirstIncrementDoesNotGrowWithTheIncrementCount) {
  // Issue 18: the checkpoint listed every increment left (31 bytes each), rewritten after each.
  SlidingRamp ramp;
  test::write_text(ramp.dir / "many.yaml", test::ramp_case("full.csv", 10000));
  ASSERT_EQ(hotmesh(ramp.deform("few"), killed_after(1)).exit_code, kKilled);
  const std::string many = shell_quote((ramp.dir / "many.yaml").string());
  ASSERT_EQ(hotmesh("deform " + many + " -o " + shell_quote((ramp.dir / "many").string()), killed_after(1)).exit_code,
            kKilled);
  // Both hold the same state but for N and the first increment's record (its Newton steps):
  // without that record, the same size to a few digits, where 9994 more increments listed
  // took 300 kB.
  const auto bytes_but_record = [&](const char* folder) {
    const auto path = ramp.dir / folder / io::kCheckpointName;
    const auto parts = test::checkpoint_parts(path);
    EXPECT_EQ(parts.header["records"].size(), 1u);
    EXPECT_TRUE(parts.header["split_pieces"].empty());
    return static_cast<double>(std::filesystem::file_size(path) - parts.header["records"].dump().size());
  };
  EXPECT_NEAR(bytes_but_record("many"), bytes_but_record("few"), 100.0);
}

/// The ramp's case in 6 increments with `linear: amg`, Eisenstat-Walker forcing and the given
/// `amg_reuse` (and without the walls' features if `features` is false), run into `straight`
/// and into `out`, that one killed after its third increment and resumed (what this returns).
auto amg_run_killed_and_resumed(const SlidingRamp& ramp, const std::string& reuse, bool features = true) {
  std::string text = test::ramp_case("full.csv", 6);
  const std::string solver = "pcg_tolerance: 1.0e-6}";
  text.replace(text.find(solver), solver.size(),
               "pcg_tolerance: 1.0e-6, linear: amg, forcing: eisenstat-walker, amg_reuse: " + reuse + "}");
  const std::string sliding = "role: sliding";
  for (auto at = text.find(sliding); !features && at != std::string::npos; at = text.find(sliding, at + 1)) {
    text.insert(at + sliding.size(), ", features: off");
  }
  test::write_text(ramp.dir / "case.yaml", text);
  EXPECT_EQ(hotmesh("-q " + ramp.deform("straight")).exit_code, 0);
  EXPECT_EQ(hotmesh(ramp.deform("out"), killed_after(3)).exit_code, kKilled);
  return hotmesh(ramp.deform("out", "--resume"));
}

TEST(DeformResume, AmgRunStoppedAfterAnIncrementResumesToTheSameOutputs) {
  // The resumed process builds its first matrix and multigrid hierarchy anew; the uninterrupted
  // one reuses its matrix and had built hierarchies before. With each increment's hierarchy
  // built anew both must give the same bits: the first assembly adds the values as the later
  // ones do, and every increment's hierarchy comes from a new KSP (PCGAMG carries state from
  // one set-up to the next).
  const SlidingRamp ramp;
  const auto resumed = amg_run_killed_and_resumed(ramp, "preconditioner");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_THAT(resumed.output, HasSubstr("3 of 6 increments done"));
  expect_same_outputs(ramp.dir / "straight", ramp.dir / "out");
}

TEST(DeformResume, AmgRunKeepingItsHierarchyAcrossIncrementsResumesToAConvergedMeshOfItsOwn) {
  // `amg_reuse: adaptive` (auto's choice from 100 000 cells) keeps a hierarchy built increments
  // before; the resumed process cannot have it and builds one at its first increment, so its
  // CG iterations differ and it ends on a converged mesh of its own, not on the uninterrupted
  // run's bits. On this ramp, whose sliding walls are flat, the two meshes are up to 1.5e-2 of
  // the domain apart (measured, without features; 2e-3 with them): Newton's tolerance (1e-6
  // of the residual) holds the sliding nodes' tangential places only loosely. So the test asks
  // for an accepted run of the same increments and quality.
  const SlidingRamp ramp;
  const auto resumed = amg_run_killed_and_resumed(ramp, "adaptive");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const auto straight = read_json(ramp.dir / "straight" / "report.json"), out = read_json(ramp.dir / "out" / "report.json");
  EXPECT_EQ(straight["solver"]["amg_reuse"], "adaptive");
  ASSERT_EQ(out["increments"].size(), straight["increments"].size());
  EXPECT_EQ(out["status"], "success");
  EXPECT_EQ(out["resumed_from"]["finished_increments"], 3);
  EXPECT_EQ(out["inverted_cells"], 0);
  EXPECT_NEAR(out["min_scaled_jacobian"].get<double>(), straight["min_scaled_jacobian"].get<double>(), 0.02);
  // Its first increment built a hierarchy anew: other CG iterations than the uninterrupted run's.
  EXPECT_NE(out["increments"][3]["pcg_iterations"], straight["increments"][3]["pcg_iterations"]);
}

/// Starts `hotmesh arguments...` in the background, its output to `log`.
pid_t start_hotmesh(const std::vector<std::string>& arguments, const std::filesystem::path& log) {
  std::vector<std::string> words{HOTMESH_EXE};
  words.insert(words.end(), arguments.begin(), arguments.end());
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

TEST(DeformResume, RunKilledWithSigkillResumesToTheSameOutputs) {
  // The ramp sample (2280 cells, both walls sliding) in 8 increments: slow enough to be killed
  // while it runs, at whatever point of the increment after the second it has reached.
  test::TempDir dir;
  std::filesystem::copy_file(test::kSample / "ramp2d.msh", dir / "ramp2d.msh");
  std::filesystem::copy_file(test::kSample / "ramp.csv", dir / "ramp.csv");
  std::string yaml = test::read_text(test::kSample / "ramp2d-sliding.yaml");
  yaml.replace(yaml.find("increments: 16"), 14, "increments: 8");
  test::write_text(dir / "case.yaml", yaml);
  const std::string case_file = (dir / "case.yaml").string();
  ASSERT_EQ(hotmesh(fmt::format("-q deform {} -o {}", shell_quote(case_file), shell_quote((dir / "straight").string()))).exit_code, 0);

  const auto out = dir / "out";
  const pid_t pid = start_hotmesh({"deform", case_file, "-o", out.string()}, dir / "run.log");
  ASSERT_GT(pid, 0);
  int finished = 0, status = 0;
  bool exited = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  while (finished < 2 && std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    try {
      finished = io::read_checkpoint_info(out / io::kCheckpointName).finished_increments;
    } catch (const InputError&) {  // not written yet
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (!exited) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  ASSERT_FALSE(exited) << "the run ended before it could be killed:\n" << test::read_text(dir / "run.log");
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  ASSERT_GE(finished, 2) << test::read_text(dir / "run.log");
  ASSERT_FALSE(std::filesystem::exists(out / "report.json"));

  const auto resumed = hotmesh(fmt::format("deform {} -o {} --resume", shell_quote(case_file), shell_quote(out.string())));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_THAT(resumed.output, HasSubstr("resuming from"));
  expect_same_outputs(dir / "straight", out);
}

TEST(DeformResume, RestartedRunResumesToo) {
  // The next coupling iteration (restart: from a finished run's restart.hmr), killed and resumed.
  SlidingRamp ramp;
  test::write_text(ramp.dir / "first.yaml", test::ramp_case("half.csv", 2));
  test::write_text(ramp.dir / "second.yaml", test::ramp_case("full.csv", 4, "restart: first-out/restart.hmr\n"));
  ASSERT_EQ(hotmesh("-q deform " + shell_quote((ramp.dir / "first.yaml").string())).exit_code, 0);
  const std::string second = "deform " + shell_quote((ramp.dir / "second.yaml").string()) + " -o ";
  ASSERT_EQ(hotmesh("-q " + second + shell_quote((ramp.dir / "straight").string())).exit_code, 0);
  const std::string out = shell_quote((ramp.dir / "out").string());
  ASSERT_EQ(hotmesh(second + out, killed_after(2)).exit_code, kKilled);
  const auto resumed = hotmesh(second + out + " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  expect_same_outputs(ramp.dir / "straight", ramp.dir / "out");
  EXPECT_THAT(test::read_text(ramp.dir / "out" / "report.json"), HasSubstr("first-out/restart.hmr"));
}

TEST(DeformResume, ChangedCaseOrTableIsRefusedNamingTheFile) {
  SlidingRamp ramp;
  ASSERT_EQ(hotmesh(ramp.deform("out"), killed_after(1)).exit_code, kKilled);
  const std::string yaml = test::read_text(ramp.dir / "case.yaml");
  test::write_text(ramp.dir / "case.yaml", yaml + "# a comment is a change too\n");
  const auto changed_case = hotmesh(ramp.deform("out", "--resume"));
  EXPECT_EQ(changed_case.exit_code, 2);
  EXPECT_THAT(changed_case.output, HasSubstr("cannot resume"));
  EXPECT_THAT(changed_case.output, HasSubstr((ramp.dir / "case.yaml").string() + " has changed"));
  test::write_text(ramp.dir / "case.yaml", yaml);

  const std::string table = test::read_text(ramp.dir / "full.csv");
  test::write_text(ramp.dir / "full.csv", table + "# FEM time step 813\n");
  const auto changed_table = hotmesh(ramp.deform("out", "--resume"));
  EXPECT_EQ(changed_table.exit_code, 2);
  EXPECT_THAT(changed_table.output, HasSubstr((ramp.dir / "full.csv").string() + " has changed"));
  EXPECT_THAT(changed_table.output, Not(HasSubstr("case.yaml has changed")));
  test::write_text(ramp.dir / "full.csv", table);

  // The refusals left the checkpoint alone: with the inputs restored, the run goes on.
  const auto resumed = hotmesh("-q " + ramp.deform("out", "--resume"));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
}

TEST(DeformResume, WithoutCheckpointIsAUserError) {
  SlidingRamp ramp;
  const auto r = hotmesh(ramp.deform("out", "--resume"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--resume: there is no checkpoint.hmc in the output folder"));
  ASSERT_EQ(hotmesh("-q " + ramp.deform("out")).exit_code, 0);  // a run that ends leaves none
  EXPECT_EQ(hotmesh(ramp.deform("out", "--resume")).exit_code, 2);
}

TEST(DeformResume, FreshRunDoesNotReplaceACheckpointUnlessForced) {
  SlidingRamp ramp;
  ASSERT_EQ(hotmesh(ramp.deform("out"), killed_after(3)).exit_code, kKilled);
  const auto refused = hotmesh(ramp.deform("out"));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.output, HasSubstr("holds checkpoint.hmc, the checkpoint of an interrupted run"));
  EXPECT_THAT(refused.output, HasSubstr("3 of 6 increments done"));
  EXPECT_THAT(refused.output, HasSubstr("--resume"));
  EXPECT_EQ(io::read_checkpoint_info(ramp.dir / "out" / io::kCheckpointName).finished_increments, 3);
  const auto forced = hotmesh(ramp.deform("out", "--force"));
  EXPECT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_THAT(forced.output, HasSubstr("increment 1/6"));
  EXPECT_FALSE(std::filesystem::exists(ramp.dir / "out" / io::kCheckpointName));
}

TEST(DeformResume, OutOfMemoryExitsWithCodeFourAndKeepsTheCheckpoint) {
  if (!test::allocation_faults_reach_hotmesh()) GTEST_SKIP() << "clang's AddressSanitizer keeps operator new to itself";
  SlidingRamp ramp;
  ASSERT_EQ(hotmesh("-q " + ramp.deform("straight")).exit_code, 0);
  // The test library fails the first large allocation after the second checkpoint: an array of
  // increment 3, allocated before its first Newton step. The phase is the last one reported,
  // that of increment 2's steps.
  const auto r = hotmesh(ramp.deform("out"), {.fail_allocation_after_checkpoint = 2});
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_THAT(r.output, HasSubstr("out of memory while moving the mesh (increment 2 of 6) on a mesh of"));
  EXPECT_THAT(r.output, HasSubstr("the last checkpoint, 2 increments done, is kept in"));
  EXPECT_THAT(r.output, HasSubstr("--resume"));
  EXPECT_EQ(io::read_checkpoint_info(ramp.dir / "out" / io::kCheckpointName).finished_increments, 2);
  const auto resumed = hotmesh("-q " + ramp.deform("out", "--resume"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  expect_same_outputs(ramp.dir / "straight", ramp.dir / "out");
}

TEST(DeformResume, TooLittleMemoryForTheThreadsExitsWithCodeFour) {
  // Issue 18: out of memory around the OpenMP loops ended the run with "libgomp: Thread
  // creation failed" and exit code 1 (which means the motion failed) once the first loop
  // large enough to run in parallel started its threads. The ramp sample (2280 cells) in one
  // increment on 64 threads, whose stacks of 8 MB do not fit in 400 MB of address space: the
  // run stops before any work, as out of memory. (Not under AddressSanitizer, which reserves
  // terabytes of address space.)
  if (test::under_sanitizers()) GTEST_SKIP() << "ulimit -v does not work under AddressSanitizer";
  std::string yaml = test::read_text(test::kSample / "ramp2d.yaml");
  yaml.replace(yaml.find("increments: 16"), 14, "increments: 1");
  const test::RampCase ramp(yaml);
  const std::string limited = "ulimit -s 8192 && ulimit -v 400000 && env -u OMP_STACKSIZE -u GOMP_STACKSIZE " +
                              std::string(HOTMESH_EXE) + " deform " + ramp.case_file();
  const auto r = test::run_command(limited + " --threads 64");
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_THAT(r.output, HasSubstr("out of memory while starting 64 threads"));
  EXPECT_THAT(r.output, Not(HasSubstr("libgomp")));
  EXPECT_FALSE(std::filesystem::exists(ramp.dir / "case-out"));
  // With the threads it can hold, the same run goes through.
  const auto fits = test::run_command(limited + " --threads 2");
  EXPECT_EQ(fits.exit_code, 0) << fits.output;
}

TEST(DeformCommand, ProgressLinePerNewtonStepOnRequest) {
  SlidingRamp ramp;
  const auto plain = hotmesh(ramp.deform("a"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_THAT(plain.output, Not(HasSubstr(" Newton 1:")));  // a small mesh: one line per increment
  const auto progress = hotmesh(ramp.deform("b", "--progress"));
  ASSERT_EQ(progress.exit_code, 0) << progress.output;
  EXPECT_THAT(progress.output, HasSubstr("increment 1/6 Newton 1: residual "));
  EXPECT_THAT(progress.output, HasSubstr("increment 6/6 Newton 2: residual "));
  EXPECT_THAT(progress.output, HasSubstr(" of initial, PCG "));
  // The first solve of an increment stops on ||D^-1 r|| (method.md, inexact Newton), as does the
  // one after a step that raised the residual (here the second); the others on ||r||.
  EXPECT_THAT(progress.output, ContainsRegex("increment 1/6 Newton 1: residual [^\n]* PCG [0-9]+ in the Newton norm, "));
  EXPECT_THAT(progress.output, ContainsRegex("increment 1/6 Newton 4: residual [^\n]* PCG [0-9]+, "));
  EXPECT_THAT(progress.output, HasSubstr(", sliding projection "));
  EXPECT_THAT(progress.output, HasSubstr(" s (run "));
  EXPECT_THAT(hotmesh("-v " + ramp.deform("c")).output, HasSubstr("increment 1/6 Newton 1: "));
  const auto quiet = hotmesh("-q " + ramp.deform("d", "--progress"));
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_EQ(quiet.output, "");
}

}  // namespace
}  // namespace hotmesh::app
