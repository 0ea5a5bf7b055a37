// hotmesh deform CASE.yaml [-o DIR] [--threads N] [--force] [--binary]: the main job. Reads and
// validates everything first, moves the mesh increment by increment, and writes the deformed
// mesh (.msh, .vtu), pictures for 2D meshes, report.json and restart.hmr (the state the next
// coupling iteration continues from) to the output folder. If the motion fails it keeps the
// last valid mesh, writes failed.vtu marking the failed cells and exits with code 1.
#include <CLI/CLI.hpp>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "deform_outputs.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/case_setup.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/io/output_folder.hpp"
#include "hotmesh/io/restart_file.hpp"

namespace hotmesh::app {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void log_increment(const deform::IncrementRecord& r, int increments) {
  std::string pcg;
  for (std::size_t i = 0; i + 1 < r.newton.size(); ++i) pcg += fmt::format("{}{}", i ? "+" : "", r.newton[i].pcg_iterations);
  const std::string piece = r.split_depth > 0 ? fmt::format(" (1/{} piece)", 1 << r.split_depth) : "";
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

}  // namespace

Command add_deform_command(CLI::App& parent) {
  struct Options {
    std::string case_file;
    std::string output;
    int threads = -1;
    bool force = false;
    bool binary = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand("deform", "Deform a mesh as a case file describes (the main job)");
  cmd->add_option("CASE", options->case_file, "Case file (.yaml), see docs/case-file.md")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", options->output, "Output folder (default: the case's `output`)");
  cmd->add_option("--threads", options->threads, "OpenMP threads (default: the case's solver.threads; 0: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--force", options->force, "Write into the output folder even if it holds input files");
  cmd->add_flag("--binary", options->binary, "Write deformed.msh in binary (smaller, faster for large meshes)");
  return [options] {
    const auto start = Clock::now();
    RunTimings timings;

    // 1. Everything the run needs is read and checked before any work.
    auto t = Clock::now();
    const io::Case c = io::read_case(options->case_file);
    spdlog::info("case {}", c.file.string());
    io::LoadedMesh loaded = io::read_mesh(c.mesh);
    const deform::Mesh& mesh = loaded.mesh;
    spdlog::info("mesh {}: {} nodes, {} cells", c.mesh.string(), mesh.node_count(), mesh.cell_count());
    io::check_case_against_mesh(c, mesh);
    const std::filesystem::path output = options->output.empty() ? c.output : std::filesystem::path(options->output);
    const auto inputs = c.inputs();
    io::prepare_output_folder(output, inputs, options->force);
    for (const auto& name : output_names(c, mesh)) io::refuse_overwriting_input(output / name, inputs);
    const int threads = options->threads >= 0 ? options->threads : c.solver.threads;
    if (threads > 0) omp_set_num_threads(threads);

    // A restarted run continues from the state a previous run saved (section 4.3).
    std::optional<io::RestartState> previous;
    std::optional<deform::MotionStart> resume;
    if (c.restart) {
      previous = io::read_restart(*c.restart, mesh);
      resume = deform::MotionStart{previous->points, previous->sliding};
      spdlog::info("restarting from {} ({} sliding nodes)", c.restart->string(), previous->sliding.size());
    }
    timings.read = seconds_since(t);

    // 2. The deflected shapes, from the FEM tables (section 4.2).
    t = Clock::now();
    const io::CaseSetup setup = io::set_up_case(c, mesh, previous ? &*previous : nullptr);
    for (const auto& s : setup.shapes) {
      spdlog::info("patch {}: deflected shape through {} FEM nodes (degree {})", s.patch, s.reconstruction.used_nodes,
                   s.reconstruction.degree);
    }
    timings.shapes = seconds_since(t);

    // 3. The motion, increment by increment.
    spdlog::info("moving the mesh in {} increments on {} threads, linear solver {}{}", c.solver.increments,
                 omp_get_max_threads(), deform::to_string(c.solver.linear),
                 c.solver.linear == deform::LinearSolverKind::amg ? fmt::format(" ({})", deform::to_string(c.solver.amg)) : "");
    const deform::MotionResult result = deform::move_mesh(
        mesh, setup.motions, c.material, c.solver,
        [&c](const deform::IncrementRecord& r) { log_increment(r, c.solver.increments); }, resume ? &*resume : nullptr);
    for (const auto& note : result.notes) spdlog::warn("{}", note);
    const auto& m = result.timings;
    spdlog::info("motion {:.2f} s: assembly {:.2f} s, preconditioner {:.2f} s, solve {:.2f} s, projection {:.2f} s",
                 m.total, m.assembly, m.preconditioner, m.solve, m.projection);

    // 4. Outputs, each written atomically; on failure the last valid mesh.
    t = Clock::now();
    RunOutputs outputs = write_outputs(output, c, mesh, setup, result, options->binary);
    if (result.success) {  // the state the next coupling iteration restarts from
      io::write_restart(output / "restart.hmr", io::restart_state(c, mesh, result));
      outputs.files.push_back(output / "restart.hmr");
    }
    timings.write = seconds_since(t);
    timings.wall = seconds_since(start);
    write_report(output, c, loaded, setup, result, timings, outputs);

    if (!result.success) {
      spdlog::error("{}", result.message);
      spdlog::error("kept the last valid mesh (stage {:.4f}) in {}; failed.vtu marks the failed cells",
                    result.lambda_reached, output.string());
      return 1;
    }
    spdlog::info("done in {:.2f} s: min scaled Jacobian {:.3f}, outputs in {}", timings.wall,
                 result.summary.min_scaled_jacobian, output.string());
    return 0;
  };
}

}  // namespace hotmesh::app
