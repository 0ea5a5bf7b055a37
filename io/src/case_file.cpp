// hotmesh io: reader and validator of the case file (YAML, schema in docs/case-file.md).
// The whole file is checked before anything is returned: every problem (unknown key, wrong
// type, value out of range, missing file, bad deflection table, inconsistent patch roles or
// periodic pairs) is collected and reported in one InputError, one line per problem, as
// "<case file>:<line>: <key path>: <what is wrong, and what is expected>". yaml-cpp stays in
// this file; its marks are 0-based, ours 1-based.
#include "hotmesh/io/case_file.hpp"

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
#include "yaml_checks.hpp"

namespace hotmesh::io {
namespace {

using namespace detail;  // NOLINT: the checking vocabulary of this file

namespace fs = std::filesystem;
using geometry::SampleFrame;

constexpr std::array<std::string_view, 11> kTopKeys{"mesh",     "cad",      "length_unit", "output",
                                                   "axis",     "solver",   "material",    "quality",
                                                   "patches",  "pictures", "restart"};
constexpr std::array<std::string_view, 3> kQualityKeys{"min_scaled_jacobian", "max_non_orthogonality", "max_skewness"};
constexpr std::array<std::string_view, 2> kAxisKeys{"origin", "direction"};
constexpr std::array<std::string_view, 12> kSolverKeys{
    "increments", "newton_tolerance", "max_newton_iterations", "pcg_tolerance", "max_pcg_iterations", "threads",
    "max_increment_splits", "linear", "amg", "amg_reuse", "forcing", "predictor"};
constexpr std::array<std::string_view, 5> kMaterialKeys{"law", "alpha_s", "alpha_v", "drop_jacobian",
                                                        "wall_distance_exponent"};
constexpr std::array<std::string_view, 5> kPatchKeys{"role", "deflection", "partner", "angle_deg", "features"};
constexpr std::array<std::string_view, 1> kFeatureKeys{"angle"};
constexpr std::array<std::string_view, 2> kOutputKeys{"folder", "series"};
constexpr std::string_view kFeaturesExample = "`features: {angle: 25}` (degrees) or `features: off`";
constexpr std::array<std::string_view, 7> kDeflectionKeys{"file", "calculix", "degree", "faces", "edges", "form", "mode"};
constexpr std::array<std::string_view, 5> kCalculixKeys{"frd", "inp", "set", "step", "time"};
constexpr std::string_view kCalculixExample = "`calculix: {frd: disc.frd, inp: disc.inp, set: DISC_FACE}`";
constexpr std::string_view kRoleList = "fixed, prescribed, slip, sliding, passive, periodic";
constexpr std::string_view kAxisExample = "axis: {origin: [0, 0, 0], direction: [0, 0, 1]}";

/// What the validation learns about a patch besides its PatchSpec.
struct PatchNotes {
  bool role_known = false;
  bool has_angle = false;  ///< angle_deg given (even if its value was wrong)
  std::size_t partner_line = 0;
  std::size_t angle_line = 0;
};

class CaseParser {
 public:
  explicit CaseParser(const fs::path& file) : reader_(problems_) {
    c_.file = fs::absolute(file).lexically_normal();
    folder_ = c_.file.parent_path();
  }

  Case parse(std::string_view text) {
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

 private:
  void read_top(const Entry& root) {
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

  fs::path resolve(const std::string& text) const {
    const fs::path path(text);
    return (path.is_absolute() ? path : folder_ / path).lexically_normal();
  }

  /// A path that must name an existing file.
  /// Whether an input may be a folder (a mesh in a folder of files, as OpenFOAM's polyMesh).
  enum class Folders { refused, accepted };

  std::optional<fs::path> input_file(const Entry& e, std::string_view what, Folders folders = Folders::refused) {
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

  void read_cad(const Entry& e) {
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
  void read_output(const Entry& e) {
    if (e.value.IsMap()) {
      const MapEntries m = reader_.keys(e, kOutputKeys);
      if (const Entry* folder = m.find("folder")) read_output_folder(*folder);
      if (const Entry* series = m.find("series")) c_.series = reader_.boolean(*series).value_or(false);
      return;
    }
    read_output_folder(e);
  }

  void read_output_folder(const Entry& e) {
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

  void read_axis(const Entry& e) {
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

  void read_solver(const Entry& e) {
    if (!reader_.map_or_empty(e, cat("a map of solver options (", join(kSolverKeys), ")"))) return;
    const MapEntries m = reader_.keys(e, kSolverKeys);
    const auto integer = [&](std::string_view key, int& field, int low) {
      if (const Entry* x = m.find(key)) field = reader_.integer_in(*x, low).value_or(field);
    };
    // Relative tolerances: below about 1e-14 double precision cannot reach them, and the
    // solvers would iterate on rounding until their limit.
    const auto fraction = [&](std::string_view key, double& field) {
      const auto reachable = [](double v) { return v >= 1e-14 && v < 1.0; };
      if (const Entry* x = m.find(key)) {
        field = reader_.number_where(*x, reachable, "at least 1e-14 (what double precision reaches) and below 1")
                    .value_or(field);
      }
    };
    deform::SolverOptions& s = c_.solver;
    if (const Entry* x = m.find("increments")) {
      const auto n = x->value.IsScalar() && !quoted(x->value) ? detail::parse<std::int64_t>(x->value.Scalar()) : std::nullopt;
      if (n && *n > kMaxIncrements) {
        reader_.error(*x, cat("must be at most ", std::to_string(kMaxIncrements), ", got ", x->value.Scalar(),
                              ": the paper's cases take 16, and an increment too large for the mesh is halved by "
                              "the solver itself (max_increment_splits), so tens of increments are enough"));
      } else {
        s.increments = reader_.integer_in(*x, 1).value_or(s.increments);
      }
    }
    fraction("newton_tolerance", s.newton_tolerance);
    integer("max_newton_iterations", s.max_newton_iterations, 1);
    fraction("pcg_tolerance", s.pcg_tolerance);
    integer("max_pcg_iterations", s.max_pcg_iterations, 1);
    integer("threads", c_.threads, 0);
    if (const Entry* x = m.find("max_increment_splits")) {
      s.max_increment_splits = reader_.integer_in(*x, 0, kMaxIncrementSplits).value_or(s.max_increment_splits);
    }
    if (const Entry* x = m.find("linear")) {
      if (const auto k = reader_.choice(*x, deform::kLinearSolverNames)) s.linear = *k;
    }
    if (const Entry* x = m.find("amg")) {
      if (const auto k = reader_.choice(*x, deform::kAmgPackageNames)) s.amg = *k;
    }
    if (const Entry* x = m.find("amg_reuse")) {
      if (const auto k = reader_.choice(*x, deform::kAmgReuseNames)) {
        if (*k == deform::AmgReuse::interpolation && s.amg == deform::AmgPackage::hypre) {
          reader_.error(*x, "interpolation is kept by amg: gamg only; with hypre choose preconditioner or none");
        } else {
          s.amg_reuse = *k;
        }
      }
    }
    if (const Entry* x = m.find("forcing")) {
      if (const auto k = reader_.choice(*x, deform::kForcingTermNames)) s.forcing = *k;
    }
    if (const Entry* x = m.find("predictor")) s.predictor = reader_.boolean(*x).value_or(s.predictor);
  }

  void read_material(const Entry& e) {
    if (!reader_.map_or_empty(e, cat("a map of material options (", join(kMaterialKeys), ")"))) return;
    const MapEntries m = reader_.keys(e, kMaterialKeys);
    deform::MaterialOptions& mat = c_.material;
    if (const Entry* x = m.find("law")) {
      if (const auto law = reader_.choice(*x, deform::kStiffnessLawNames)) mat.law = *law;
    }
    if (const Entry* x = m.find("drop_jacobian")) mat.drop_jacobian = reader_.boolean(*x).value_or(mat.drop_jacobian);
    if (const Entry* x = m.find("alpha_s")) {
      mat.alpha_s = reader_.number_where(*x, [](double v) { return v > 0.0; }, "> 0").value_or(mat.alpha_s);
    }
    if (const Entry* x = m.find("alpha_v")) {
      mat.alpha_v = reader_.number_where(*x, [](double v) { return v >= 0.0; }, ">= 0").value_or(mat.alpha_v);
    }
    if (const Entry* x = m.find("wall_distance_exponent")) {
      mat.wall_distance_exponent =
          reader_.number_where(*x, [](double v) { return v >= 0.0 && v <= 4.0; }, "from 0 to 4")
              .value_or(mat.wall_distance_exponent);
    }
  }

  /// The limits every increment's cells keep (deform::QualityLimits).
  void read_quality(const Entry& e) {
    if (!reader_.map_or_empty(e, cat("a map of quality limits (", join(kQualityKeys), ")"))) return;
    const MapEntries m = reader_.keys(e, kQualityKeys);
    deform::QualityLimits& q = c_.solver.quality;
    if (const Entry* x = m.find("min_scaled_jacobian")) {
      q.min_scaled_jacobian =
          reader_.number_where(*x, [](double v) { return v > 0.0 && v < 1.0; }, "above 0 and below 1 (the ideal cell's)")
              .value_or(q.min_scaled_jacobian);
    }
    if (const Entry* x = m.find("max_non_orthogonality")) {
      q.max_non_orthogonality =
          reader_.number_where(*x, [](double v) { return v > 0.0 && v < 90.0; }, "degrees above 0 and below 90")
              .value_or(q.max_non_orthogonality);
    }
    if (const Entry* x = m.find("max_skewness")) {
      q.max_skewness = reader_.number_where(*x, [](double v) { return v > 0.0; }, "> 0").value_or(q.max_skewness);
    }
  }

  void read_pictures(const Entry& e) {
    if (!reader_.map_or_empty(e, "a map of picture names to views [xmin, xmax, ymin, ymax]")) return;
    for (const Entry& view : reader_.keys(e, {}).entries) {
      const bool plain = std::all_of(view.name.begin(), view.name.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
      });
      if (!plain) {
        reader_.error(view, "picture names become file names: use letters, digits, '_' and '-'");
        continue;
      }
      if (!view.value.IsSequence() || view.value.size() != 4) {
        reader_.error(view, "expected a view [xmin, xmax, ymin, ymax], got " + describe(view.value));
        continue;
      }
      std::array<double, 4> v{};
      bool ok = true;
      for (std::size_t i = 0; i < 4 && ok; ++i) {
        const auto value = reader_.number(view.item(i));
        ok = value.has_value();
        v[i] = value.value_or(0.0);
      }
      if (!ok) continue;
      if (!(v[0] < v[1] && v[2] < v[3])) {
        reader_.error(view, "the view needs xmin < xmax and ymin < ymax");
        continue;
      }
      c_.pictures.push_back({view.name, v[0], v[1], v[2], v[3], view.line});
    }
  }

  void read_patches(const Entry& e) {
    c_.patches_line = e.line;
    if (!reader_.map_or_empty(e, "a map of patch names to {role: ...}")) return;
    const MapEntries m = reader_.keys(e, {});
    if (m.entries.empty()) {
      reader_.error(e, "is empty; give every mesh patch a role, e.g. `wall: {role: fixed}`");
      return;
    }
    for (const Entry& patch : m.entries) read_patch(patch);
    check_periodic_pairs();
    check_tables_agree();
  }

  /// Adds the patch to the case even when it has problems, so later checks can refer to it.
  void read_patch(const Entry& e) {
    PatchSpec spec;
    spec.name = e.name;
    spec.line = e.line;
    PatchNotes& notes = notes_.emplace_back();
    const MapEntries m = reader_.map_or_empty(e, "a map {role: ...}") ? reader_.keys(e, kPatchKeys) : MapEntries{};
    if (const Entry* r = m.find("role")) {
      if (const auto text = reader_.text(*r, cat("a role (one of ", kRoleList, ")"))) {
        const std::optional<PatchRole> role = deform::kBoundaryRoleNames.parse(*text);
        notes.role_known = role.has_value();
        if (role) spec.role = *role;
        if (!notes.role_known) reader_.error(*r, cat("unknown role '", *text, "'; expected one of ", kRoleList));
      }
    } else if (e.value.IsMap() || e.value.IsNull()) {
      reader_.error(e.line, e.sub("role"), cat("missing; expected one of ", kRoleList));
    }
    const bool known = notes.role_known;
    const std::string_view role_name = to_string(spec.role);

    const Entry* deflection = m.find("deflection");
    const bool takes_table = spec.role == PatchRole::prescribed || spec.role == PatchRole::sliding;
    if (deflection != nullptr && known && !takes_table) {
      reader_.error(*deflection, cat("not allowed for role ", role_name,
                                     "; only prescribed and sliding patches take a deflection table"));
    } else if (deflection != nullptr) {
      spec.deflection = read_deflection(*deflection, spec);
    } else if (known && spec.role == PatchRole::prescribed) {
      reader_.error(e.line, e.sub("deflection"), "missing; a prescribed patch needs `deflection: {file: <table.csv>}`");
    }

    if (const Entry* features = m.find("features")) {
      if (known && spec.role != PatchRole::sliding) {
        reader_.error(*features, cat("only sliding patches have features (this patch is ", role_name,
                                     "): the corners of a wall that sliding nodes hold"));
      } else {
        read_features(*features, spec.features);
      }
    }

    for (const std::string_view key : {std::string_view("partner"), std::string_view("angle_deg")}) {
      const Entry* item = m.find(key);
      if (item == nullptr) continue;
      if (known && spec.role != PatchRole::periodic) {
        reader_.error(*item, cat("only periodic patches have ", key, " (this patch is ", role_name, ")"));
      } else if (key == "partner") {
        notes.partner_line = item->line;
        spec.partner = reader_.text(*item, "the name of the other periodic patch").value_or("");
      } else {
        notes.has_angle = true;
        notes.angle_line = item->line;
        const auto valid = [](double a) { return a != 0.0 && std::abs(a) <= 180.0; };
        spec.angle_deg =
            reader_.number_where(*item, valid, "a non-zero angle in degrees with |angle_deg| <= 180").value_or(0.0);
      }
    }
    c_.patches.push_back(std::move(spec));
  }

  /// `features: off | on | {angle: A}`: which corners of a sliding wall its nodes hold.
  void read_features(const Entry& e, deform::FeatureOptions& features) {
    if (e.value.IsScalar()) {
      if (const auto on = reader_.boolean(e)) features.enabled = *on;
      return;
    }
    if (!reader_.map_or_empty(e, cat("on, off or a map {angle: <degrees>}, e.g. ", kFeaturesExample))) return;
    const MapEntries m = reader_.keys(e, kFeatureKeys);
    if (const Entry* angle = m.find("angle")) {
      const auto valid = [](double a) { return a > 0.0 && a < 180.0; };
      if (const auto degrees = reader_.number_where(*angle, valid, "an angle in degrees between 0 and 180")) {
        features.angle = *degrees * std::numbers::pi / 180.0;
      }
    }
  }

  std::optional<DeflectionSpec> read_deflection(const Entry& e, const PatchSpec& patch) {
    if (!reader_.map_or_empty(e, "a map {file: <table.csv>, degree: <1..5>, faces: [...]}")) return std::nullopt;
    const MapEntries m = reader_.keys(e, kDeflectionKeys);
    DeflectionSpec spec;
    spec.line = e.line;
    bool table_read = false;
    const Entry* file = m.find("file");
    const Entry* calculix = m.find("calculix");
    if (file != nullptr && calculix != nullptr) {
      reader_.error(*calculix, "give either `file:` (a CSV table) or `calculix:` (CalculiX results), not both");
    } else if (calculix != nullptr) {
      table_read = read_calculix(*calculix, spec);
    } else if (file == nullptr) {
      reader_.error(e.line, e.sub("file"), cat("missing; give the deflection table, e.g. `file: deflections.csv`, "
                                               "or CalculiX results, e.g. ", kCalculixExample));
    } else if (auto path = input_file(*file, "the deflection table file name (.csv)")) {
      spec.file = *path;
      spec.files = {*path};
      try {
        spec.samples = parse_deflection_csv(read_file(*path), path->string());
        table_read = true;
      } catch (const InputError& error) {
        reader_.error(*file, error.what());
      }
    }
    const Entry& source = file != nullptr ? *file : (calculix != nullptr ? *calculix : e);
    bool ok = table_read;
    const Entry* degree = m.find("degree");
    if (degree != nullptr) {
      const auto value = reader_.integer_in(*degree, 1, geometry::kMaxReconstructionDegree);
      ok = ok && value.has_value();
      spec.degree = value.value_or(spec.degree);
    }
    if (ok && spec.samples.size() < static_cast<std::size_t>(spec.degree) + 1) {
      reader_.error(degree != nullptr ? *degree : source,
                    cat("a degree-", std::to_string(spec.degree), " curve needs at least ",
                        std::to_string(spec.degree + 1), " samples, the table has ",
                        std::to_string(spec.samples.size())));
      ok = false;
    }
    const Entry* faces = m.find("faces");
    const Entry* edges = m.find("edges");
    if (faces != nullptr) ok = read_cad_ids(*faces, "face", spec.faces) && ok;
    if (edges != nullptr) ok = read_cad_ids(*edges, "edge", spec.edges) && ok;
    if (faces != nullptr && edges != nullptr) {
      reader_.error(*edges, "give either `faces:` (CAD faces: 3D walls, or an axisymmetric 2D case's) or `edges:` "
                            "(CAD edges in the plane of a 2D case), not both");
      ok = false;
    }
    if (const Entry* form = m.find("form")) {
      const auto value = reader_.choice(*form, geometry::kDeflectionFormNames);
      ok = ok && value.has_value();
      if (value) spec.form = *value;
    }
    if (const Entry* mode = m.find("mode")) {
      const auto value = reader_.choice(*mode, kWallModeNames);
      ok = ok && value.has_value();
      if (value) spec.mode = *value;
      if (value == WallMode::meridional && !has_axis_) {
        reader_.error(*mode, cat("a meridional wall is a surface of revolution about the top-level axis; give it, "
                                 "e.g. ",
                                 kAxisExample));
        ok = false;
      }
    }

    if (table_read && spec.samples.frame == SampleFrame::meridional && !has_axis_) {
      reader_.error(patch.line, "patches." + patch.name,
                    cat("its deflection table is meridional (r, z), which needs the top-level axis, e.g. ",
                        kAxisExample));
    }
    if (!ok) return std::nullopt;
    return spec;
  }

  /// `calculix: {frd, inp, set, step | time}`: the table of a node set or surface of a deck,
  /// from a DISP block of its results. Each problem is reported at the key it comes from.
  bool read_calculix(const Entry& e, DeflectionSpec& spec) {
    if (!reader_.map_or_empty(e, cat("a map such as ", kCalculixExample))) return false;
    const MapEntries m = reader_.keys(e, kCalculixKeys);
    CalculixSelection selection;
    bool ok = true;
    const auto required = [&](std::string_view key, std::string_view what) -> const Entry* {
      const Entry* x = m.find(key);
      if (x == nullptr) reader_.error(e.line, e.sub(key), cat("missing; give ", what, ", e.g. ", kCalculixExample));
      ok = ok && x != nullptr;
      return x;
    };
    const Entry* frd = required("frd", "the results file ccx wrote (.frd)");
    const Entry* inp = required("inp", "the input deck ccx solved (.inp), which defines the set");
    const Entry* set = required("set", "a node set (*NSET) or surface (*SURFACE) of the deck");
    if (frd != nullptr) {
      const auto path = input_file(*frd, "the CalculiX results file (.frd)");
      ok = ok && path.has_value();
      selection.frd = path.value_or(fs::path());
    }
    if (inp != nullptr) {
      const auto path = input_file(*inp, "the CalculiX input deck (.inp)");
      ok = ok && path.has_value();
      selection.inp = path.value_or(fs::path());
    }
    if (set != nullptr) {
      const auto name = reader_.text(*set, "the name of a node set or surface of the deck");
      ok = ok && name.has_value();
      selection.set = name.value_or("");
    }
    ok = read_step_choice(m, selection.choice) && ok;
    if (!ok) return false;
    return read_calculix_results(e, m, selection, spec);
  }

  /// `step: last | N` and `time: T` of a `calculix:` map.
  bool read_step_choice(const MapEntries& m, FrdStepChoice& choice) {
    bool ok = true;
    const Entry* step = m.find("step");
    if (step != nullptr && !(step->value.IsScalar() && step->value.Scalar() == "last")) {
      const auto n = step->value.IsScalar() && !quoted(step->value) ? detail::parse<std::int64_t>(step->value.Scalar())
                                                                     : std::nullopt;
      if (!n || *n < 1 || *n > INT_MAX) {
        reader_.error(*step, "expected `last` or the number of an analysis step (*STEP, from 1), got " +
                                 describe(step->value));
        ok = false;
      } else {
        choice.step = static_cast<int>(*n);
      }
    }
    if (const Entry* time = m.find("time")) {
      choice.time = reader_.number(*time);
      ok = ok && choice.time.has_value();
    }
    return ok;
  }

  /// Reads the deck and the results of a checked selection; reports each problem at its key.
  bool read_calculix_results(const Entry& e, const MapEntries& m, const CalculixSelection& selection,
                             DeflectionSpec& spec) {
    const auto attempt = [&](const Entry& at, const auto& work) {
      try {
        work();
        return true;
      } catch (const InputError& error) {
        reader_.error(at, error.what());
        return false;
      }
    };
    InpDeck deck;
    FrdResults results;
    if (!attempt(*m.find("inp"), [&] { deck = read_inp(selection.inp); })) return false;
    if (!attempt(*m.find("set"), [&] { deck.set_nodes(selection.set); })) return false;
    if (!attempt(*m.find("frd"), [&] { results = read_frd(selection.frd); })) return false;
    const Entry* step = m.find("step");
    const Entry* time = m.find("time");
    const Entry& choice_at = step != nullptr ? *step : (time != nullptr ? *time : *m.find("frd"));
    if (!attempt(choice_at, [&] { choose_displacements(results, selection.choice); })) return false;
    return attempt(e, [&] {
      CalculixTable table = calculix_table(results, deck, selection);
      spec.file = selection.frd;
      spec.files = table.files;
      spec.samples = std::move(table.samples);
      spec.calculix = CalculixNote{selection, table.kind, table.step, table.time, table.min_temperature,
                                   table.max_temperature};
    });
  }

  /// `faces: [...]` or `edges: [...]`: numbers of CAD faces or edges (`what`), as `hotmesh cad`
  /// lists them.
  bool read_cad_ids(const Entry& e, std::string_view what, std::vector<int>& ids) {
    if (!e.value.IsSequence() || e.value.size() == 0) {
      const std::string got = e.value.IsSequence() ? "an empty list" : describe(e.value);
      reader_.error(e, cat("expected a list of CAD ", what, " numbers (>= 1), e.g. [3, 4], got ", got));
      return false;
    }
    bool ok = true;
    for (std::size_t i = 0; i < e.value.size(); ++i) {
      const Entry entry = e.item(i);
      const auto id = reader_.integer_in(entry, 1);
      if (id && std::find(ids.begin(), ids.end(), *id) != ids.end()) {
        reader_.error(entry, cat(what, " ", std::to_string(*id), " is listed twice"));
      } else if (id) {
        ids.push_back(*id);
        continue;
      }
      ok = false;
    }
    if (!has_cad_) {
      reader_.error(e, cat("CAD ", what, " numbers need a CAD file; add `cad: <file.step>` at the top level"));
      ok = false;
    }
    return ok;
  }

  std::optional<std::size_t> index_of(std::string_view name) const {
    const PatchSpec* p = c_.find_patch(name);
    return p == nullptr ? std::nullopt : std::optional<std::size_t>(static_cast<std::size_t>(p - c_.patches.data()));
  }

  bool periodic(std::size_t i) const { return notes_[i].role_known && c_.patches[i].role == PatchRole::periodic; }

  /// The periodic patch that declares patch `j` as its partner with an angle, if any.
  const PatchSpec* declarer_of(std::size_t j) const {
    for (std::size_t k = 0; k < c_.patches.size(); ++k) {
      if (periodic(k) && notes_[k].has_angle && c_.patches[k].partner == c_.patches[j].name) return &c_.patches[k];
    }
    return nullptr;
  }

  /// Each periodic pair is declared on one side (partner + angle_deg); the other side names
  /// no partner or the first one, and gives no angle. Every periodic patch is in one pair.
  void check_periodic_pairs() {
    std::vector<std::vector<std::string>> pairs(c_.patches.size());  // partners of each patch
    std::vector<bool> reported(c_.patches.size(), false);            // a problem of its pairing was reported
    pair_periodic_patches(pairs, reported);
    require_one_partner_each(pairs, reported);
  }

  /// Each pair declared by `partner:` and `angle_deg:` on one side, into the partners of both
  /// sides; every problem of a declaration reported at its key.
  void pair_periodic_patches(std::vector<std::vector<std::string>>& pairs, std::vector<bool>& reported) {
    const std::size_t n = c_.patches.size();
    std::vector<std::string> periodic_names;
    for (std::size_t i = 0; i < n; ++i) {
      if (periodic(i)) periodic_names.push_back(c_.patches[i].name);
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!periodic(i)) continue;
      const PatchSpec& p = c_.patches[i];
      const PatchNotes& pn = notes_[i];
      const auto problem = [&](std::size_t line, std::string_view sub, const std::string& message) {
        reader_.error(line, cat("patches.", p.name, sub), message);
        reported[i] = true;
      };
      if (p.partner.empty()) {  // the other side of a pair, or a partner value already reported
        if (pn.has_angle && pn.partner_line == 0) {
          problem(pn.angle_line, ".angle_deg", "needs `partner: <other periodic patch>` beside it");
        }
        reported[i] = reported[i] || pn.partner_line != 0;
        continue;
      }
      const auto j = index_of(p.partner);
      if (!j) {
        problem(pn.partner_line, ".partner",
                cat("'", p.partner, "' is not a patch of this case; periodic patches: ", join(periodic_names)));
        continue;
      }
      if (*j == i) {
        problem(pn.partner_line, ".partner", "a patch cannot be its own partner; name the other side");
        continue;
      }
      const PatchSpec& q = c_.patches[*j];
      const PatchNotes& qn = notes_[*j];
      if (!periodic(*j)) {
        reported[i] = true;  // an unknown role of q was reported already
        if (qn.role_known) {
          problem(pn.partner_line, ".partner",
                  cat("'", q.name, "' has role ", to_string(q.role), "; the partner must be periodic too"));
        }
        continue;
      }
      const bool back = q.partner == p.name;
      const std::string elsewhere = cat("'", q.name, "' names '", q.partner, "' as its partner, not '", p.name, "'");
      if (pn.has_angle && qn.has_angle && back) {
        if (i > *j) {
          problem(pn.angle_line, ".angle_deg",
                  cat("'", q.name, "' gives angle_deg too; give it on one side of the pair only"));
        }
        reported[i] = true;
      } else if (!q.partner.empty() && !back) {
        problem(pn.partner_line, ".partner", elsewhere);
      } else if (pn.has_angle) {
        pairs[i].push_back(q.name);
        pairs[*j].push_back(p.name);
      } else if (back && qn.has_angle) {
        continue;  // declared from the other side
      } else if (const PatchSpec* other = back ? nullptr : declarer_of(*j)) {
        problem(pn.partner_line, ".partner", cat("'", q.name, "' is already paired with '", other->name, "'"));
      } else {
        if (!back || i < *j) {
          problem(p.line, "", cat("the periodic pair ", p.name, "/", q.name,
                                  " has no angle_deg; add angle_deg (the rotation from one patch to the other, "
                                  "in degrees) on one side"));
        }
        reported[i] = reported[*j] = true;
      }
    }
  }

  /// Every periodic patch in exactly one pair; the side without angle_deg learns its partner.
  void require_one_partner_each(const std::vector<std::vector<std::string>>& pairs, const std::vector<bool>& reported) {
    for (std::size_t i = 0; i < c_.patches.size(); ++i) {
      if (!periodic(i)) continue;
      PatchSpec& p = c_.patches[i];
      const std::string key = "patches." + p.name;
      if (pairs[i].size() > 1) {
        reader_.error(p.line, key, cat("is in more than one periodic pair (with ", join(pairs[i]),
                                       "); each periodic patch pairs with exactly one other"));
      } else if (pairs[i].empty() && !reported[i]) {
        reader_.error(p.line, key, "periodic patch without a partner; declare the pair on one side with "
                                   "`partner: <other>` and `angle_deg: <degrees>`");
      } else if (pairs[i].size() == 1 && !notes_[i].has_angle) {
        p.partner = pairs[i][0];
      } else if (pairs[i].size() == 1 && !has_axis_) {
        reader_.error(p.line, key, cat("the periodic pair ", p.name, "/", pairs[i][0],
                                       " needs the top-level axis (the axis of the rotation), e.g. ", kAxisExample));
      }
    }
  }

  /// A planar table belongs to a 2D mesh, cartesian and meridional ones to a 3D mesh; with an
  /// axis, planar and meridional tables go together too (a 2D axisymmetric case; the mesh
  /// decides, check_case_against_mesh).
  void check_tables_agree() {
    const PatchSpec* first = nullptr;
    for (const PatchSpec& p : c_.patches) {
      if (!p.deflection) continue;
      if (first == nullptr) first = &p;
      const SampleFrame mine = p.deflection->samples.frame;
      const SampleFrame theirs = first->deflection->samples.frame;
      const bool axisymmetric_2d = has_axis_ && mine != SampleFrame::cartesian && theirs != SampleFrame::cartesian;
      if ((mine == SampleFrame::planar) != (theirs == SampleFrame::planar) && !axisymmetric_2d) {
        reader_.error(p.deflection->line, cat("patches.", p.name, ".deflection"),
                      cat("its table is ", geometry::to_string(mine), " but the table of patch '", first->name,
                          "' (line ", std::to_string(first->deflection->line), ") is ", geometry::to_string(theirs),
                          "; planar tables are for 2D meshes, the others for 3D meshes"));
      }
    }
  }

  Case c_;
  fs::path folder_;
  Problems problems_;
  Reader reader_;
  std::vector<PatchNotes> notes_;  ///< parallel to c_.patches
  bool has_cad_ = false;
  bool has_axis_ = false;
};

}  // namespace

const PatchSpec* Case::find_patch(std::string_view name) const {
  const auto it = std::find_if(patches.begin(), patches.end(), [&](const PatchSpec& p) { return p.name == name; });
  return it == patches.end() ? nullptr : &*it;
}

std::vector<std::filesystem::path> Case::inputs() const {
  std::vector<std::filesystem::path> files{file};
  const std::vector<std::filesystem::path> mesh_files = mesh_input_files(mesh);
  files.insert(files.end(), mesh_files.begin(), mesh_files.end());
  if (cad) files.push_back(*cad);
  if (restart) files.push_back(*restart);
  for (const PatchSpec& p : patches) {
    if (!p.deflection) continue;
    const std::vector<std::filesystem::path>& read = p.deflection->files;
    for (const std::filesystem::path& f : read.empty() ? std::vector{p.deflection->file} : read) {
      if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
    }
  }
  return files;
}

Case parse_case(std::string_view text, const std::filesystem::path& file) { return CaseParser(file).parse(text); }

Case read_case(const std::filesystem::path& file) { return parse_case(read_file(file), file); }

void check_case_against_mesh(const Case& c, const mesh::Mesh& mesh) {
  Problems problems;
  std::vector<std::string> mesh_names;
  for (const mesh::Patch& p : mesh.patches) {
    mesh_names.push_back(p.name);
    if (c.find_patch(p.name) == nullptr) {
      problems.add(c.patches_line, "patches",
                   cat("mesh patch '", p.name, "' has no role; add `", p.name, ": {role: ...}` under patches"));
    }
  }
  const auto dimension_name = [](int d) { return d == 2 ? "2D" : "3D"; };
  for (const PatchSpec& spec : c.patches) {
    const std::string key = "patches." + spec.name;
    if (mesh.find_patch(spec.name) == nullptr) {
      problems.add(spec.line, key,
                   cat("no patch '", spec.name, "' in the mesh ", c.mesh.filename().string(), "; its patches are: ",
                       mesh_names.empty() ? std::string("(none)") : join(mesh_names)));
    }
    if (!spec.deflection) continue;
    const DeflectionSpec& d = *spec.deflection;
    if (mesh.dimension == 2 && d.mode != WallMode::automatic) {
      problems.add(d.line, key + ".deflection.mode",
                   "is for the walls of 3D meshes (a surface of revolution or CAD faces); a 2D wall is a curve");
    }
    if (mesh.dimension == 3 && !d.edges.empty()) {
      problems.add(d.line, key + ".deflection.edges",
                   "CAD edges are the walls of 2D cases (curves in the plane z = 0); a 3D wall is on CAD faces: "
                   "give them, `faces: [...]`");
    }
    if (mesh.dimension == 2 && !d.faces.empty() && !c.axis) {
      problems.add(d.line, key + ".deflection.faces",
                   cat("CAD faces are surfaces: a 2D case takes them only when it is axisymmetric, with the "
                       "top-level axis (the mesh's x, y are then z, r about it; ", kAxisExample,
                       "); a planar 2D wall is CAD edges in the plane z = 0, `edges: [...]` (hotmesh cad lists "
                       "them)"));
    }
    const SampleFrame frame = d.samples.frame;
    // 2D axisymmetric cases (an axis) take meridional tables too: (r, z) becomes (x, y) = (z, r).
    const bool axial_plane = mesh.dimension == 2 && c.axis && frame == SampleFrame::meridional;
    const int wanted = frame == SampleFrame::planar ? 2 : 3;
    if (mesh.dimension != wanted && !axial_plane) {
      problems.add(d.line, key + ".deflection",
                   cat("a ", geometry::to_string(frame), " table is for ", dimension_name(wanted),
                       " meshes but the mesh is ", dimension_name(mesh.dimension), "; give its columns as ",
                       mesh.dimension == 2 ? "x,y,dx,dy (or r,z,dr,dz in an axisymmetric case, with the axis)"
                                           : "x,y,z,dx,dy,dz or r,z,dr,dz"));
    }
  }
  if (!problems.empty()) problems.raise(c.file.string());
}

}  // namespace hotmesh::io
