// hotmesh info MESH [--json]: counts, patches and a quality summary of a mesh; for a CGNS
// file also its bases, zones, sections, BCs, connections and families.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "reports/cgns_summary.hpp"
#include "cli/commands.hpp"
#include "hotmesh/api/mesh_summary.hpp"

namespace hotmesh::app {

// The reports and checks of the library's run layer (api/).
using namespace hotmesh::api;  // NOLINT(google-build-using-namespace)

Command add_info_command(CLI::App& parent) {
  struct Options {
    std::string mesh;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand("info", "Show counts, patches and cell quality of a mesh");
  cmd->add_option("MESH", options->mesh, "Mesh file (.msh, .cgns) or OpenFOAM case / polyMesh folder")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_flag("--json", options->json, "Print the summary as JSON");
  return [options] {
    const io::LoadedMesh loaded = io::read_mesh(options->mesh);
    nlohmann::json summary = mesh_summary(loaded, options->mesh);
    std::string text = mesh_summary_text(summary);
    if (io::mesh_format(options->mesh) == io::MeshFormat::cgns) {
      summary["cgns"] = cgns_summary_json(io::describe_cgns(options->mesh));
      text += cgns_summary_text(summary["cgns"]);
    }
    std::cout << (options->json ? summary.dump(2) + "\n" : text);
    return 0;
  };
}

}  // namespace hotmesh::app
