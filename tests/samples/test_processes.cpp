// hotmesh deform under mpirun: the cells partitioned among 2 and 4 processes (oversubscribed
// on a machine with fewer cores) move the stator-well sector — 3D, sliding disc walls,
// passive and periodic faces — to where one process moves it: with the tolerances tightened
// to 1e-10 the meshes agree to 1e-8 of the domain; runs on two ranks repeat bit for bit on a
// busy machine. Rank 0 alone writes the outputs; a killed job resumes on another number of
// ranks; a rank out of memory ends the job with exit code 4; a case the ranks cannot run
// (jacobi-pcg) is refused once, with exit code 2 from mpirun, as is a launch by another MPI's
// launcher.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "faults.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/split_cells.hpp"
#include "coarse_ramp.hpp"
#include "output_folders.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::samples {
namespace {

namespace fs = std::filesystem;

/// Under the sanitizers, a process whose Open MPI is not an isolated singleton runs without
/// LeakSanitizer: Open MPI's runtime (its event thread, the plugins it unloads at exit) leaves
/// allocations LSan cannot attribute. hotmesh's own code is leak-checked in the one-process
/// runs.
const std::string kOpenMpiRuntime = "ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" ";

/// `env -u` for every variable of Open MPI's runtime in this process's environment: a test
/// that ran the amg solver in this process started an MPI singleton, which wrote them
/// (OMPI_MCA_ess=singleton, ...), and mpirun or hotmesh started with them would join that
/// singleton's job instead of starting their own.
std::string without_open_mpi_runtime() {
  std::string command = "env";
  for (char** variable = environ; *variable; ++variable) {
    const std::string entry = *variable;
    const std::string name = entry.substr(0, entry.find('='));
    for (const char* prefix : {"OMPI_", "PMIX_", "OPAL_"}) {
      if (name.rfind(prefix, 0) == 0) command += " -u " + name;
    }
  }
  return command + " ";
}

/// Open MPI's launcher: allowed to run as root (CI containers), on more ranks than cores,
/// one thread per rank, shared memory between ranks without the cross-memory attach that
/// containers often forbid (ptrace); `faults` injected into the ranks.
std::string mpirun(int ranks, const test::Faults& faults = {}) {
  return without_open_mpi_runtime() + kOpenMpiRuntime + fmt::format("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 "
                                       "{} -n {} --oversubscribe --mca mpi_yield_when_idle 1 "
                                       "--mca btl_vader_single_copy_mechanism none {}",
                                       HOTMESH_MPIEXEC, ranks, test::mpirun_fault_options(faults));
}

/// `text` with its first `from` replaced by `to`; fails the test if there is none.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the case";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

nlohmann::json report(const fs::path& out) { return test::read_json(out / "report.json"); }

/// Every core kept half busy (2 ms on, 2 ms off) while it lives, so that threads of the
/// processes under test are scheduled differently from run to run.
class BusyCores {
 public:
  BusyCores() {
    for (unsigned i = 0; i < std::max(2U, std::thread::hardware_concurrency()); ++i) {
      threads_.emplace_back([this] {
        using Clock = std::chrono::steady_clock;
        while (!done_.load(std::memory_order_relaxed)) {
          for (const auto until = Clock::now() + std::chrono::milliseconds(2); Clock::now() < until;) {
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
      });
    }
  }
  ~BusyCores() {
    done_ = true;
    for (auto& thread : threads_) thread.join();
  }
  BusyCores(const BusyCores&) = delete;
  BusyCores& operator=(const BusyCores&) = delete;

 private:
  std::atomic<bool> done_ = false;
  std::vector<std::thread> threads_;
};

class Processes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    const auto generate = test::run_command(std::string(HOTMESH_MAKE_STATOR_WELL) + " --cells 2000 " +
                                            test::shell_quote(dir_->path().string()));
    ASSERT_EQ(generate.exit_code, 0) << generate.output;
    // The amg solver, tolerances tightened, 4 increments (2 under the sanitizers, where the
    // one- and two-rank runs of 4 took 100 s).
    std::string text = test::read_text(*dir_ / "case_small.yaml");
    text = replaced(text, "solver: {increments: 16}",
                    fmt::format("solver: {{increments: {}, linear: amg, newton_tolerance: 1.0e-10, "
                                "pcg_tolerance: 1.0e-10, max_newton_iterations: 60}}",
                                test::under_sanitizers() ? 2 : 4));
    test::write_text(*dir_ / "tight.yaml", text);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  /// `hotmesh deform` of `case_file` on `ranks` processes (0: without mpirun) into `out`, with
  /// `faults` injected.
  static test::CommandResult deform_case(int ranks, const fs::path& case_file, const fs::path& out,
                                         const std::string& options = "", const test::Faults& faults = {}) {
    return test::run_command((ranks > 0 ? mpirun(ranks, faults) : test::fault_variables(faults)) + HOTMESH_EXE +
                             " deform " + test::shell_quote(case_file.string()) + " -o " +
                             test::shell_quote(out.string()) + options);
  }

  /// The coarse ramp channel with both walls sliding over `table` in `increments`, solved to
  /// 1e-10 with `linear` in one process (out-1) and on two ranks (out-2): both must succeed and
  /// end within 1e-8 of each other.
  static fs::path sliding_ramp_on_one_and_two_ranks(const fs::path& dir, const std::string& linear,
                                                    const std::string& table, int increments) {
    fs::create_directories(dir);
    test::write_coarse_ramp(dir);
    std::string text = test::ramp_case(table, increments);
    text = replaced(text, "newton_tolerance: 1.0e-6",
                    "linear: " + linear + ", newton_tolerance: 1.0e-10, max_newton_iterations: 60");
    test::write_text(dir / "case.yaml", text);
    const auto one = deform_case(0, dir / "case.yaml", dir / "out-1");
    EXPECT_EQ(one.exit_code, 0) << one.output;
    const auto two = deform_case(2, dir / "case.yaml", dir / "out-2");
    EXPECT_EQ(two.exit_code, 0) << two.output;
    if (one.exit_code == 0 && two.exit_code == 0) {
      EXPECT_EQ(report(dir / "out-2")["solver"]["linear"], linear);
      EXPECT_EQ(report(dir / "out-2")["solver"]["processes"], 2);
      EXPECT_GT(report(dir / "out-2")["sliding_nodes"].get<int>(), 0);
      EXPECT_LT(test::largest_relative_distance(dir / "out-1", dir / "out-2"), 1e-8);
    }
    return dir;
  }

  /// `hotmesh deform` of the tight case on `ranks` processes (0: without mpirun) into `out`.
  static test::CommandResult deform(int ranks, const fs::path& out, const std::string& options = "",
                                    const test::Faults& faults = {}) {
    return deform_case(ranks, *dir_ / "tight.yaml", out, options, faults);
  }

  /// The run on `ranks` processes into out-<ranks>, once per test program.
  static fs::path run(int ranks) {
    const fs::path out = *dir_ / fmt::format("out-{}", ranks);
    if (fs::exists(out / "report.json")) return out;
    const auto r = deform(ranks, out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return out;
  }

  static test::TempDir* dir_;
};
test::TempDir* Processes::dir_ = nullptr;

TEST_F(Processes, OneTwoAndFourRanksMoveTheSectorAlike) {
  const fs::path serial = run(0);
  const fs::path two = run(2);
  EXPECT_LT(test::largest_relative_distance(serial, two), 1e-8);
  EXPECT_EQ(report(two)["solver"]["processes"], 2);
  EXPECT_EQ(report(serial)["solver"]["processes"], 1);
  // The same increments, sliding and periodic checks as one process.
  EXPECT_EQ(report(two)["increments"].size(), report(serial)["increments"].size());
  EXPECT_LT(report(two)["max_periodic_mismatch_relative"].get<double>(), 1e-12);
  // The job's memory: both ranks' peaks, each holding the whole mesh; one process's own.
  const auto peak = [](const nlohmann::json& r, const char* key) { return r[key].get<double>(); };
  EXPECT_GT(peak(report(two), "peak_memory_bytes_all_ranks"), 1.5 * peak(report(two), "peak_memory_bytes"));
  EXPECT_EQ(peak(report(serial), "peak_memory_bytes_all_ranks"), peak(report(serial), "peak_memory_bytes"));
  if (test::under_sanitizers()) return;  // four ranks under the sanitizers: minutes
  const fs::path four = run(4);
  EXPECT_LT(test::largest_relative_distance(serial, four), 1e-8);
  EXPECT_LT(test::largest_relative_distance(two, four), 1e-8);
}

/// A job of two ranks killed after its second increment resumes in one process (the
/// checkpoint knows nothing of the partition) and ends where an uninterrupted run does.
TEST_F(Processes, AKilledJobResumesOnAnotherNumberOfRanks) {
  if (test::under_sanitizers()) GTEST_SKIP() << "a minute under the sanitizers; DeformResume checks the resume's memory";
  const fs::path out = *dir_ / "out-killed";
  const auto killed = deform(2, out, "", {.kill_after_checkpoint = 2});  // rank 0, which writes the checkpoints
  EXPECT_NE(killed.exit_code, 0) << killed.output;
  ASSERT_TRUE(fs::exists(out / "checkpoint.hmc")) << killed.output;
  EXPECT_FALSE(fs::exists(out / "report.json"));
  const auto resumed = deform(0, out, " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(report(out)["resumed_from"]["finished_increments"], 2);
  EXPECT_LT(test::largest_relative_distance(run(0), out), 1e-8);
}

/// A job of two ranks killed after its second increment and resumed on two ranks ends with the
/// very mesh of the uninterrupted job: the partition, made by one PT-Scotch thread, is the same
/// in both jobs, and each increment's hierarchy comes from a new KSP (`amg_reuse: auto` on a
/// mesh this small).
TEST_F(Processes, AKilledJobResumedOnTwoRanksEndsBitForBitAsTheUninterruptedOne) {
  // A property of determinism, which the sanitizers add nothing to; the two-rank write and the
  // read of a checkpoint run under them in the test above (2.5 minutes there).
  if (test::under_sanitizers()) GTEST_SKIP() << "two more two-rank runs under the sanitizers: minutes";
  const fs::path out = *dir_ / "out-killed-2";
  const auto killed = deform(2, out, "", {.kill_after_checkpoint = 2});
  ASSERT_TRUE(fs::exists(out / "checkpoint.hmc")) << killed.output;
  const auto resumed = deform(2, out, " --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  test::expect_same_outputs(run(2), out);
}

/// Runs of one case on two ranks repeat bit for bit, even on a busy machine: PT-Scotch's
/// threads, scheduled differently from run to run, made other partitions (2 loaded runs in 6
/// of the 18 000-cell sector), so other CG iterations and other meshes, until the partitioner
/// was given one thread. Three runs of that sector stopped after their first increment, with
/// every core also kept half busy: the same CG iterations and the same nodes.
/// The sector as a hybrid mesh (every second hex split about its centre into tetrahedra, with
/// pyramids against the hexes kept), its walls sliding over their surfaces of revolution on
/// faces of triangles and quads: two ranks move it as one process does.
TEST_F(Processes, AHybridSectorMovesOnTwoRanksAsInOneProcess) {
  if (test::under_sanitizers()) GTEST_SKIP() << "the hex sector's runs cover the ranks under the sanitizers";
  mesh::Mesh hexes = io::read_mesh(*dir_ / "stator_well.msh").mesh;
  hexes.node_ids.clear();  // numbered 1, 2, 3, ... in the file
  hexes.cell_ids.clear();
  std::vector<mesh::CellSplit> split(hexes.cell_count(), mesh::CellSplit::keep);
  for (std::size_t c = 0; c < split.size(); c += 2) split[c] = mesh::CellSplit::tetrahedra;
  io::write_gmsh(*dir_ / "hybrid.msh", mesh::split_cells(hexes, split));
  std::string text = replaced(test::read_text(*dir_ / "tight.yaml"), "mesh: stator_well.msh", "mesh: hybrid.msh");
  text = replaced(text, "increments: 4", "increments: 2");
  test::write_text(*dir_ / "hybrid.yaml", text);
  const fs::path one = *dir_ / "hybrid-1", two = *dir_ / "hybrid-2";
  const auto r1 = deform_case(0, *dir_ / "hybrid.yaml", one);
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  const auto r2 = deform_case(2, *dir_ / "hybrid.yaml", two);
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  EXPECT_LT(test::largest_relative_distance(one, two), 1e-10);
  const nlohmann::json on_two = report(two);
  for (const char* type : {"hex8", "tet4", "pyramid5"}) {
    EXPECT_EQ(on_two["quality"]["by_type"][type]["inverted_cells"], 0) << type;
  }
  EXPECT_GT(on_two["sliding_nodes"].get<int>(), 0);
  EXPECT_EQ(on_two["solver"]["processes"], 2);
}

TEST_F(Processes, RunsOnTwoRanksRepeatOnABusyMachine) {
  if (test::under_sanitizers()) GTEST_SKIP() << "three 18 000-cell runs under the sanitizers: minutes";
  const fs::path dir = *dir_ / "repeat";
  const auto generate = test::run_command(std::string(HOTMESH_MAKE_STATOR_WELL) + " " + test::shell_quote(dir.string()));
  ASSERT_EQ(generate.exit_code, 0) << generate.output;
  std::string text = test::read_text(dir / "case_small.yaml");
  text = replaced(text, "solver: {increments: 16}", "solver: {increments: 16, linear: amg, forcing: eisenstat-walker}");
  test::write_text(dir / "repeat.yaml", text);

  const io::Case repeat = io::read_case(dir / "repeat.yaml");
  const mesh::Mesh mesh = io::read_mesh(repeat.mesh).mesh;
  const auto inputs = io::input_fingerprints(repeat);
  std::vector<deform::MotionCheckpoint> runs;
  {
    const BusyCores busy;
    for (int attempt = 0; attempt < 3; ++attempt) {
      const fs::path out = dir / fmt::format("out-{}", attempt);
      const auto r = deform_case(2, repeat.file, out, "", {.kill_after_checkpoint = 1});
      ASSERT_TRUE(fs::exists(out / "checkpoint.hmc")) << r.output;
      runs.push_back(io::read_checkpoint(out / "checkpoint.hmc", mesh, inputs).state);
    }
  }
  const auto cg_iterations = [](const deform::MotionCheckpoint& state) {
    std::vector<int> counts;
    for (const auto& step : state.records.at(0).newton) counts.push_back(step.pcg_iterations);
    return counts;
  };
  for (std::size_t k = 1; k < runs.size(); ++k) {
    EXPECT_EQ(cg_iterations(runs[k]), cg_iterations(runs[0])) << "run " << k + 1;
    ASSERT_EQ(runs[k].points.size(), runs[0].points.size());
    std::size_t elsewhere = 0;
    for (std::size_t i = 0; i < runs[0].points.size(); ++i) {
      if (runs[k].points[i] != runs[0].points[i]) ++elsewhere;
    }
    EXPECT_EQ(elsewhere, 0U) << "run " << k + 1 << ": nodes elsewhere than in the first run";
  }
}

/// One rank out of memory ends the whole job with exit code 4, says which rank, and keeps the
/// checkpoint of the increments done. The rank is rank 0: the test library fails an allocation
/// after a checkpoint, which only the rank that writes it knows to be in place. (The other
/// ranks run ahead into the next increment while it is written, and from outside none can tell
/// where in its run it is.)
TEST_F(Processes, ARankOutOfMemoryEndsTheJobWithExitCode4) {
  if (!test::allocation_faults_reach_hotmesh()) GTEST_SKIP() << "clang's AddressSanitizer keeps operator new to itself";
  const fs::path out = *dir_ / "out-memory";
  // The first large allocation after the first checkpoint: an array of increment 2, before its
  // first Newton step (so the phase is still that of increment 1's steps).
  const auto r = deform(2, out, "", {.fail_allocation_after_checkpoint = 1});
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("out of memory in rank 0 of 2 while moving the mesh (increment 1 of 4)"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("the last checkpoint, 1 increments done"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "checkpoint.hmc"));
}

/// Started by another MPI's launcher (MPICH's mpiexec sets PMI_SIZE), hotmesh's Open MPI would
/// see one process of its own in each launched process, all writing the same files: refused.
TEST_F(Processes, AnotherMpisLauncherIsRefusedWithExitCode2) {
  const auto r = test::run_command(without_open_mpi_runtime() + kOpenMpiRuntime + "PMI_SIZE=2 PMI_RANK=0 " + HOTMESH_EXE + " deform " +
                                   test::shell_quote((*dir_ / "tight.yaml").string()) + " -o " +
                                   test::shell_quote((*dir_ / "out-launcher").string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("an MPI launcher started hotmesh as one of 2 processes"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Open MPI's mpirun"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(*dir_ / "out-launcher" / "report.json"));
}

/// `linear: direct` under mpirun: MUMPS factorizes the matrix the ranks share (CHOLMOD in one
/// process), and a coarse ramp channel with both walls sliding ends where one process puts it.
TEST_F(Processes, DirectSolverOnTwoRanksMovesASlidingRampAsOneProcess) {
  // Under the sanitizers MUMPS's factorizations took 158 s for 4 increments: 2 there.
  const fs::path dir = sliding_ramp_on_one_and_two_ranks(*dir_ / "direct", "direct", "full.csv", test::under_sanitizers() ? 2 : 4);
  // One CG iteration per Newton step on either: the factors are exact on every rank's rows.
  EXPECT_EQ(report(dir / "out-2")["pcg_iterations"], report(dir / "out-2")["newton_iterations"]);
}

/// `linear: icc` under mpirun: block Jacobi between the ranks, incomplete factors of each
/// rank's rows; the same motion as one process, without going over to `direct`.
TEST_F(Processes, IccOnTwoRanksMovesASlidingRampAsOneProcess) {
  // The half ramp: every increment converges as it comes (the full ramp in 4 increments splits
  // its first, whose Newton steps stall at 3e-7 and ask ICC for more than it is made for).
  const fs::path dir = sliding_ramp_on_one_and_two_ranks(*dir_ / "icc", "icc", "half.csv", 4);
  for (const char* out : {"out-1", "out-2"}) EXPECT_TRUE(report(dir / out)["notes"].empty()) << report(dir / out)["notes"];
}

TEST_F(Processes, JacobiPcgIsRefusedOnceWithExitCode2) {
  std::string text = test::read_text(*dir_ / "tight.yaml");
  text = replaced(text, "linear: amg", "linear: jacobi-pcg");
  test::write_text(*dir_ / "jacobi.yaml", text);
  const auto r = deform_case(2, *dir_ / "jacobi.yaml", *dir_ / "out-jacobi");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string message = "solver.linear: jacobi-pcg runs in one process";
  const auto first = r.output.find(message);
  ASSERT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(message, first + 1), std::string::npos) << "reported by more than rank 0:\n" << r.output;
  EXPECT_FALSE(fs::exists(*dir_ / "out-jacobi" / "report.json"));
}

}  // namespace
}  // namespace hotmesh::samples
