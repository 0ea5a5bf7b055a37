// hotmesh app: the subcommands of the command line. Each add_*_command registers its
// options on the parent and returns the function that runs it once the line is parsed.
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace hotmesh::app {

/// Runs a parsed subcommand; returns the process exit code. User errors are thrown as
/// hotmesh::InputError (exit code 2), failures of the work itself return 1.
using Command = std::function<int()>;

/// Exit code when memory runs out (std::bad_alloc): neither bad input (2) nor a bug (3).
inline constexpr int kExitOutOfMemory = 4;

Command add_info_command(CLI::App& parent);
Command add_convert_command(CLI::App& parent);
Command add_deform_command(CLI::App& parent);
Command add_cad_command(CLI::App& parent);
Command add_curve_command(CLI::App& parent);
Command add_surface_command(CLI::App& parent);
Command add_serve_command(CLI::App& parent);
Command add_check_command(CLI::App& parent);
Command add_fem_command(CLI::App& parent);

}  // namespace hotmesh::app
