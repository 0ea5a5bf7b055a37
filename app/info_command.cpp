// hotmesh info MESH [--json]: counts, patches and a quality summary of a mesh.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mesh_summary.hpp"

namespace hotmesh::app {

Command add_info_command(CLI::App& parent) {
  struct Options {
    std::string mesh;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand("info", "Show counts, patches and cell quality of a mesh");
  cmd->add_option("MESH", options->mesh, "Mesh file (.msh) or OpenFOAM case / polyMesh folder")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_flag("--json", options->json, "Print the summary as JSON");
  return [options] {
    const io::LoadedMesh loaded = io::read_mesh(options->mesh);
    const nlohmann::json summary = mesh_summary(loaded, options->mesh);
    std::cout << (options->json ? summary.dump(2) + "\n" : mesh_summary_text(summary));
    return 0;
  };
}

}  // namespace hotmesh::app
