// hotmesh check: CAD-vs-mesh consistency. Measures the distance of every node of each mapped
// boundary patch to its reference shape (its CAD faces, or the deflected shape reconstructed
// from FEM deflections for a deformed mesh), reports per patch the maximum, the mean and the
// worst node as text, JSON or JUnit XML, and exits with code 1 when a patch is above the
// tolerance. Nodes on the shape do not make a wall on it (an edge between two nodes cuts a
// corner of the shape no node lands on), so it also measures the patch's faces against the
// shape both ways (the Hausdorff distance, wall_deviation_report.hpp) and names where it is
// worst; that decides too when --wall-tol is given. The patches and their shapes come from
// options (--map, --deflection; CAD faces taken meridionally or as surfaces as hotmesh deform
// takes them, or as --mode says) or from a case file (--case): a mesh deformed by `hotmesh
// deform` against the case's deflected walls, or the case's own mesh against its undeformed
// walls. A check that cannot be made still writes its JUnit report (a test case in error)
// before exiting with the error's code.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "hotmesh/api/case_check.hpp"
#include "hotmesh/api/check_report.hpp"
#include "hotmesh/api/mesh_summary.hpp"
#include "cli/commands.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/io/output_folder.hpp"

namespace hotmesh::app {

// The reports and checks of the library's run layer (api/).
using namespace hotmesh::api;  // NOLINT(google-build-using-namespace)

geometry::LengthUnit parse_unit_option(const std::string& text);  // cad_command.cpp

namespace {

struct Options {
  std::string case_file;
  std::string cad;
  std::string mesh;
  std::vector<std::string> maps;
  std::vector<std::string> deflections;
  std::vector<double> axis;
  std::string mode = "auto";
  double tolerance = 0.0;
  double wall_tolerance = 0.0;  ///< 0: none
  std::string unit = "m";
  int degree = 1;
  std::string form = "curve";
  std::string format = "text";
  std::string output;
  std::vector<std::string> given;  ///< the options above that were given on the command line
};

/// Options that say what a case file says too.
constexpr std::array kCaseOptions{"--cad", "--map", "--deflection", "--axis", "--mode", "--unit", "--degree", "--form"};

bool given(const Options& o, std::string_view option) {
  return std::find(o.given.begin(), o.given.end(), option) != o.given.end();
}

/// "PATCH=VALUE" of an option.
std::pair<std::string, std::string> assignment(const std::string& text, const char* option, const char* example) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw InputError(fmt::format("{} {}: expected PATCH={}", option, text, example));
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::vector<int> face_ids(const std::string& list, const std::string& text) {
  std::vector<int> ids;
  std::size_t start = 0;
  while (start <= list.size()) {
    const auto comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    int id = 0;
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), id);
    if (item.empty() || error != std::errc() || end != item.data() + item.size() || id < 1) {
      throw InputError(fmt::format("--map {}: face ids are integers from 1, separated by commas, e.g. wall=1,2", text));
    }
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) {
      throw InputError(fmt::format("--map {}: face {} is listed twice", text, id));
    }
    ids.push_back(id);
    start = comma + 1;
  }
  return ids;
}

/// The patches to check, in the order first named, with their faces and tables.
std::vector<PatchCheckSpec> patch_specs(const Options& o, const mesh::Mesh& mesh) {
  std::vector<PatchCheckSpec> specs;
  auto spec_of = [&](const std::string& patch, const std::string& option) -> PatchCheckSpec& {
    if (!mesh.find_patch(patch)) {
      std::vector<std::string> names;
      for (const auto& p : mesh.patches) names.push_back(p.name);
      throw InputError(fmt::format("{} {}: the mesh has no patch '{}' (its patches: {})", option, patch, patch,
                                   fmt::join(names, ", ")));
    }
    const auto it = std::find_if(specs.begin(), specs.end(), [&](const PatchCheckSpec& s) { return s.patch == patch; });
    if (it != specs.end()) return *it;
    specs.push_back({patch, {}, std::nullopt});
    return specs.back();
  };
  for (const std::string& text : o.maps) {
    const auto [patch, faces] = assignment(text, "--map", "FACE_IDS, e.g. wall=1,2");
    PatchCheckSpec& spec = spec_of(patch, "--map");
    if (!spec.faces.empty()) throw InputError(fmt::format("--map {}: patch '{}' is mapped twice", text, patch));
    spec.faces = face_ids(faces, text);
  }
  for (const std::string& text : o.deflections) {
    const auto [patch, file] = assignment(text, "--deflection", "CSV, e.g. wall=wall.csv");
    PatchCheckSpec& spec = spec_of(patch, "--deflection");
    if (spec.deflection) throw InputError(fmt::format("--deflection {}: patch '{}' has two tables", text, patch));
    spec.deflection = file;
  }
  if (specs.empty()) throw InputError("nothing to check: give --map PATCH=FACE_IDS and/or --deflection PATCH=CSV");
  return specs;
}

std::optional<double> wall_tolerance(const Options& o) {
  return o.wall_tolerance > 0.0 ? std::optional<double>(o.wall_tolerance) : std::nullopt;
}

/// The check the options describe (--map, --deflection, --cad, --axis, ...).
CheckResult check_with_options(const Options& o, const std::vector<std::filesystem::path>& inputs) {
  if (o.mesh.empty()) {
    throw InputError("give the mesh to check: hotmesh check MESH --map PATCH=FACE_IDS ... (or --case CASE.yaml)");
  }
  if (o.axis.size() != 0 && o.axis.size() != 6) {
    throw InputError(fmt::format("--axis needs six numbers ox,oy,oz,dx,dy,dz, got {}", o.axis.size()));
  }
  ReferenceOptions options;
  options.unit = parse_unit_option(o.unit);
  options.reconstruction.degree = o.degree;
  options.reconstruction.form =
      geometry::kDeflectionFormNames.parse(o.form).value();  // CLI::IsMember checked it
  options.mode = io::kWallModeNames.parse(o.mode).value();  // likewise
  if (!o.axis.empty()) {
    try {
      options.axis = geometry::Axis({o.axis[0], o.axis[1], o.axis[2]}, {o.axis[3], o.axis[4], o.axis[5]});
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--axis: ") + e.what());
    }
  }
  const io::LoadedMesh loaded = io::read_mesh(o.mesh);
  const mesh::Mesh& mesh = loaded.mesh;
  const std::vector<PatchCheckSpec> specs = patch_specs(o, mesh);
  if (!o.output.empty()) io::refuse_overwriting_input(o.output, inputs);
  std::optional<geometry::CadModel> cad;
  if (!o.cad.empty()) cad.emplace(geometry::CadModel::read(o.cad, {.unit = options.unit}));

  CheckResult result;
  result.mesh = o.mesh;
  result.quality = mesh_quality_json(loaded);
  result.cad = o.cad;
  result.unit = geometry::to_string(options.unit);
  result.tolerance = o.tolerance > 0.0 ? o.tolerance : default_tolerance(mesh);
  result.wall_tolerance = wall_tolerance(o);
  for (const PatchCheckSpec& spec : specs) {
    PatchReference reference = make_patch_reference(spec, cad ? &*cad : nullptr, mesh, options);
    result.patches.push_back(
        check_patch(*mesh.find_patch(spec.patch), mesh, reference, result.tolerance, result.wall_tolerance));
    log_patch(result.patches.back());
  }
  return result;
}

/// The check a case file describes: every patch that follows a boundary, against the walls
/// hotmesh deform builds for the case; undeformed for the case's own mesh, deflected for any
/// other (a mesh the case was deformed into). `inputs_known` is set once the case is read.
CheckResult check_with_case(const Options& o, std::vector<std::filesystem::path>& inputs, bool& inputs_known) {
  std::vector<std::string> conflicts;
  for (const char* option : kCaseOptions) {
    if (given(o, option)) conflicts.emplace_back(option);
  }
  if (!conflicts.empty()) {
    throw InputError(fmt::format("{}: not with --case, which gives the CAD file, the faces and tables of every patch, "
                                 "the axis, the unit, the degree and form of each table and the mode of each wall; "
                                 "drop --case to check other faces or tables",
                                 fmt::join(conflicts, ", ")));
  }
  api::CaseCheckOptions options;
  options.case_file = o.case_file;
  options.mesh = o.mesh;
  options.output = o.output;
  options.tolerance = o.tolerance;
  options.wall_tolerance = wall_tolerance(o);
  return api::check_with_case(options, inputs, inputs_known);
}

bool replaces_input(const std::filesystem::path& output, const std::vector<std::filesystem::path>& inputs) {
  try {
    io::refuse_overwriting_input(output, inputs);
  } catch (const InputError&) {
    return true;
  }
  return false;
}

/// No file at `path` yet, or an XML document (an earlier report).
bool nothing_or_xml(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return !ec;
  std::ifstream in(path, std::ios::binary);
  std::string start(5, '\0');
  in.read(start.data(), static_cast<std::streamsize>(start.size()));
  return in && start == "<?xml";
}

/// Replaces the JUnit report with one test case in error carrying `message`: never over an
/// input, and while the case file could not be read (its inputs unknown) only over nothing or
/// an earlier XML report. A report that cannot be written is only logged: the error itself is
/// what the user needs to see.
void write_error_report(const Options& o, const std::vector<std::filesystem::path>& inputs, bool inputs_known,
                        const char* type, const std::string& message) {
  if (o.format != "junit" || o.output.empty() || replaces_input(o.output, inputs)) return;
  if (!inputs_known && !nothing_or_xml(o.output)) {
    spdlog::warn("{}: not replaced by the report of the error: it is no XML report and may be a file the case names",
                 o.output);
    return;
  }
  try {
    io::write_file_atomically(o.output, check_junit_error(o.mesh.empty() ? o.case_file : o.mesh, type, message));
  } catch (const std::exception& e) {
    spdlog::warn("the report of the error could not be written: {}", e.what());
  }
}

int run_check(const Options& o) {
  // The files the check reads, never to be replaced by its report; a case file adds its own.
  std::vector<std::filesystem::path> inputs;
  for (const std::string& file : {o.mesh, o.cad, o.case_file}) {
    if (!file.empty()) inputs.emplace_back(file);
  }
  for (const std::string& text : o.deflections) {  // PATCH=CSV
    if (const auto eq = text.find('='); eq != std::string::npos && eq + 1 < text.size()) inputs.emplace_back(text.substr(eq + 1));
  }
  bool inputs_known = o.case_file.empty();
  try {
    if (!o.output.empty()) io::refuse_overwriting_input(o.output, inputs);
    const CheckResult result = o.case_file.empty() ? check_with_options(o, inputs) : check_with_case(o, inputs, inputs_known);
    const std::string report = o.format == "json"    ? check_json(result)
                               : o.format == "junit" ? check_junit(result)
                                                     : check_text(result);
    if (o.output.empty()) {
      std::cout << report << std::flush;
    } else {
      io::write_file_atomically(o.output, report);
      std::cout << check_text(result) << std::flush;
    }
    return result.passed() ? 0 : 1;
  } catch (const InputError& e) {
    write_error_report(o, inputs, inputs_known, "input error", e.what());
    throw;
  } catch (const std::bad_alloc&) {
    write_error_report(o, inputs, inputs_known, "out of memory", "out of memory");
    throw;
  } catch (const std::exception& e) {
    write_error_report(o, inputs, inputs_known, "internal error", e.what());
    throw;
  }
}

}  // namespace

Command add_check_command(CLI::App& parent) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(
      "check",
      "Distance of mesh boundary nodes, and of their faces both ways, to their CAD faces or to the deflected shape; "
      "exit code 1 above --tol (or --wall-tol)");
  cmd->add_option("mesh,--mesh", options->mesh,
                  "Mesh (.msh) to check: undeformed, or deformed when tables are given; with --case, default: the "
                  "case's own mesh")
      ->check(CLI::ExistingFile);
  cmd->add_option("--case", options->case_file,
                  "Case file (YAML) giving the patches, faces, tables and axis: a mesh deformed by the case is "
                  "compared with its deflected walls, the case's own mesh with its undeformed walls")
      ->check(CLI::ExistingFile);
  cmd->add_option("--cad", options->cad, "CAD file (.step, .stp, .iges, .igs) with the faces --map names")
      ->check(CLI::ExistingFile);
  cmd->add_option("--map", options->maps,
                  "PATCH=FACE_IDS: a patch and its CAD faces, e.g. casing=1,2 (repeatable); on a 2D mesh its CAD edges "
                  "in the plane z = 0, or with --axis (x along it, y the radius) its faces");
  cmd->add_option("--deflection", options->deflections,
                  "PATCH=CSV: FEM deflections of the patch; its nodes are measured to the deflected shape (repeatable)");
  cmd->add_option("--axis", options->axis,
                  "Axis of revolution ox,oy,oz,dx,dy,dz: CAD faces that all turn about it are measured "
                  "meridionally (default: an axis the faces share); on a 2D mesh: the mesh is axisymmetric about it")
      ->delimiter(',');
  cmd->add_option("--mode", options->mode,
                  "How CAD faces are measured, as the case file's deflection mode: meridional (a surface of "
                  "revolution, through the faces' meridional curve), surface (the faces themselves), or auto: "
                  "meridional when every face of the patch turns about one axis, else surface")
      ->check(CLI::IsMember(io::kWallModeNames.names()))
      ->capture_default_str();
  cmd->add_option("--tol", options->tolerance,
                  "Largest distance allowed, in the length unit (default: 1e-6 of the mesh's size)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--wall-tol", options->wall_tolerance,
                  "Largest two-sided distance allowed between a patch's faces and its shape, in the length unit "
                  "(default: none, the distance is reported only)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--unit", options->unit, "Length unit of the mesh, tables and CAD import: m, mm, cm, um, in, ft")
      ->capture_default_str();
  cmd->add_option("--degree", options->degree, "Degree of the deflected B-spline (as the case's deflection degree)")
      ->check(CLI::Range(1, 5))
      ->capture_default_str();
  cmd->add_option("--form", options->form, "curve or displacement (as the case's deflection form)")
      ->check(CLI::IsMember(geometry::kDeflectionFormNames.names()))
      ->capture_default_str();
  cmd->add_option("--format", options->format, "Report format: text, json or junit")
      ->check(CLI::IsMember({"text", "json", "junit"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "Write the report to this file (atomically); stdout gets the text form");
  return [options, cmd] {
    for (const char* option : kCaseOptions) {
      if (cmd->count(option) > 0) options->given.emplace_back(option);
    }
    return run_check(*options);
  };
}

}  // namespace hotmesh::app
