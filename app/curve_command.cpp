// hotmesh curve: section 4.2 on its own. Reads FEM boundary nodes with their deflections and
// the boundary's CAD faces (or, for 2D cases, only the nodes), reconstructs the deflected
// curve (eq. 21) and writes it with the undeformed one, a picture and a summary to a folder.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <array>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "curve_fit.hpp"
#include "curve_outputs.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/output_folder.hpp"

namespace hotmesh::app {

geometry::LengthUnit parse_unit_option(const std::string& text);  // cad_command.cpp

namespace {

struct Options {
  std::string cad;
  std::vector<int> faces;
  std::vector<double> axis;
  std::string fem;
  int degree = 1;
  std::string form = "curve";
  double tolerance = 0.0;
  bool drop_far_nodes = false;
  std::string unit = "m";
  std::size_t samples = 2000;
  double amplification = 0.0;
  std::string output;
  bool force = false;
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
CurveRun with_cad(const Options& o, const geometry::DeflectionSamples& samples,
                  const geometry::ReconstructionOptions& reconstruction) {
  if (o.faces.empty()) throw InputError("--cad needs --faces: the ids of the boundary's faces (see 'hotmesh cad')");
  require_cad_frame(samples);
  const std::optional<geometry::Axis> axis = axis_option(o.axis);
  if (samples.frame == geometry::SampleFrame::meridional && !axis) {
    throw InputError::in(samples.source, "meridional (r, z) nodes need --axis: z is measured from the axis origin");
  }
  geometry::CadReadOptions read;
  read.unit = parse_unit_option(o.unit);
  const geometry::CadModel model = geometry::CadModel::read(o.cad, read);
  geometry::MeridionalOptions meridional;
  meridional.axis = axis;
  const geometry::MeridionalCurve curve = model.meridional_curve(o.faces, meridional);
  spdlog::info("{}: meridional curve of faces {} (degree {}, {} poles)", o.cad, fmt::join(curve.faces, ", "),
               curve.curve.degree(), curve.curve.poles().size());
  return fit_on_cad_curve(curve, samples, reconstruction, read.unit, o.cad);
}

/// Without CAD: the nodes define the curve, in (x, y) (2D) or (r, z).
CurveRun without_cad(const Options& o, const geometry::DeflectionSamples& samples,
                     const geometry::ReconstructionOptions& reconstruction) {
  if (!o.faces.empty()) throw InputError("--faces needs --cad");
  return fit_without_cad(samples, axis_option(o.axis), reconstruction, parse_unit_option(o.unit), "--axis");
}

int run_curve(const Options& o) {
  geometry::ReconstructionOptions reconstruction;
  reconstruction.degree = o.degree;
  reconstruction.form = geometry::kDeflectionFormNames.parse(o.form).value();  // CLI::IsMember checked it
  reconstruction.tolerance = o.tolerance;
  reconstruction.far_nodes = o.drop_far_nodes ? geometry::FarNodePolicy::drop : geometry::FarNodePolicy::reject;

  const geometry::DeflectionSamples samples = io::read_deflection_csv(o.fem);
  const CurveRun run = o.cad.empty() ? without_cad(o, samples, reconstruction) : with_cad(o, samples, reconstruction);

  // The folder is made only once the inputs have been read and the curve built.
  std::vector<std::filesystem::path> inputs{o.fem};
  if (!o.cad.empty()) inputs.emplace_back(o.cad);
  const io::OutputFolder folder_guard = io::prepare_output_folder(o.output, inputs, o.force);
  const std::filesystem::path folder(o.output);
  for (const char* name : {"undeformed.csv", "deformed.csv", "curves.step", "curves.igs", "plot.svg", "summary.json"}) {
    io::refuse_overwriting_input(folder / name, inputs);
  }
  const auto& report = run.fit.report;
  for (const auto& node : report.rejected_nodes) {
    spdlog::warn("{}: {} is {:.3g} from the CAD curve (tolerance {:.3g}): left out", o.fem, node.label, node.distance,
                 report.tolerance);
  }
  write_curve_outputs(folder, run, {o.samples, o.amplification});
  spdlog::info("{} nodes ({} used), degree {}, form {}: max node distance to the curve {:.3g}, residual {:.3g}",
               report.nodes, report.used_nodes, report.degree, geometry::to_string(report.form),
               report.max_node_distance_to_cad, report.max_node_residual);
  spdlog::info("wrote {}: undeformed.csv, deformed.csv, curves.step, curves.igs, plot.svg, summary.json",
               folder.string());
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
  cmd->add_option("--fem", options->fem, "FEM nodes and deflections (CSV: x,y,dx,dy | x,y,z,dx,dy,dz | r,z,dr,dz)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--degree", options->degree, "Degree q of the deflected B-spline")
      ->check(CLI::Range(1, 5))
      ->capture_default_str();
  cmd->add_option("--form", options->form, "curve: interpolate Q+delta (eq. 21); displacement: r(t) + d(t)")
      ->check(CLI::IsMember(geometry::kDeflectionFormNames.names()))
      ->capture_default_str();
  cmd->add_option("--tolerance", options->tolerance,
                  "Largest node distance from the CAD curve (default: 1e-3 of the curve's size)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--drop-far-nodes", options->drop_far_nodes,
                "Leave out nodes farther than the tolerance (listed in summary.json) instead of failing");
  cmd->add_option("--unit", options->unit, "Length unit of the CAD import and the node table: m, mm, cm, um, in, ft")
      ->capture_default_str();
  cmd->add_option("--samples", options->samples, "Samples of the curves in the CSV files (plus every knot)")
      ->check(CLI::Range(2, 10000000))
      ->capture_default_str();
  cmd->add_option("--amplification", options->amplification,
                  "Scale of the deflections in plot.svg (default: automatic, arrows up to 10 % of the curve)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("-o,--output", options->output, "Output folder")->required();
  cmd->add_flag("--force", options->force, "Write into a folder that holds input files (never over them)");
  return [options] { return run_curve(*options); };
}

}  // namespace hotmesh::app
