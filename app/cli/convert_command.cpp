// hotmesh convert IN OUT: re-write a mesh in another format (.msh, .cgns or an OpenFOAM folder ->
// .msh 4.1, .cgns, .vtu or a new OpenFOAM polyMesh folder).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <array>
#include <memory>
#include <vector>

#include "cli/commands.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/io/output_folder.hpp"

namespace hotmesh::app {

Command add_convert_command(CLI::App& parent) {
  struct Options {
    std::string input;
    std::string output;
    bool binary = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(
      "convert",
      "Convert a mesh: Gmsh 2.2/4.1 (.msh), CGNS (.cgns) or OpenFOAM (a case or polyMesh folder) to Gmsh 4.1 (.msh), "
      "CGNS (.cgns: one unstructured zone), OpenFOAM (a folder named polyMesh, or a case folder: 3D meshes) or "
      "ParaView (.vtu with cell quality)");
  cmd->add_option("IN", options->input, "Input mesh (.msh, .cgns, or an OpenFOAM case / polyMesh folder)")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("OUT", options->output, "Output mesh (.msh, .cgns, .vtu, or .../polyMesh or a case folder for OpenFOAM); never the input")->required();
  cmd->add_flag("--binary", options->binary, "Write .msh or OpenFOAM files in binary (smaller, faster for large meshes)");
  return [options] {
    const std::array<std::filesystem::path, 1> input{options->input};
    io::refuse_overwriting_input(options->output, input);
    if (io::mesh_format(options->output) == io::MeshFormat::foam) {  // a polyMesh folder's files
      const std::vector<std::filesystem::path> inputs = io::mesh_input_files(options->input);
      const std::filesystem::path folder = io::foam_output_folder(options->output);
      for (const char* name : {"points", "faces", "owner", "neighbour", "boundary"}) {
        io::refuse_overwriting_input(folder / name, inputs);
      }
    }
    const io::LoadedMesh loaded = io::read_mesh(options->input);
    const auto& mesh = loaded.mesh;
    if (io::mesh_format(options->output) == io::MeshFormat::gmsh) {
      io::write_gmsh(options->output, mesh, {.binary = options->binary});
    } else if (io::mesh_format(options->output) == io::MeshFormat::foam) {
      io::write_foam(options->output, mesh, mesh.points, {.binary = options->binary});
    } else {
      io::write_mesh(options->output, mesh, mesh.points, io::quality_fields(mesh, mesh.points, loaded.layer));
    }
    spdlog::info("wrote {} ({} nodes, {} cells)", options->output, mesh.node_count(), mesh.cell_count());
    return 0;
  };
}

}  // namespace hotmesh::app
