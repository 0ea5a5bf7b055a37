// hotmesh app: the options and outputs `hotmesh curve` and `hotmesh surface` share (see
// node_fit.hpp).
#include "fits/node_fit.hpp"

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <vector>

namespace hotmesh::app {

void add_node_fit_options(CLI::App& command, NodeFitOptions& options, const std::string& fem_help,
                          const std::string& degree_help, const std::string& shape) {
  command.add_option("--fem", options.fem, fem_help)->required()->check(CLI::ExistingFile);
  command.add_option("--degree", options.degree, degree_help)->check(CLI::Range(1, 5))->capture_default_str();
  command.add_option("--tolerance", options.tolerance,
                     "Largest node distance from " + shape + " (default: 1e-3 of the size of " + shape + ")")
      ->check(CLI::NonNegativeNumber);
  command.add_flag("--drop-far-nodes", options.drop_far_nodes,
                   "Leave out nodes farther than the tolerance (listed in summary.json) instead of failing");
  command.add_option("--unit", options.unit, "Length unit of the CAD import and the node table: m, mm, cm, um, in, ft")
      ->capture_default_str();
}

void add_output_options(CLI::App& command, NodeFitOptions& options) {
  command.add_option("-o,--output", options.output, "Output folder")->required();
  command.add_flag("--force", options.force, "Write into a folder that holds input files (never over them)");
}

geometry::ReconstructionOptions reconstruction_options(const NodeFitOptions& options) {
  geometry::ReconstructionOptions reconstruction;
  reconstruction.degree = options.degree;
  reconstruction.tolerance = options.tolerance;
  reconstruction.far_nodes = options.drop_far_nodes ? geometry::FarNodePolicy::drop : geometry::FarNodePolicy::reject;
  return reconstruction;
}

io::OutputFolder prepare_fit_folder(const NodeFitOptions& options, std::span<const std::filesystem::path> inputs,
                                    std::span<const char* const> files) {
  io::OutputFolder folder = io::prepare_output_folder(options.output, inputs, options.force);
  for (const char* name : files) io::refuse_overwriting_input(std::filesystem::path(options.output) / name, inputs);
  return folder;
}

void warn_dropped_nodes(const NodeFitOptions& options, std::span<const geometry::NodeDistance> nodes,
                        double tolerance, std::string_view shape) {
  for (const auto& node : nodes) {
    spdlog::warn("{}: {} is {:.3g} from {} (tolerance {:.3g}): left out", options.fem, node.label, node.distance, shape,
                 tolerance);
  }
}

nlohmann::json dropped_node_json(const geometry::NodeDistance& node, std::span<const std::int64_t> ids,
                                 std::span<const std::size_t> lines) {
  nlohmann::json entry = {{"node", node.label}, {"distance", node.distance}};
  if (node.index < ids.size()) entry["id"] = ids[node.index];
  if (node.index < lines.size()) entry["line"] = lines[node.index];
  return entry;
}

}  // namespace hotmesh::app
