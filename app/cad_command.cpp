// hotmesh cad FILE [--json] [--unit U]: the faces of a STEP or IGES file: id, name, surface
// kind, axis of revolution (where there is one) and bounding box.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cad_json.hpp"
#include "commands.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/input_error.hpp"

namespace hotmesh::app {

namespace {

nlohmann::json model_json(const geometry::CadModel& model) {
  return {{"file", model.path().string()}, {"unit", geometry::to_string(model.unit())}, {"faces", faces_json(model)}};
}

/// Coordinates to 6 digits, with values below `noise` (rounding left by the CAD system or the
/// axis fit) shown as 0.
std::string point_text(const geometry::Vec3& v, double noise) {
  const auto clean = [noise](double x) { return std::abs(x) < noise ? 0.0 : x; };
  return fmt::format("({:.6g}, {:.6g}, {:.6g})", clean(v.x), clean(v.y), clean(v.z));
}

std::string faces_text(const geometry::CadModel& model) {
  double size = 0.0;
  for (const geometry::FaceInfo& face : model.faces()) {
    for (int k = 0; k < 3; ++k) size = std::max({size, std::abs(face.bounds.min[k]), std::abs(face.bounds.max[k])});
  }
  const double noise = 1e-12 * size;
  std::string text = fmt::format("{}: {} faces, lengths in {}\n", model.path().string(), model.faces().size(),
                                 geometry::to_string(model.unit()));
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
  return text;
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
    bool json = false;
    std::string unit = "m";
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand("cad", "List the faces of a STEP or IGES file: id, name, kind, axis, bounds");
  cmd->add_option("FILE", options->file, "CAD file (.step, .stp, .iges, .igs)")->required();
  cmd->add_flag("--json", options->json, "Print the list as JSON");
  cmd->add_option("--unit", options->unit, "Length unit of the coordinates shown: m, mm, cm, um, in, ft")
      ->capture_default_str();
  return [options] {
    geometry::CadReadOptions read;
    read.unit = parse_unit_option(options->unit);
    const geometry::CadModel model = geometry::CadModel::read(options->file, read);
    std::cout << (options->json ? model_json(model).dump(2) + "\n" : faces_text(model));
    return 0;
  };
}

}  // namespace hotmesh::app
