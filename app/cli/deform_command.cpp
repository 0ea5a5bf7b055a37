// hotmesh deform CASE.yaml [-o DIR] [--threads N] [--force] [--binary] [--resume] [--progress]
// [--foam-time T]:
// the main job. Reads and validates everything first, moves the mesh increment by increment
// (saving a checkpoint after each), and writes the deformed mesh (.msh, .vtu), pictures for 2D
// meshes, report.json and restart.hmr (the state the next coupling iteration continues from)
// to the output folder. If the motion fails it keeps the last valid mesh, writes failed.vtu
// marking the failed cells and exits with code 1. --resume continues a killed run from its
// checkpoint. An OpenFOAM mesh is also written back as polyMesh/ in the output folder (and
// with --foam-time into the case's time folder T/polyMesh). Running out of memory is reported
// with the phase and exit code 4. Under mpirun every rank runs this command; rank 0 alone logs
// progress and writes files.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <array>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <new>
#include <optional>
#include <span>

#include "cli/commands.hpp"
#include "hotmesh/api/deform_checkpoint.hpp"
#include "hotmesh/api/deform_outputs.hpp"
#include "hotmesh/api/deform_run.hpp"
#include "hotmesh/api/series_outputs.hpp"
#include "hotmesh/core/clock.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/io/output_folder.hpp"
#include "hotmesh/io/restart_file.hpp"
#include "hotmesh/parallel/processes.hpp"
#include "hotmesh/parallel/threads.hpp"
#include "cli/logging.hpp"
#include "cli/passive_wait.hpp"

namespace hotmesh::app {
namespace {

using api::CheckpointWriter;
using api::RunState;
using api::RunTimings;
using api::SeriesWriter;
using api::peak_memory_bytes;
using api::output_names;
using api::refuse_to_replace_checkpoint;

struct Options {
  std::string case_file;
  std::string output;
  int threads = -1;
  bool force = false;
  bool binary = false;
  bool resume = false;
  bool progress = false;
  bool series = false;     ///< --series: as the case's `output: {series: true}`
  std::string foam_time;  ///< empty: no time folder written into the OpenFOAM case
};

void report_out_of_memory(const RunState& state) {
  std::string sizes = state.nodes > 0 ? fmt::format(" on a mesh of {} nodes and {} cells", state.nodes, state.cells) : "";
  const parallel::Processes job = parallel::processes();
  const std::string rank = job.count > 1 ? fmt::format(" in rank {} of {}", job.rank, job.count) : "";
  spdlog::error("out of memory{} while {}{} (peak memory of this process {:.2f} GB)", rank, state.phase, sizes,
                static_cast<double>(peak_memory_bytes()) / 1e9);
  if (job.count > 1) {
    spdlog::error("every rank keeps the whole mesh and its share of the matrix: with fewer ranks per machine each "
                  "has more memory");
  }
  if (state.checkpoint_increments >= 0) {
    spdlog::error("the last checkpoint, {} increments done, is kept in {}: run the same command with --resume where "
                  "more memory is available (or with fewer threads) to continue from it",
                  state.checkpoint_increments, state.checkpoint.string());
  } else if (!state.checkpoint.empty()) {
    spdlog::error("no increment had finished, so there is nothing to resume; outputs already in the folder are "
                  "those of earlier runs");
  }
}

/// Makes the output folder ready (`folder`); with --resume, reads the checkpoint in it and
/// checks it against this run's inputs (`fingerprints`).
std::optional<io::Checkpoint> prepare_output(const Options& options, const io::Case& c, const io::LoadedMesh& loaded,
                                             const std::filesystem::path& output,
                                             std::span<const io::InputFingerprint> fingerprints,
                                             io::OutputFolder& folder) {
  const auto inputs = c.inputs();
  const auto names = output_names(c, loaded);
  std::optional<io::Checkpoint> resumed;
  if (options.resume) {
    // The folder was accepted by the run that wrote the checkpoint: no check for inputs in it
    // (that run may have been forced), but no output may replace one.
    const auto path = output / io::kCheckpointName;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      throw InputError::in(output.string(), fmt::format("--resume: there is no {} in the output folder, so no "
                                                        "interrupted run to continue; run without --resume to start",
                                                        io::kCheckpointName));
    }
    resumed = io::read_checkpoint(path, loaded.mesh, fingerprints);
    if (resumed->info.hotmesh_version != HOTMESH_VERSION) {
      spdlog::warn("the checkpoint was written by hotmesh {}, this is {}: the result may differ slightly from an "
                   "uninterrupted run", resumed->info.hotmesh_version, HOTMESH_VERSION);
    }
  } else {
    folder = io::prepare_output_folder(output, inputs, options.force);
    refuse_to_replace_checkpoint(output, options.force);
  }
  for (const auto& name : names) io::refuse_overwriting_input(output / name, inputs);
  // Only rank 0 writes: the other ranks leave the folder to it.
  if (parallel::processes().root()) {
    io::remove_stale_temporaries(output, names);
  } else {
    folder.keep();
  }
  return resumed;
}

/// --foam-time T: the mesh must be an OpenFOAM case's, and T/polyMesh/points no input.
void check_foam_time(const Options& options, const io::Case& c) {
  if (options.foam_time.empty()) return;
  if (io::mesh_format(c.mesh) != io::MeshFormat::foam) {
    throw InputError::in("--foam-time", "writes into an OpenFOAM case, but the case's mesh " + c.mesh.string() +
                                            " is not an OpenFOAM polyMesh");
  }
  const std::filesystem::path folder = io::foam_time_folder(c.mesh, options.foam_time);
  const auto inputs = c.inputs();
  for (const char* name : {"points", "points.gz"}) io::refuse_overwriting_input(folder / name, inputs);
}

/// What a run reads and checks before any work.
struct RunInputs {
  api::LoadedCase run;  ///< the case, its CAD file and mesh, the threads
  std::filesystem::path output;
  std::vector<io::InputFingerprint> fingerprints;
  io::OutputFolder folder;  // removed again if the run fails before writing in it
  std::optional<io::Checkpoint> resumed;
  // A restarted run continues from the state a previous run saved (section 4.3).
  std::optional<io::RestartState> previous;
  std::optional<deform::MotionStart> restart;
};

/// 1. Everything the run needs, read and checked before any work.
void read_inputs(const Options& options, RunState& state, RunInputs& in) {
  in.run.c = io::read_case(options.case_file);
  const io::Case& c = in.run.c;
  in.run.threads.wait = wait_policy();
  api::load_case(in.run, api::thread_request(options.threads, "--threads", c), state);
  const mesh::Mesh& mesh = in.run.loaded.mesh;
  check_foam_time(options, c);
  in.output = options.output.empty() ? c.output : std::filesystem::path(options.output);
  state.phase = "checking the inputs";
  in.fingerprints = io::input_fingerprints(c);
  in.resumed = prepare_output(options, c, in.run.loaded, in.output, in.fingerprints, in.folder);
  if (c.restart) {
    in.previous = io::read_restart(*c.restart, mesh);
    in.restart = deform::MotionStart{in.previous->points, in.previous->sliding};
    spdlog::info("restarting from {} ({} sliding nodes)", c.restart->string(), in.previous->sliding.size());
  }
}

/// The series of the run (--series, or the case's `output: {series: true}`), written by rank 0.
std::optional<SeriesWriter> start_series(const Options& options, const RunInputs& in, const setup::CaseSetup& setup) {
  std::optional<SeriesWriter> series;
  if (!(options.series || in.run.c.series) || !parallel::processes().root()) return series;
  const io::LoadedMesh& loaded = in.run.loaded;
  if (in.resumed) {
    series.emplace(in.output, loaded.mesh, loaded.layer, setup.motions,
                   in.resumed->state.lambda * in.run.c.solver.increments);
  } else {
    series.emplace(in.output, loaded.mesh, loaded.layer, setup.motions);
    series->add(0.0, 0.0, in.restart ? std::span<const geometry::Vec3>(in.restart->points) : loaded.mesh.points);
  }
  return series;
}

int run_deform(const Options& options, RunState& state) {
  const auto start = Clock::now();
  RunTimings timings;

  auto t = Clock::now();
  RunInputs in;
  read_inputs(options, state, in);
  timings.read = seconds_since(t);

  // 2. The deflected shapes, from the FEM tables (section 4.2).
  state.phase = "building the deflected shapes";
  t = Clock::now();
  const setup::CaseSetup setup = api::set_up_shapes(in.run, in.previous ? &*in.previous : nullptr);
  timings.shapes = seconds_since(t);

  const io::Case& c = in.run.c;
  const int increments = c.solver.increments;
  CheckpointWriter checkpoints(in.output / io::kCheckpointName, c, in.run.loaded.mesh, std::move(in.fingerprints));
  state.checkpoint = checkpoints.path();
  if (in.resumed) state.checkpoint_increments = in.resumed->info.finished_increments;
  std::optional<SeriesWriter> series = start_series(options, in, setup);
  const parallel::Processes job = parallel::processes();
  api::MotionSettings motion;
  motion.progress = options.progress;
  motion.restart = in.restart ? &*in.restart : nullptr;
  motion.resumed = in.resumed ? &*in.resumed : nullptr;
  motion.checkpoint_path = checkpoints.path();
  motion.checkpoint = [&](const deform::MotionCheckpoint& k) {
    // The series step first: a run that stops after its checkpoint has it too.
    if (series) series->add(k.lambda * increments, k.lambda, k.points);
    if (job.root()) checkpoints.write(k);  // before rank 0 joins the others in the next step
    state.checkpoint_increments = k.finished_increments;
  };
  const deform::MotionResult result = api::move_the_mesh(in.run, setup, motion, state, start);
  if (series && result.success && std::any_of(result.increments.begin(), result.increments.end(), [](const auto& r) {
        return r.corner_pass && r.accepted;
      })) {
    series->add(increments + 1.0, 1.0, result.points);  // after the corner pass
  }
  const std::optional<io::CheckpointInfo> resumed_from = in.resumed ? std::optional(in.resumed->info) : std::nullopt;
  in.resumed.reset();  // its copy of the mesh is no longer needed
  api::log_motion(in.run.loaded.mesh, result);

  state.phase = "writing the outputs";
  std::array<double, 1> memory{static_cast<double>(peak_memory_bytes())};
  parallel::job_exchange().sum(memory);  // every rank: the job's memory for rank 0's report
  timings.peak_memory_all_ranks = static_cast<std::uint64_t>(memory[0]);
  if (!job.root()) return result.success ? 0 : 1;
  api::OutputSettings outputs;
  outputs.binary_msh = options.binary;
  if (!options.foam_time.empty()) outputs.write_back.foam_time = options.foam_time;
  outputs.checkpoints = &checkpoints;
  outputs.resumed_from = resumed_from ? &*resumed_from : nullptr;
  return api::write_run_outputs(in.output, c, in.run, setup, result, outputs, timings, start);
}

}  // namespace

Command add_deform_command(CLI::App& parent) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand("deform", "Deform a mesh as a case file describes (the main job)");
  cmd->add_option("CASE", options->case_file, "Case file (.yaml), see docs/case-file.md")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", options->output, "Output folder (default: the case's `output`, else <case name>-out beside the case file)");
  cmd->add_option("--threads", options->threads,
                  "OpenMP threads (default: the case's solver.threads; 0: hotmesh chooses from the mesh's size and the "
                  "cores other processes leave free)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--series", options->series,
                "Write the mesh and the walls after every increment as ParaView time series (deformed.pvd, walls.pvd)");
  cmd->add_flag("--force", options->force,
                "Write into the output folder even if it holds input files or the checkpoint of an interrupted run");
  cmd->add_flag("--binary", options->binary, "Write deformed.msh in binary (smaller, faster for large meshes)");
  cmd->add_flag("--resume", options->resume,
                "Continue an interrupted run from the checkpoint in its output folder (same case and inputs)");
  cmd->add_flag("--progress", options->progress,
                "Log every Newton step (the default for meshes of 100 000 cells or more; -v shows them too)");
  cmd->add_option("--foam-time", options->foam_time,
                  "OpenFOAM meshes: also write the moved points into the case's time folder T/polyMesh (see "
                  "docs/openfoam.md)");
  return [options] {
    RunState state;
    const parallel::Processes job = parallel::start_processes();  // mpirun: MPI, this process's rank
    if (!job.root()) quiet_other_ranks(job.rank);
    try {
      return run_deform(*options, state);
    } catch (const std::bad_alloc&) {
      report_out_of_memory(state);
      return kExitOutOfMemory;
    }
  };
}

}  // namespace hotmesh::app
