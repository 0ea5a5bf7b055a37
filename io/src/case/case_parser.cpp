// hotmesh io: the case file's top level: the mesh, CAD, length unit, output and restart
// files and the axis (case_parser.hpp).
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "case/case_parser.hpp"

namespace hotmesh::io::detail {

namespace {

constexpr std::array<std::string_view, 11> kTopKeys{"mesh",     "cad",      "length_unit", "output",
                                                   "axis",     "solver",   "material",    "quality",
                                                   "patches",  "pictures", "restart"};
constexpr std::array<std::string_view, 2> kAxisKeys{"origin", "direction"};
constexpr std::array<std::string_view, 2> kOutputKeys{"folder", "series"};

}  // namespace

CaseParser::CaseParser(const fs::path& file) : reader_(problems_) {
  c_.file = fs::absolute(file).lexically_normal();
  folder_ = c_.file.parent_path();
}

Case CaseParser::parse(std::string_view text) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw InputError::at(c_.file.string(), line_of(e.mark), "invalid YAML: " + e.msg);
  }
  if (root.IsNull()) {
    problems_.add(0, "", "the case file is empty; it needs at least `mesh:` and `patches:` (see docs/case-file.md)");
  } else if (!root.IsMap()) {
    problems_.add(line_of(root), "", "expected a map of keys (mesh, patches, ...), got " + describe(root));
  } else {
    read_top(Entry{"", root, line_of(root), ""});
  }
  if (!problems_.empty()) problems_.raise(c_.file.string());
  return std::move(c_);
}

void CaseParser::read_top(const Entry& root) {
  const MapEntries top = reader_.keys(root, kTopKeys);
  if (const Entry* e = top.find("mesh")) {
    if (auto path = input_file(*e, "the mesh file name", Folders::accepted)) c_.mesh = *path;
  } else {
    reader_.error(root.line, "mesh", "missing; give the mesh file, e.g. `mesh: mesh.msh`");
  }
  has_cad_ = top.find("cad") != nullptr;
  if (has_cad_) read_cad(*top.find("cad"));
  if (const Entry* e = top.find("length_unit")) {
    if (const auto unit = reader_.choice(*e, geometry::kLengthUnitNames)) c_.length_unit = *unit;
  }
  c_.output = folder_ / (c_.file.stem().string() + "-out");
  if (const Entry* e = top.find("output")) read_output(*e);
  has_axis_ = top.find("axis") != nullptr;
  if (has_axis_) read_axis(*top.find("axis"));
  if (const Entry* e = top.find("solver")) read_solver(*e);
  if (const Entry* e = top.find("material")) read_material(*e);
  if (const Entry* e = top.find("quality")) read_quality(*e);
  if (const Entry* e = top.find("pictures")) read_pictures(*e);
  if (const Entry* e = top.find("restart")) {
    if (auto path = input_file(*e, "the restart file of a previous run (restart.hmr)")) c_.restart = *path;
  }
  if (const Entry* e = top.find("patches")) {
    read_patches(*e);
  } else {
    reader_.error(root.line, "patches",
                  "missing; give every mesh patch a role, e.g. `patches: {wall: {role: fixed}}`");
  }
}

fs::path CaseParser::resolve(const std::string& text) const {
  const fs::path path(text);
  return (path.is_absolute() ? path : folder_ / path).lexically_normal();
}

std::optional<fs::path> CaseParser::input_file(const Entry& e, std::string_view what, Folders folders) {
  const auto text = reader_.text(e, what);
  if (!text) return std::nullopt;
  const fs::path path = resolve(*text);
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    reader_.error(e, cat("file not found: ", path.string(), " (relative paths start from the case file's folder)"));
  } else if (folders == Folders::accepted && fs::is_directory(path, ec)) {
    return path;  // its reader checks what is in it
  } else if (const std::string problem = input_file_problem(path); !problem.empty()) {
    reader_.error(e, cat(path.string(), " ", problem));
  } else {
    return path;
  }
  return std::nullopt;
}

void CaseParser::read_cad(const Entry& e) {
  const auto path = input_file(e, "the CAD file name (.step, .stp, .iges or .igs)");
  if (!path) return;
  const std::string extension = ascii_lower(path->extension().string());
  if (extension != ".step" && extension != ".stp" && extension != ".iges" && extension != ".igs") {
    reader_.error(e, cat("'", path->filename().string(),
                         "' is not a CAD file hotmesh reads; expected .step, .stp, .iges or .igs"));
    return;
  }
  c_.cad = *path;
}

  /// `output: FOLDER` or `output: {folder: FOLDER, series: true}`.
void CaseParser::read_output(const Entry& e) {
  if (e.value.IsMap()) {
    const MapEntries m = reader_.keys(e, kOutputKeys);
    if (const Entry* folder = m.find("folder")) read_output_folder(*folder);
    if (const Entry* series = m.find("series")) c_.series = reader_.boolean(*series).value_or(false);
    return;
  }
  read_output_folder(e);
}

void CaseParser::read_output_folder(const Entry& e) {
  const auto text = reader_.text(e, "the output folder name");
  if (!text) return;
  const fs::path path = resolve(*text);
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) {
    reader_.error(e, cat(path.string(), " exists and is not a folder; give a folder for the results"));
    return;
  }
  c_.output = path;
}

void CaseParser::read_axis(const Entry& e) {
  if (!reader_.map_or_empty(e, "a map {origin: [x, y, z], direction: [x, y, z]}")) return;
  const MapEntries m = reader_.keys(e, kAxisKeys);
  std::optional<geometry::Vec3> origin;
  std::optional<geometry::Vec3> direction;
  for (const std::string_view key : kAxisKeys) {
    if (const Entry* item = m.find(key)) {
      (key == "origin" ? origin : direction) = reader_.vec3(*item);
    } else {
      reader_.error(e.line, e.sub(key), cat("missing; the axis needs both, e.g. ", kAxisExample));
    }
  }
  if (direction && norm(*direction) == 0.0) {
    reader_.error(*m.find("direction"), "must not be [0, 0, 0]; give the direction of the axis, e.g. [0, 0, 1]");
  } else if (origin && direction) {
    try {
      c_.axis = geometry::Axis(*origin, *direction);
    } catch (const std::invalid_argument& ex) {
      reader_.error(e, ex.what());
    }
  }
}

}  // namespace hotmesh::io::detail
