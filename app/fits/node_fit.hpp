// hotmesh app: what `hotmesh curve` and `hotmesh surface` share, both section 4.2 run from a
// command line on one table of FEM nodes: the options of the reconstruction and of the output
// folder (same names, defaults and meaning), the folder made ready, the warnings about nodes
// left out, and those nodes as summary.json lists them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/output_folder.hpp"

namespace CLI {
class App;
}

namespace hotmesh::app {

/// The --unit option of the commands that read CAD files (cad_command.cpp). Throws
/// hotmesh::InputError for an unknown unit.
geometry::LengthUnit parse_unit_option(const std::string& text);

/// The options of a reconstruction from FEM nodes and of its output folder.
struct NodeFitOptions {
  std::string fem;
  int degree = 1;
  double tolerance = 0.0;
  bool drop_far_nodes = false;
  std::string unit = "m";
  std::string output;
  bool force = false;
};

/// Registers --fem, --degree, --tolerance, --drop-far-nodes and --unit. `fem_help` says which
/// tables the command reads, `degree_help` what has degree q, `shape` what nodes are measured
/// against ("the CAD curve").
void add_node_fit_options(CLI::App& command, NodeFitOptions& options, const std::string& fem_help,
                          const std::string& degree_help, const std::string& shape);
/// Registers -o/--output and --force.
void add_output_options(CLI::App& command, NodeFitOptions& options);

/// degree, tolerance and the far-node policy as the options give them (the default form).
geometry::ReconstructionOptions reconstruction_options(const NodeFitOptions& options);

/// The output folder, made once the inputs are read: refused if it holds one of `inputs`
/// (unless --force) or if one of the outputs `files` would replace an input.
[[nodiscard]] io::OutputFolder prepare_fit_folder(const NodeFitOptions& options,
                                                  std::span<const std::filesystem::path> inputs,
                                                  std::span<const char* const> files);

/// A warning per node left out for its distance from `shape` (--drop-far-nodes).
void warn_dropped_nodes(const NodeFitOptions& options, std::span<const geometry::NodeDistance> nodes,
                        double tolerance, std::string_view shape);

/// A node left out, as summary.json lists it: {"node": label, "distance", "id", "line"} (id and
/// line where the table has them).
nlohmann::json dropped_node_json(const geometry::NodeDistance& node, std::span<const std::int64_t> ids,
                                 std::span<const std::size_t> lines);

}  // namespace hotmesh::app
