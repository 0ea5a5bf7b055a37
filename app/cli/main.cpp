// hotmesh: command line entry point. Parses the command line, sets up logging and turns
// errors into exit codes: 0 success, 1 the work failed, 2 bad input (files, case keys,
// options), 3 internal error, 4 out of memory (the exit code of mpirun too).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <chrono>
#include <exception>
#include <new>
#include <thread>
#include <vector>

#include "cli/commands.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/parallel/processes.hpp"
#include "cli/logging.hpp"
#include "cli/passive_wait.hpp"

// In `hotmesh deform`, waiting OpenMP threads sleep (OMP_WAIT_POLICY=passive) unless the user
// says otherwise: the program starts itself again so, before libgomp reads its environment as
// it is loaded (passive_wait.hpp). Here, in the program's own file, and in no library: only
// the hotmesh program does this, never a test, a benchmark or a program built on the libraries.
[[gnu::section(".preinit_array"), gnu::used]] static void (*const preinit_wait_passively)(int, char**, char**) =
    &hotmesh::app::restart_waiting_passively;

int main(int argc, char** argv) {
  hotmesh::parallel::restore_malloc_defaults();
  CLI::App app{"hotmesh: moves a CFD mesh onto the hot running geometry computed by an FEM code.\n"
               "Run 'hotmesh <command> --help' for the options of a command."};
  app.set_version_flag("--version", HOTMESH_VERSION);
  app.require_subcommand(1);
  // The global options are taken after the command too (`hotmesh deform case.yaml -q`): an
  // option a command does not know falls through to here. Every command inherits this.
  app.fallthrough();
  int verbose = 0;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbose, "More log output on stderr (-vv: trace)");
  app.add_flag("-q,--quiet", quiet, "Only warnings and errors on stderr");

  using Entry = std::pair<CLI::App*, hotmesh::app::Command>;
  std::vector<Entry> commands;
  auto remember = [&](hotmesh::app::Command run) { commands.emplace_back(app.get_subcommands({}).back(), std::move(run)); };
  remember(hotmesh::app::add_info_command(app));
  remember(hotmesh::app::add_convert_command(app));
  remember(hotmesh::app::add_deform_command(app));
  remember(hotmesh::app::add_cad_command(app));
  remember(hotmesh::app::add_curve_command(app));
  remember(hotmesh::app::add_surface_command(app));
  remember(hotmesh::app::add_check_command(app));
  remember(hotmesh::app::add_fem_command(app));
  remember(hotmesh::app::add_serve_command(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  hotmesh::app::configure_logging(quiet ? -1 : verbose);

  // Several processes of an MPI job (hotmesh deform under mpirun) end together: a rank that
  // stops alone would leave the others waiting for it. A bad input stops every rank at the
  // same place: rank 0 reports it.
  const auto finish = [](int code) {
    if (hotmesh::parallel::processes().count > 1 && code > 1) hotmesh::parallel::abort_processes(code);
    return code;
  };
  try {
    for (auto& [sub, run] : commands) {
      if (sub->parsed()) return finish(run());
    }
    return 2;
  } catch (const hotmesh::InputError& e) {
    if (hotmesh::parallel::processes().root()) spdlog::error("{}", e.what());
    else std::this_thread::sleep_for(std::chrono::seconds(2));  // rank 0 reports, and ends the job
    return finish(2);
  } catch (const std::bad_alloc&) {
    spdlog::error("out of memory: this machine (or its limits for this process) cannot hold the job");
    return finish(hotmesh::app::kExitOutOfMemory);
  } catch (const std::exception& e) {
    spdlog::critical("internal error: {} (please report this with the command line and input files)", e.what());
    return finish(3);
  }
}
