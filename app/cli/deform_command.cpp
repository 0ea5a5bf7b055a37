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
#include <omp.h>
#include <spdlog/spdlog.h>

#include <array>
#include <map>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <new>
#include <optional>
#include <span>

#include "cli/commands.hpp"
#include "reports/deform_checkpoint.hpp"
#include "reports/deform_outputs.hpp"
#include "reports/series_outputs.hpp"
#include "hotmesh/deform/move_mesh.hpp"
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
#include "hotmesh/mesh/parallel_loops.hpp"
#include "hotmesh/parallel/processes.hpp"
#include "hotmesh/parallel/threads.hpp"
#include "cli/logging.hpp"
#include "cli/passive_wait.hpp"

namespace hotmesh::app {
namespace {

/// From this size on, every Newton step is logged at info level (else at debug, -v): a step
/// then takes seconds to minutes, and a user wants to see the run is alive.
constexpr std::size_t kProgressCells = 100'000;

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

/// Where the run is, for the message if memory runs out (kept outside the run, which the
/// exception unwinds).
struct RunState {
  std::string phase = "reading the case";
  std::size_t nodes = 0;
  std::size_t cells = 0;
  std::filesystem::path checkpoint;  ///< set once the motion starts
  int checkpoint_increments = -1;    ///< increments done in the last checkpoint written, -1: none
};

/// "1 thread", "2 threads".
std::string counted(int count, const char* noun) { return fmt::format("{} {}{}", count, noun, count == 1 ? "" : "s"); }

std::string piece_of(int split_depth) { return split_depth > 0 ? fmt::format(" (1/{} piece)", 1 << split_depth) : ""; }

void log_increment(const deform::IncrementRecord& r, int increments) {
  if (r.corner_pass) {
    spdlog::info("corner pass {}: nodes onto the corners of the sliding walls, {} Newton iterations, min scaled "
                 "Jacobian {:.3f}{}",
                 r.increment - increments, r.newton.size() - 1, r.min_scaled_jacobian,
                 r.accepted ? "" : fmt::format(", rejected: {}", r.failure));
    return;
  }
  std::string pcg;
  for (std::size_t i = 0; i + 1 < r.newton.size(); ++i) pcg += fmt::format("{}{}", i ? "+" : "", r.newton[i].pcg_iterations);
  const std::string piece = piece_of(r.split_depth);
  if (r.accepted) {
    spdlog::info("increment {}/{}{}: stage {:.4f}, {} Newton iterations (PCG {}), residual {:.2e}, min scaled "
                 "Jacobian {:.3f}, {:.2f} s",
                 r.increment, increments, piece, r.lambda_end, r.newton.size() - 1, pcg, r.residual_reduction,
                 r.min_scaled_jacobian, r.seconds);
  } else {
    spdlog::warn("increment {}/{}{}: stage {:.4f} rejected: {}", r.increment, increments, piece, r.lambda_end,
                 r.failure);
  }
}

void log_newton_step(const deform::NewtonProgress& p, spdlog::level::level_enum level, bool sliding, double run_seconds) {
  spdlog::log(level, "increment {}/{}{} Newton {}: residual {:.2e} of initial, PCG {}{}{}{}, {:.1f} s (run {:.0f} s)",
              p.step.increment, p.increments, piece_of(p.step.split_depth), p.iteration, p.residual_reduction,
              p.pcg_iterations, p.newton_norm ? " in the Newton norm" : "", p.pcg_converged ? "" : " (not converged)",
              sliding ? fmt::format(", sliding projection {:.2e}", p.max_projection) : "", p.seconds, run_seconds);
}

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
  io::Case c;
  std::optional<geometry::CadModel> cad;
  io::LoadedMesh loaded;
  std::filesystem::path output;
  std::vector<io::InputFingerprint> fingerprints;
  io::OutputFolder folder;  // removed again if the run fails before writing in it
  std::optional<io::Checkpoint> resumed;
  // A restarted run continues from the state a previous run saved (section 4.3).
  std::optional<io::RestartState> previous;
  std::optional<deform::MotionStart> restart;
  RunThreads threads;
};

/// The threads the user asked for: --threads, else the case's solver.threads, else
/// OMP_NUM_THREADS; none (0) lets hotmesh choose.
parallel::ThreadRequest thread_request(const Options& options, const io::Case& c) {
  if (options.threads > 0) return {options.threads, fmt::format("--threads {}", options.threads)};
  if (options.threads < 0 && c.threads > 0) return {c.threads, fmt::format("solver.threads: {}", c.threads)};
  const char* environment = std::getenv("OMP_NUM_THREADS");
  if (const int count = environment ? std::atoi(environment) : 0; count > 0) {
    return {count, fmt::format("OMP_NUM_THREADS={}", environment)};
  }
  return {};
}

/// The threads of the run, from the mesh's size and the cores other processes leave free
/// (measured since the run started), logged with why.
void choose_the_threads(const mesh::Mesh& mesh, RunThreads& threads) {
  threads.inputs.nodes = mesh.node_count();
  threads.inputs.pay_from = mesh.dimension == 2 ? parallel::kThreadsPayNodes2d : parallel::kThreadsPayNodes3d;
  threads.choice = parallel::choose_threads(threads.inputs, [&] { return threads.load.others(); });
  omp_set_num_threads(threads.choice.threads);
  threads.wait = wait_policy();
  spdlog::info("on {} ({}){}", counted(threads.choice.threads, "thread"), threads.choice.reason,
               threads.choice.threads > 1 ? fmt::format("; waiting threads: {}", threads.wait) : "");
}

/// 1. Everything the run needs, read and checked before any work.
void read_inputs(const Options& options, RunState& state, RunInputs& in) {
  in.c = io::read_case(options.case_file);
  const io::Case& c = in.c;
  spdlog::info("case {}", c.file.string());
  const parallel::Processes job = parallel::processes();
  if (job.count > 1 && c.solver.linear == deform::LinearSolverKind::jacobi_pcg) {
    throw InputError::in(c.file.string(), fmt::format("solver.linear: {} runs in one process; with mpirun ({} "
                                                      "processes) use `linear: amg`",
                                                      deform::to_string(c.solver.linear), job.count));
  }
  // The threads before the mesh, while memory is plentiful (hotmesh/mesh/parallel_loops.hpp):
  // as many as the run may use; how many it does use waits for the mesh's size.
  in.threads.inputs.request = thread_request(options, c);
  in.threads.inputs.cores = parallel::machine_cores();
  in.threads.inputs.processes = parallel::local_processes(job.count);
  const int most = in.threads.inputs.request.count > 0
                       ? in.threads.inputs.request.count
                       : std::max(1, in.threads.inputs.cores / in.threads.inputs.processes);
  state.phase = fmt::format("starting {}", counted(most, "thread"));
  mesh::start_threads(most);
  // Every file the case names is checked before any work: the CAD file too, whether or not a
  // patch takes faces from it.
  state.phase = "reading the CAD file";
  in.cad = setup::read_case_cad(c);
  state.phase = "reading the mesh";
  in.loaded = io::read_mesh(c.mesh);
  const mesh::Mesh& mesh = in.loaded.mesh;
  state.nodes = mesh.node_count();
  state.cells = mesh.cell_count();
  spdlog::info("mesh {}: {} nodes, {} cells", c.mesh.string(), mesh.node_count(), mesh.cell_count());
  choose_the_threads(mesh, in.threads);
  io::check_case_against_mesh(c, mesh);
  check_foam_time(options, c);
  in.output = options.output.empty() ? c.output : std::filesystem::path(options.output);
  state.phase = "checking the inputs";
  in.fingerprints = io::input_fingerprints(c);
  in.resumed = prepare_output(options, c, in.loaded, in.output, in.fingerprints, in.folder);
  if (c.restart) {
    in.previous = io::read_restart(*c.restart, mesh);
    in.restart = deform::MotionStart{in.previous->points, in.previous->sliding};
    spdlog::info("restarting from {} ({} sliding nodes)", c.restart->string(), in.previous->sliding.size());
  }
}

/// 3. The motion, increment by increment, with a checkpoint after each.
deform::MotionResult move_the_mesh(const Options& options, RunState& state, const RunInputs& in, const setup::CaseSetup& setup,
                                   CheckpointWriter& checkpoints, SeriesWriter* series, Clock::time_point start) {
  const io::Case& c = in.c;
  const mesh::Mesh& mesh = in.loaded.mesh;
  const parallel::Processes job = parallel::processes();
  const int increments = c.solver.increments;
  const deform::LinearSolverChoice linear = linear_solver_of(c, mesh, setup);
  deform::SolverOptions solver = c.solver;
  solver.linear = linear.kind;
  solver.quality.layer = in.loaded.layer;
  if (in.resumed) {
    const io::CheckpointInfo& info = in.resumed->info;
    spdlog::info("resuming from {} (written {}): {} of {} increments done, stage {:.4f}; on {}",
                 checkpoints.path().string(), info.written_at, info.finished_increments, info.increments, info.lambda,
                 counted(omp_get_max_threads(), "thread"));
  } else {
    spdlog::info("moving the mesh in {} increments on {}{}, linear solver {}{} ({}{})", increments,
                 job.count > 1 ? fmt::format("{} processes of ", job.count) : "", counted(omp_get_max_threads(), "thread"),
                 deform::to_string(linear.kind),
                 linear.kind == deform::LinearSolverKind::amg ? fmt::format(" with {}", deform::to_string(c.solver.amg)) : "",
                 c.solver.linear == deform::LinearSolverKind::automatic ? "auto: " : "", linear.reason);
  }
  const bool sliding = std::any_of(setup.motions.begin(), setup.motions.end(),
                                   [](const deform::PatchMotion& m) { return m.role == deform::BoundaryRole::sliding; });
  const auto newton_level =
      options.progress || mesh.cell_count() >= kProgressCells ? spdlog::level::info : spdlog::level::debug;
  deform::MotionObservers observers;
  observers.increment = [increments](const deform::IncrementRecord& r) { log_increment(r, increments); };
  observers.newton = [&](const deform::NewtonProgress& p) {
    state.phase = fmt::format("moving the mesh (increment {} of {})", p.step.increment, increments);
    log_newton_step(p, newton_level, sliding, seconds_since(start));
  };
  observers.checkpoint = [&](const deform::MotionCheckpoint& k) {
    // The series step first: a run that stops after its checkpoint has it too.
    if (series) series->add(k.lambda * increments, k.lambda, k.points);
    if (job.root()) checkpoints.write(k);  // before rank 0 joins the others in the next step
    state.checkpoint_increments = k.finished_increments;
  };
  state.phase = "moving the mesh";
  try {
    return deform::move_mesh(mesh, setup.motions, c.material, solver, observers, in.restart ? &*in.restart : nullptr,
                             in.resumed ? &in.resumed->state : nullptr, parallel::job_exchange());
  } catch (const deform::FreeRigidMotion& e) {  // the roles as a whole: the case's `patches:`
    throw InputError::at(c.file.string(), c.patches_line, fmt::format("patches: {}", e.what()));
  }
}

/// 4. Outputs, each written atomically; on failure the last valid mesh. Every rank holds the
/// same result: rank 0 writes it. The exit code.
int write_run_outputs(const RunInputs& in, const setup::CaseSetup& setup, const deform::MotionResult& result,
                      const Options& options, CheckpointWriter& checkpoints, RunTimings& timings,
                      const io::CheckpointInfo* resumed_from, Clock::time_point start) {
  const io::Case& c = in.c;
  const mesh::Mesh& mesh = in.loaded.mesh;
  const std::filesystem::path& output = in.output;
  const auto t = Clock::now();
  io::WriteBackOptions write_back;
  if (!options.foam_time.empty()) write_back.foam_time = options.foam_time;
  const mesh::SolverQuality solver = mesh::solver_quality(mesh, result.points, in.loaded.layer);
  RunOutputs outputs = write_outputs(output, c, in.loaded, setup, result, solver, options.binary, write_back);
  if (result.success) {  // the state the next coupling iteration restarts from
    io::write_restart(output / "restart.hmr", io::restart_state(c, mesh, result));
    outputs.files.push_back(output / "restart.hmr");
  }
  timings.write = seconds_since(t);
  timings.checkpoints = checkpoints.written();
  timings.checkpoint = checkpoints.seconds();
  timings.checkpoint_bytes = checkpoints.bytes();
  timings.wall = seconds_since(start);
  write_report(output, c, in.loaded, setup, result, solver, timings, in.threads, outputs, resumed_from);
  checkpoints.remove();  // the run has ended: the outputs supersede it

  if (!result.success) {
    spdlog::error("{}", result.message);
    const bool residual = !result.failure.residual.empty();
    spdlog::error("kept the last valid mesh (stage {:.4f}) in {}; failed.vtu holds the failed attempt ({}{})",
                  result.lambda_reached, output.string(), failure_text(result.failure),
                  residual ? "; its point data newton_residual shows where" : "");
    return 1;
  }
  const mesh::SolverQualitySummary& measured = solver.summary;
  spdlog::info("done in {:.2f} s: min scaled Jacobian {:.3f}; as a flow solver sees the cells: max non-orthogonality "
               "{:.1f} deg (average {:.1f}, {} faces over {:.0f}), max skewness {:.2f}, volume ratio {:.3g}, aspect ratio "
               "{:.3g}; outputs in {}",
               timings.wall, result.summary.min_scaled_jacobian, measured.max_non_orthogonality.value,
               measured.mean_non_orthogonality, measured.severely_non_orthogonal_faces, mesh::kSevereNonOrthogonality,
               measured.max_skewness.value, measured.max_volume_ratio.value, measured.max_aspect_ratio.value,
               output.string());
  return 0;
}

/// How far each moving wall of the mesh was from its undeformed wall before the motion put it
/// on it, and the corners the sliding walls' nodes hold.
void log_walls(const mesh::Mesh& mesh, const deform::MotionResult& result) {
  for (const deform::WallGap& gap : result.wall_gaps) {
    if (gap.node < 0) continue;
    const geometry::Vec3& x = mesh.points[static_cast<std::size_t>(gap.node)];
    spdlog::info("patch {}: its nodes lay within {:.3g} of its undeformed wall before the motion put them on it (the "
                 "farthest: node {} at ({:.6g}, {:.6g}, {:.6g}))",
                 gap.patch, gap.distance, mesh.node_id(gap.node), x.x, x.y, x.z);
  }
  std::map<std::string, std::array<std::size_t, 4>> held;  // corners from the start, by the pass; creases likewise
  for (const deform::WallFeature& f : result.features) {
    ++held[f.patch][(f.faces.empty() ? 0u : 2u) + (f.from_start ? 0u : 1u)];
  }
  for (const auto& [patch, counts] : held) {
    spdlog::info("patch {}: {} corners and {} creases held from the start by the nodes on them, {} corners and {} "
                 "creases given nodes by the corner pass",
                 patch, counts[0], counts[2], counts[1], counts[3]);
  }
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
  const setup::CaseSetup setup = setup::set_up_case(in.c, in.loaded.mesh, in.previous ? &*in.previous : nullptr,
                                              in.cad ? &*in.cad : nullptr);
  for (const auto& s : setup.shapes) {
    spdlog::info("patch {}: deflected shape through {} FEM nodes (degree {})", s.patch, s.reconstruction.used_nodes,
                 s.reconstruction.degree);
  }
  timings.shapes = seconds_since(t);

  CheckpointWriter checkpoints(in.output / io::kCheckpointName, in.c, in.loaded.mesh, std::move(in.fingerprints));
  state.checkpoint = checkpoints.path();
  if (in.resumed) state.checkpoint_increments = in.resumed->info.finished_increments;
  std::optional<SeriesWriter> series;
  if ((options.series || in.c.series) && parallel::processes().root()) {
    const int n = in.c.solver.increments;
    if (in.resumed) {
      series.emplace(in.output, in.loaded.mesh, in.loaded.layer, setup.motions, in.resumed->state.lambda * n);
    } else {
      series.emplace(in.output, in.loaded.mesh, in.loaded.layer, setup.motions);
      series->add(0.0, 0.0, in.restart ? std::span<const geometry::Vec3>(in.restart->points) : in.loaded.mesh.points);
    }
  }
  const deform::MotionResult result =
      move_the_mesh(options, state, in, setup, checkpoints, series ? &*series : nullptr, start);
  if (series && result.success && std::any_of(result.increments.begin(), result.increments.end(), [](const auto& r) {
        return r.corner_pass && r.accepted;
      })) {
    series->add(in.c.solver.increments + 1.0, 1.0, result.points);  // after the corner pass
  }
  const std::optional<io::CheckpointInfo> resumed_from = in.resumed ? std::optional(in.resumed->info) : std::nullopt;
  in.resumed.reset();  // its copy of the mesh is no longer needed
  log_walls(in.loaded.mesh, result);
  for (const auto& note : result.notes) spdlog::warn("{}", note);
  if (const auto& repair = result.corner_repair; repair.cells_below > 0) {
    spdlog::info("corner pass: {} cells below the motion's worst cell; {} interior nodes moved, worst cell {:.3f} -> {:.3f}",
                 repair.cells_below, repair.nodes_moved, repair.min_before, repair.min_after);
  }
  const auto& m = result.timings;
  spdlog::info("motion {:.2f} s: assembly {:.2f} s, preconditioner {:.2f} s, solve {:.2f} s, projection {:.2f} s",
               m.total, m.assembly, m.preconditioner, m.solve, m.projection);

  state.phase = "writing the outputs";
  std::array<double, 1> memory{static_cast<double>(peak_memory_bytes())};
  parallel::job_exchange().sum(memory);  // every rank: the job's memory for rank 0's report
  timings.peak_memory_all_ranks = static_cast<std::uint64_t>(memory[0]);
  if (!parallel::processes().root()) return result.success ? 0 : 1;
  return write_run_outputs(in, setup, result, options, checkpoints, timings, resumed_from ? &*resumed_from : nullptr,
                           start);
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
