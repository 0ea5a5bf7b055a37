// hotmesh surface: section 4.2 on CAD faces of any shape on its own (issue 23, item 3), as
// `hotmesh curve` is for curves. Reads the faces of a CAD file and a cartesian table of FEM nodes,
// reconstructs the deflection field d(t, s) of each face and writes the deformed faces S + d for
// CAD systems, the nodes and faces for ParaView, a picture of the residuals over (t, s) and a
// summary to a folder.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <memory>

#include "cli/commands.hpp"
#include "hotmesh/setup/face_fit.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "fits/node_fit.hpp"
#include "fits/surface_outputs.hpp"

namespace hotmesh::app {

namespace {

struct Options {
  std::string cad;
  std::vector<int> faces;
  NodeFitOptions fit;
  std::size_t samples = SurfaceOutputOptions{}.samples;
};

int run_surface(const Options& o) {
  geometry::CadReadOptions read;
  read.unit = parse_unit_option(o.fit.unit);
  const geometry::DeflectionSamples samples = io::read_deflection_csv(o.fit.fem);
  const geometry::CadModel model = geometry::CadModel::read(o.cad, read);
  const setup::SurfaceRun run = setup::fit_on_cad_faces(model, o.faces, samples, reconstruction_options(o.fit));

  // The folder is made only once the inputs have been read and the fields fitted.
  const std::vector<std::filesystem::path> inputs{o.fit.fem, o.cad};
  const io::OutputFolder folder_guard = prepare_fit_folder(o.fit, inputs, kSurfaceFiles);
  const std::filesystem::path folder(o.fit.output);
  const geometry::SurfaceReconstructionReport& report = run.fit.report;
  warn_dropped_nodes(o.fit, report.rejected_nodes, report.tolerance, "the CAD faces");
  SurfaceOutputOptions outputs;
  outputs.samples = o.samples;
  const nlohmann::json summary = write_surface_outputs(folder, run, outputs);
  for (const nlohmann::json& face : summary["faces"]) {
    spdlog::info("face {}: {} nodes, {} ({} x {} poles), max residual {:.3g}; deformed face {}",
                 face["id"].get<int>(), face["nodes"].get<std::size_t>(), face["method"].get<std::string>(),
                 face["poles"][0].get<std::size_t>(), face["poles"][1].get<std::size_t>(),
                 face["max_residual"].get<double>(),
                 face["exact"].get<bool>()
                     ? std::string("exact")
                     : fmt::format("interpolated, within {:.3g}", face["max_deviation"].get<double>()));
  }
  spdlog::info("{} nodes ({} used), degree {}: max node distance to the faces {:.3g}, residual {:.3g}, edge gap {:.3g} "
               "({} of {} shared edges joined)",
               report.nodes, report.used_nodes, report.degree, report.max_node_distance_to_cad,
               report.max_node_residual, report.max_edge_gap, report.joined_edges, report.shared_edges);
  spdlog::info("wrote {}: {}", folder.string(), fmt::join(kSurfaceFiles, ", "));
  return 0;
}

}  // namespace

Command add_surface_command(CLI::App& parent) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(
      "surface", "Reconstruct the deflection of CAD faces of any shape from FEM nodes and write the deformed faces");
  cmd->add_option("--cad", options->cad, "CAD file of the faces (.step, .stp, .iges, .igs)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--faces", options->faces, "Ids of the faces, e.g. 3,4 (see 'hotmesh cad')")
      ->required()
      ->delimiter(',');
  add_node_fit_options(*cmd, options->fit, "FEM nodes and deflections (CSV: x,y,z,dx,dy,dz)",
                       "Degree q of the deflection surface d(t, s) of each face", "the CAD faces");
  cmd->add_option("--samples", options->samples, "Grid intervals per direction of each face in faces.vtp")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  add_output_options(*cmd, options->fit);
  return [options] { return run_surface(*options); };
}

}  // namespace hotmesh::app
