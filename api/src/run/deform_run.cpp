// hotmesh api: the steps of a `hotmesh deform` run that the command and the library share (see deform_run.hpp).
#include "hotmesh/api/deform_run.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/io/restart_file.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"
#include "hotmesh/parallel/processes.hpp"

namespace hotmesh::api {
namespace {

/// From this size on, every Newton step is logged at info level (else at debug, -v): a step
/// then takes seconds to minutes, and a user wants to see the run is alive.
constexpr std::size_t kProgressCells = 100'000;

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

/// The threads of the run, from the mesh's size and the cores other processes leave free
/// (measured since the run started), logged with why.
void choose_the_threads(const mesh::Mesh& mesh, RunThreads& threads) {
  threads.inputs.nodes = mesh.node_count();
  threads.inputs.pay_from = mesh.dimension == 2 ? parallel::kThreadsPayNodes2d : parallel::kThreadsPayNodes3d;
  threads.choice = parallel::choose_threads(threads.inputs, [&] { return threads.load.others(); });
  omp_set_num_threads(threads.choice.threads);
  spdlog::info("on {} ({}){}", counted(threads.choice.threads, "thread"), threads.choice.reason,
               threads.choice.threads > 1 ? fmt::format("; waiting threads: {}", threads.wait) : "");
}

/// Logs how the motion starts: resumed from a checkpoint, or from the start with its solver.
void log_motion_start(const LoadedCase& in, const MotionSettings& settings, const deform::LinearSolverChoice& linear) {
  const io::Case& c = in.c;
  if (settings.resumed) {
    const io::CheckpointInfo& info = settings.resumed->info;
    spdlog::info("resuming from {} (written {}): {} of {} increments done, stage {:.4f}; on {}",
                 settings.checkpoint_path.string(), info.written_at, info.finished_increments, info.increments,
                 info.lambda, counted(omp_get_max_threads(), "thread"));
    return;
  }
  const parallel::Processes job = parallel::processes();
  spdlog::info("moving the mesh in {} increments on {}{}, linear solver {}{} ({}{})", c.solver.increments,
               job.count > 1 ? fmt::format("{} processes of ", job.count) : "", counted(omp_get_max_threads(), "thread"),
               deform::to_string(linear.kind),
               linear.kind == deform::LinearSolverKind::amg ? fmt::format(" with {}", deform::to_string(c.solver.amg)) : "",
               c.solver.linear == deform::LinearSolverKind::automatic ? "auto: " : "", linear.reason);
}

}  // namespace

parallel::ThreadRequest thread_request(int threads, const char* option, const io::Case& c) {
  if (threads > 0) return {threads, fmt::format("{} {}", option, threads)};
  if (threads < 0 && c.threads > 0) return {c.threads, fmt::format("solver.threads: {}", c.threads)};
  const char* environment = std::getenv("OMP_NUM_THREADS");
  if (const int count = environment ? std::atoi(environment) : 0; count > 0) {
    return {count, fmt::format("OMP_NUM_THREADS={}", environment)};
  }
  return {};
}

void load_case(LoadedCase& in, const parallel::ThreadRequest& request, RunState& state) {
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
  in.threads.inputs.request = request;
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
}

setup::CaseSetup set_up_shapes(const LoadedCase& in, const io::RestartState* previous) {
  setup::CaseSetup setup = setup::set_up_case(in.c, in.loaded.mesh, previous, in.cad ? &*in.cad : nullptr);
  for (const auto& s : setup.shapes) {
    spdlog::info("patch {}: deflected shape through {} FEM nodes (degree {})", s.patch, s.reconstruction.used_nodes,
                 s.reconstruction.degree);
  }
  return setup;
}

deform::MotionResult move_the_mesh(const LoadedCase& in, const setup::CaseSetup& setup, const MotionSettings& settings,
                                   RunState& state, Clock::time_point start) {
  const io::Case& c = in.c;
  const mesh::Mesh& mesh = in.loaded.mesh;
  const int increments = c.solver.increments;
  const deform::LinearSolverChoice linear = linear_solver_of(c, mesh, setup);
  deform::SolverOptions solver = c.solver;
  solver.linear = linear.kind;
  solver.quality.layer = in.loaded.layer;
  log_motion_start(in, settings, linear);
  const bool sliding = std::any_of(setup.motions.begin(), setup.motions.end(),
                                   [](const deform::PatchMotion& m) { return m.role == deform::BoundaryRole::sliding; });
  const auto newton_level =
      settings.progress || mesh.cell_count() >= kProgressCells ? spdlog::level::info : spdlog::level::debug;
  deform::MotionObservers observers;
  observers.increment = [&](const deform::IncrementRecord& r) {
    log_increment(r, increments);
    if (settings.increment) settings.increment(r);
  };
  observers.newton = [&](const deform::NewtonProgress& p) {
    state.phase = fmt::format("moving the mesh (increment {} of {})", p.step.increment, increments);
    log_newton_step(p, newton_level, sliding, seconds_since(start));
    if (settings.newton) settings.newton(p);
  };
  if (settings.checkpoint) observers.checkpoint = settings.checkpoint;
  state.phase = "moving the mesh";
  try {
    return deform::move_mesh(mesh, setup.motions, c.material, solver, observers, settings.restart,
                             settings.resumed ? &settings.resumed->state : nullptr, parallel::job_exchange());
  } catch (const deform::FreeRigidMotion& e) {  // the roles as a whole: the case's `patches:`
    throw InputError::at(c.file.string(), c.patches_line, fmt::format("patches: {}", e.what()));
  }
}

void log_motion(const mesh::Mesh& mesh, const deform::MotionResult& result) {
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
  for (const auto& note : result.notes) spdlog::warn("{}", note);
  if (const auto& repair = result.corner_repair; repair.cells_below > 0) {
    spdlog::info("corner pass: {} cells below the motion's worst cell; {} interior nodes moved, worst cell {:.3f} -> {:.3f}",
                 repair.cells_below, repair.nodes_moved, repair.min_before, repair.min_after);
  }
  const auto& m = result.timings;
  spdlog::info("motion {:.2f} s: assembly {:.2f} s, preconditioner {:.2f} s, solve {:.2f} s, projection {:.2f} s",
               m.total, m.assembly, m.preconditioner, m.solve, m.projection);
}

int write_run_outputs(const std::filesystem::path& folder, const io::Case& c, const LoadedCase& in,
                      const setup::CaseSetup& setup, const deform::MotionResult& result,
                      const OutputSettings& settings, RunTimings& timings, Clock::time_point start) {
  const mesh::Mesh& mesh = in.loaded.mesh;
  const auto t = Clock::now();
  const mesh::SolverQuality solver = mesh::solver_quality(mesh, result.points, in.loaded.layer);
  RunOutputs outputs = write_outputs(folder, c, in.loaded, setup, result, solver, settings.binary_msh, settings.write_back);
  if (result.success) {  // the state the next coupling iteration restarts from
    io::write_restart(folder / "restart.hmr", io::restart_state(c, mesh, result));
    outputs.files.push_back(folder / "restart.hmr");
  }
  timings.write = seconds_since(t);
  if (settings.checkpoints) {
    timings.checkpoints = settings.checkpoints->written();
    timings.checkpoint = settings.checkpoints->seconds();
    timings.checkpoint_bytes = settings.checkpoints->bytes();
  }
  timings.wall = seconds_since(start);
  write_report(folder, c, in.loaded, setup, result, solver, timings, in.threads, outputs, settings.resumed_from);
  if (settings.checkpoints) settings.checkpoints->remove();  // the run has ended: the outputs supersede it

  if (!result.success) {
    spdlog::error("{}", result.message);
    const bool residual = !result.failure.residual.empty();
    spdlog::error("kept the last valid mesh (stage {:.4f}) in {}; failed.vtu holds the failed attempt ({}{})",
                  result.lambda_reached, folder.string(), failure_text(result.failure),
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
               folder.string());
  return 0;
}

}  // namespace hotmesh::api
