// hotmesh curve: section 4.2 on its own. Reads FEM boundary nodes with their deflections and
// the boundary's CAD faces (or, for 2D cases, only the nodes), reconstructs the deflected
// curve (eq. 21) and writes it with the undeformed one, a picture and a summary to a folder.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <array>
#include <memory>
#include <stdexcept>

#include "cli/commands.hpp"
#include "hotmesh/setup/curve_fit.hpp"
#include "fits/curve_outputs.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "fits/node_fit.hpp"

namespace hotmesh::app {

namespace {

struct Options {
  std::string cad;
  std::vector<int> faces;
  std::vector<double> axis;
  NodeFitOptions fit;
  std::string form = "curve";
  std::size_t samples = 2000;
  double amplification = 0.0;
};

std::optional<geometry::Axis> axis_option(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  if (values.size() != 6) {
    throw InputError("--axis needs six numbers ox,oy,oz,dx,dy,dz, got " + std::to_string(values.size()));
  }
  try {
    return geometry::Axis({values[0], values[1], values[2]}, {values[3], values[4], values[5]});
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--axis: ") + e.what());
  }
}

/// With CAD faces: their meridional curve r(t), the nodes in (r, z) about its axis.
setup::CurveRun with_cad(const Options& o, const geometry::DeflectionSamples& samples,
                  const geometry::ReconstructionOptions& reconstruction) {
  if (o.faces.empty()) throw InputError("--cad needs --faces: the ids of the boundary's faces (see 'hotmesh cad')");
  setup::require_cad_frame(samples);
  const std::optional<geometry::Axis> axis = axis_option(o.axis);
  if (samples.frame == geometry::SampleFrame::meridional && !axis) {
    throw InputError::in(samples.source, "meridional (r, z) nodes need --axis: z is measured from the axis origin");
  }
  geometry::CadReadOptions read;
  read.unit = parse_unit_option(o.fit.unit);
  const geometry::CadModel model = geometry::CadModel::read(o.cad, read);
  geometry::MeridionalOptions meridional;
  meridional.axis = axis;
  const geometry::MeridionalCurve curve = model.meridional_curve(o.faces, meridional);
  spdlog::info("{}: meridional curve of faces {} (degree {}, {} poles)", o.cad, fmt::join(curve.faces, ", "),
               curve.curve.degree(), curve.curve.poles().size());
  return setup::fit_on_cad_curve(curve, samples, reconstruction, read.unit, o.cad);
}

/// Without CAD: the nodes define the curve, in (x, y) (2D) or (r, z).
setup::CurveRun without_cad(const Options& o, const geometry::DeflectionSamples& samples,
                     const geometry::ReconstructionOptions& reconstruction) {
  if (!o.faces.empty()) throw InputError("--faces needs --cad");
  return setup::fit_without_cad(samples, axis_option(o.axis), reconstruction, parse_unit_option(o.fit.unit), "--axis");
}

int run_curve(const Options& o) {
  geometry::ReconstructionOptions reconstruction = reconstruction_options(o.fit);
  reconstruction.form = geometry::kDeflectionFormNames.parse(o.form).value();  // CLI::IsMember checked it

  const geometry::DeflectionSamples samples = io::read_deflection_csv(o.fit.fem);
  const setup::CurveRun run = o.cad.empty() ? without_cad(o, samples, reconstruction) : with_cad(o, samples, reconstruction);

  // The folder is made only once the inputs have been read and the curve built.
  std::vector<std::filesystem::path> inputs{o.fit.fem};
  if (!o.cad.empty()) inputs.emplace_back(o.cad);
  const io::OutputFolder folder_guard = prepare_fit_folder(o.fit, inputs, kCurveFiles);
  const std::filesystem::path folder(o.fit.output);
  const auto& report = run.fit.report;
  warn_dropped_nodes(o.fit, report.rejected_nodes, report.tolerance, "the CAD curve");
  write_curve_outputs(folder, run, {o.samples, o.amplification});
  spdlog::info("{} nodes ({} used), degree {}, form {}: max node distance to the curve {:.3g}, residual {:.3g}",
               report.nodes, report.used_nodes, report.degree, geometry::to_string(report.form),
               report.max_node_distance_to_cad, report.max_node_residual);
  spdlog::info("wrote {}: {}", folder.string(), fmt::join(kCurveFiles, ", "));
  return 0;
}

}  // namespace

Command add_curve_command(CLI::App& parent) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(
      "curve", "Reconstruct a deflected boundary curve from FEM nodes (eq. 21) and write it with the CAD curve");
  cmd->add_option("--cad", options->cad, "CAD file of the boundary (.step, .stp, .iges, .igs); none for 2D node tables")
      ->check(CLI::ExistingFile);
  cmd->add_option("--faces", options->faces, "Ids of the boundary's faces, e.g. 1,2 (see 'hotmesh cad')")
      ->delimiter(',');
  cmd->add_option("--axis", options->axis, "Axis of revolution ox,oy,oz,dx,dy,dz (default: the faces' axis)")
      ->delimiter(',');
  add_node_fit_options(*cmd, options->fit, "FEM nodes and deflections (CSV: x,y,dx,dy | x,y,z,dx,dy,dz | r,z,dr,dz)",
                       "Degree q of the deflected B-spline", "the CAD curve");
  cmd->add_option("--form", options->form, "curve: interpolate Q+delta (eq. 21); displacement: r(t) + d(t)")
      ->check(CLI::IsMember(geometry::kDeflectionFormNames.names()))
      ->capture_default_str();
  cmd->add_option("--samples", options->samples, "Samples of the curves in the CSV files (plus every knot)")
      ->check(CLI::Range(2, 10000000))
      ->capture_default_str();
  cmd->add_option("--amplification", options->amplification,
                  "Scale of the deflections in plot.svg (default: automatic, arrows up to 10 % of the curve)")
      ->check(CLI::NonNegativeNumber);
  add_output_options(*cmd, options->fit);
  return [options] { return run_curve(*options); };
}

}  // namespace hotmesh::app
