// hotmesh cad FILE [--edges] [--json] [--unit U]: the faces of a STEP or IGES file: id, name,
// surface kind, axis of revolution (where there is one) and bounding box; and its edges, which
// the walls of 2D cases name: id, kind of curve, end points and length. The text lists the
// edges when asked (--edges) or when they are what the file offers a 2D case: it has no faces,
// or its faces are planes in one plane z = const (a 2D drawing); the JSON always has them.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "fits/cad_json.hpp"
#include "cli/commands.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::app {

namespace {

nlohmann::json model_json(const geometry::CadModel& model) {
  return {{"file", model.path().string()},
          {"unit", geometry::to_string(model.unit())},
          {"faces", faces_json(model)},
          {"edges", edges_json(model)}};
}

/// The largest absolute coordinate of the faces' bounds (of the edges' ends without faces).
double model_size(const geometry::CadModel& model) {
  double size = 0.0;
  const auto take = [&size](const geometry::Vec3& p) {
    for (int k = 0; k < 3; ++k) size = std::max(size, std::abs(p[k]));
  };
  for (const geometry::FaceInfo& face : model.faces()) {
    take(face.bounds.min);
    take(face.bounds.max);
  }
  if (model.faces().empty()) {
    for (const geometry::EdgeInfo& edge : model.edges()) {
      take(edge.start);
      take(edge.end);
    }
  }
  return size;
}

/// A 2D drawing: no faces, or only planes, all in one plane z = const.
bool planar_drawing(const geometry::CadModel& model) {
  double low = 1e300, high = -1e300;
  for (const geometry::FaceInfo& face : model.faces()) {
    if (face.kind != geometry::SurfaceKind::plane) return false;
    low = std::min(low, face.bounds.min.z);
    high = std::max(high, face.bounds.max.z);
  }
  return model.faces().empty() || high - low <= 1e-9 * model_size(model);
}

/// Coordinates to 6 digits, with values below `noise` (rounding left by the CAD system or the
/// axis fit) shown as 0.
std::string point_text(const geometry::Vec3& v, double noise) {
  const auto clean = [noise](double x) { return std::abs(x) < noise ? 0.0 : x; };
  return fmt::format("({:.6g}, {:.6g}, {:.6g})", clean(v.x), clean(v.y), clean(v.z));
}

std::string edges_text(const geometry::CadModel& model, double noise) {
  std::string text = fmt::format("{:>4}  {:<11} {:<38} {:<38} {}\n", "edge", "kind", "start", "end", "length");
  for (const geometry::EdgeInfo& edge : model.edges()) {
    text += fmt::format("{:>4}  {:<11} {:<38} {:<38} {:.6g}\n", edge.id, geometry::to_string(edge.kind),
                        point_text(edge.start, noise), point_text(edge.end, noise), edge.length);
  }
  return text;
}

std::string listing_text(const geometry::CadModel& model, bool with_edges) {
  const double noise = 1e-12 * model_size(model);
  std::string text = fmt::format("{}: {} faces, {} edges, lengths in {}\n", model.path().string(), model.faces().size(),
                                 model.edges().size(), geometry::to_string(model.unit()));
  if (model.faces().empty()) return text + edges_text(model, noise);
  text += fmt::format("{:>4}  {:<16} {:<11} {:<58} {}\n", "id", "name", "kind", "axis", "bounds");
  for (const geometry::FaceInfo& face : model.faces()) {
    const std::string axis = face.axis ? fmt::format("{} along {} [{}]", point_text(face.axis->origin(), noise),
                                                     point_text(face.axis->direction(), 1e-12),
                                                     geometry::to_string(face.axis_source))
                                       : "-";
    text += fmt::format("{:>4}  {:<16} {:<11} {:<58} {} - {}\n", face.id, face.name.empty() ? "-" : face.name,
                        geometry::to_string(face.kind), axis, point_text(face.bounds.min, noise),
                        point_text(face.bounds.max, noise));
  }
  return with_edges ? text + "\n" + edges_text(model, noise) : text;
}

}  // namespace

/// The --unit option shared by the commands that read CAD files.
geometry::LengthUnit parse_unit_option(const std::string& text) {
  const auto unit = geometry::parse_length_unit(text);
  if (!unit) throw InputError("--unit: unknown length unit '" + text + "' (use m, mm, cm, um, in or ft)");
  return *unit;
}

Command add_cad_command(CLI::App& parent) {
  struct Options {
    std::string file;
    bool edges = false;
    bool json = false;
    std::string unit = "m";
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(
      "cad", "List the faces of a STEP or IGES file (id, name, kind, axis, bounds) and its edges (id, kind, ends, length)");
  cmd->add_option("FILE", options->file, "CAD file (.step, .stp, .iges, .igs)")->required();
  cmd->add_flag("--edges", options->edges,
                "List the edges too (the walls of 2D cases name them); listed anyway when the file has no faces or "
                "is a drawing in a plane z = const, and always in --json");
  cmd->add_flag("--json", options->json, "Print the list as JSON");
  cmd->add_option("--unit", options->unit, "Length unit of the coordinates shown: m, mm, cm, um, in, ft")
      ->capture_default_str();
  return [options] {
    geometry::CadReadOptions read;
    read.unit = parse_unit_option(options->unit);
    const geometry::CadModel model = geometry::CadModel::read(options->file, read);
    std::cout << (options->json ? model_json(model).dump(2) + "\n"
                                : listing_text(model, options->edges || planar_drawing(model)));
    return 0;
  };
}

}  // namespace hotmesh::app
