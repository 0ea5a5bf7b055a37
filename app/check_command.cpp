// hotmesh check: CAD-vs-mesh consistency. Measures the distance of every node of each mapped
// boundary patch to its reference shape (its CAD faces, or the deflected shape reconstructed
// from FEM deflections for a deformed mesh), reports per patch the maximum, the mean and the
// worst node as text, JSON or JUnit XML, and exits with code 1 when a patch is above the
// tolerance.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>

#include "check_references.hpp"
#include "check_report.hpp"
#include "commands.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/io/output_folder.hpp"

namespace hotmesh::app {

geometry::LengthUnit parse_unit_option(const std::string& text);  // cad_command.cpp

namespace {

struct Options {
  std::string cad;
  std::string mesh;
  std::vector<std::string> maps;
  std::vector<std::string> deflections;
  std::vector<double> axis;
  double tolerance = 0.0;
  std::string unit = "m";
  int degree = 1;
  std::string form = "curve";
  std::string format = "text";
  std::string output;
};

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
    ids.push_back(id);
    start = comma + 1;
  }
  return ids;
}

/// The patches to check, in the order first named, with their faces and tables.
std::vector<PatchCheckSpec> patch_specs(const Options& o, const deform::Mesh& mesh) {
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

double default_tolerance(const deform::Mesh& mesh) {
  geometry::Vec3 lo = mesh.points.front(), hi = lo;
  for (const auto& p : mesh.points) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  return 1e-6 * geometry::distance(lo, hi);
}

PatchCheck check_patch(const deform::Patch& patch, const deform::Mesh& mesh, PatchReference& reference,
                       double tolerance) {
  const auto start = std::chrono::steady_clock::now();
  PatchCheck check;
  check.patch = patch.name;
  check.reference = reference.description();
  check.nodes = patch.nodes.size();
  double sum = 0.0;
  check.max_distance = -1.0;
  for (const deform::NodeId n : patch.nodes) {
    const geometry::Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    const double d = reference.distance(p);
    sum += d;
    if (d > check.max_distance || std::isnan(d)) {
      check.max_distance = d;
      check.worst_node = mesh.node_id(n);
      check.worst_point = p;
    }
  }
  check.max_distance = std::max(check.max_distance, 0.0);
  check.mean_distance = patch.nodes.empty() ? 0.0 : sum / static_cast<double>(patch.nodes.size());
  check.passed = check.max_distance <= tolerance;  // false for NaN too
  check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return check;
}

int run_check(const Options& o) {
  if (o.axis.size() != 0 && o.axis.size() != 6) {
    throw InputError(fmt::format("--axis needs six numbers ox,oy,oz,dx,dy,dz, got {}", o.axis.size()));
  }
  ReferenceOptions options;
  options.unit = parse_unit_option(o.unit);
  options.reconstruction.degree = o.degree;
  options.reconstruction.form =
      o.form == "displacement" ? geometry::DeflectionForm::displacement : geometry::DeflectionForm::curve;
  if (!o.axis.empty()) {
    try {
      options.axis = geometry::Axis({o.axis[0], o.axis[1], o.axis[2]}, {o.axis[3], o.axis[4], o.axis[5]});
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--axis: ") + e.what());
    }
  }
  const io::LoadedMesh loaded = io::read_mesh(o.mesh);
  const deform::Mesh& mesh = loaded.mesh;
  const std::vector<PatchCheckSpec> specs = patch_specs(o, mesh);
  if (!o.output.empty()) {
    std::vector<std::filesystem::path> inputs{o.mesh};
    if (!o.cad.empty()) inputs.emplace_back(o.cad);
    for (const PatchCheckSpec& spec : specs) {
      if (spec.deflection) inputs.push_back(*spec.deflection);
    }
    io::refuse_overwriting_input(o.output, inputs);
  }
  std::optional<geometry::CadModel> cad;
  if (!o.cad.empty()) cad.emplace(geometry::CadModel::read(o.cad, {.unit = options.unit}));

  CheckResult result;
  result.mesh = o.mesh;
  result.cad = o.cad;
  result.unit = geometry::to_string(options.unit);
  result.tolerance = o.tolerance > 0.0 ? o.tolerance : default_tolerance(mesh);
  for (const PatchCheckSpec& spec : specs) {
    std::unique_ptr<PatchReference> reference = make_patch_reference(spec, cad ? &*cad : nullptr, mesh, options);
    result.patches.push_back(check_patch(*mesh.find_patch(spec.patch), mesh, *reference, result.tolerance));
    const PatchCheck& p = result.patches.back();
    spdlog::info("{}: {} nodes, max distance {:.3e} at node {}, mean {:.3e} ({})", p.patch, p.nodes, p.max_distance,
                 p.worst_node, p.mean_distance, p.passed ? "pass" : "FAIL");
  }

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
}

}  // namespace

Command add_check_command(CLI::App& parent) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(
      "check", "Distance of mesh boundary nodes to their CAD faces or to the deflected shape; exit code 1 above --tol");
  cmd->add_option("--cad", options->cad, "CAD file (.step, .stp, .iges, .igs) with the faces --map names")
      ->check(CLI::ExistingFile);
  cmd->add_option("--mesh", options->mesh, "Mesh (.msh): undeformed, or deformed when tables are given")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--map", options->maps, "PATCH=FACE_IDS: a patch and its CAD faces, e.g. casing=1,2 (repeatable)");
  cmd->add_option("--deflection", options->deflections,
                  "PATCH=CSV: FEM deflections of the patch; its nodes are measured to the deflected shape (repeatable)");
  cmd->add_option("--axis", options->axis, "Axis of revolution ox,oy,oz,dx,dy,dz (default: the faces' axis)")
      ->delimiter(',');
  cmd->add_option("--tol", options->tolerance,
                  "Largest distance allowed, in the length unit (default: 1e-6 of the mesh's size)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--unit", options->unit, "Length unit of the mesh, tables and CAD import: m, mm, cm, um, in, ft")
      ->capture_default_str();
  cmd->add_option("--degree", options->degree, "Degree of the deflected B-spline (as the case's deflection degree)")
      ->check(CLI::Range(1, 5))
      ->capture_default_str();
  cmd->add_option("--form", options->form, "curve or displacement (as the case's deflection form)")
      ->check(CLI::IsMember({"curve", "displacement"}))
      ->capture_default_str();
  cmd->add_option("--format", options->format, "Report format: text, json or junit")
      ->check(CLI::IsMember({"text", "json", "junit"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "Write the report to this file (atomically); stdout gets the text form");
  return [options] { return run_check(*options); };
}

}  // namespace hotmesh::app
