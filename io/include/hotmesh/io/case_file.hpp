// hotmesh io: the case file (YAML) that describes one deformation job. It is validated
// completely before any work starts: unknown keys, wrong types, values out of range, missing
// files and inconsistent patch roles are all reported together in one message naming each
// YAML line. Paths are relative to the case file. Full schema: docs/case-file.md.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/deform/solver_options.hpp"
#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/deflected_curve.hpp"
#include "hotmesh/geometry/deflection_samples.hpp"
#include "hotmesh/io/calculix.hpp"

namespace hotmesh::io {

/// The role of a patch (fixed, prescribed, slip, sliding, passive, periodic): the solver's.
using PatchRole = deform::BoundaryRole;

/// Bounds of solver.increments and solver.max_increment_splits (docs/case-file.md, solver):
/// far beyond any real need (the paper takes 16 increments), low enough that a mistyped value
/// is refused at once instead of running for days. Each increment is a whole Newton cycle and
/// leaves a record in report.json and in every later checkpoint; a piece of 1/2^20 of an
/// increment is a millionth of it.
inline constexpr int kMaxIncrements = 10'000;
inline constexpr int kMaxIncrementSplits = 20;

/// Where a `calculix:` deflection was read: the selection and the step it found.
struct CalculixNote {
  CalculixSelection selection;
  ModelKind kind = ModelKind::solid;
  int step = 0;
  double time = 0.0;
  std::optional<double> min_temperature, max_temperature;  ///< of the set's nodes, if the .frd has NDTEMP
};

/// How the deflected wall of a 3D patch is reconstructed (the deflection's `mode` key).
enum class WallMode {
  automatic,   ///< meridional where the walls are surfaces of revolution about the axis, else surface
  meridional,  ///< a surface of revolution: the meridional curve about the case's axis (section 4.2, Fig. 4)
  surface,     ///< the CAD faces themselves, d(t, s) per face; without faces, the table interpolated (prescribed)
};
inline constexpr EnumNames<WallMode, 3> kWallModeNames{{{{WallMode::automatic, "auto"},
                                                                   {WallMode::meridional, "meridional"},
                                                                   {WallMode::surface, "surface"}}}};

struct DeflectionSpec {
  std::filesystem::path file;           ///< the table (or the .frd), resolved against the case file's folder
  /// Every file the table was read from: the table, or the .frd, the .inp and its *INCLUDEs.
  std::vector<std::filesystem::path> files;
  std::optional<CalculixNote> calculix; ///< set when the table comes from CalculiX results
  int degree = 1;                       ///< B-spline degree q of the reconstruction, 1..5
  geometry::DeflectionForm form = geometry::DeflectionForm::curve;  ///< eq. (21), or c = r + d
  std::vector<int> faces;               ///< CAD face ids (1-based); needs `cad`
  /// CAD edge ids (1-based; 2D cases, instead of faces): the wall is their curve in the plane z = 0
  std::vector<int> edges;
  WallMode mode = WallMode::automatic;  ///< 3D walls: meridional or on the faces themselves
  geometry::DeflectionSamples samples;  ///< the table, read during validation
  std::size_t line = 0;                 ///< line of the `deflection` key in the case file
};

struct PatchSpec {
  std::string name;
  PatchRole role = PatchRole::fixed;
  std::optional<DeflectionSpec> deflection;  ///< prescribed (required), sliding (optional)
  std::string partner;                       ///< periodic: the other patch of the pair (set on both sides)
  double angle_deg = 0.0;                    ///< periodic: rotation from this patch to partner;
                                             ///< non-zero only on the side that declares the pair
  deform::FeatureOptions features;           ///< sliding: the corners of the wall its nodes hold
  std::size_t line = 0;                      ///< line of this patch in the case file
};

/// A picture of the deformed 2D mesh to write, named `<name>.png`, showing a world window.
struct PictureView {
  std::string name;
  double xmin = 0.0, xmax = 0.0, ymin = 0.0, ymax = 0.0;
  std::size_t line = 0;
};

struct Case {
  // Every path is absolute and lexically normal; relative ones were resolved against the
  // folder of the case file.
  std::filesystem::path file;                ///< the case file
  std::filesystem::path mesh;
  std::optional<std::filesystem::path> cad;
  /// Unit of the mesh and the deflection tables; the CAD file is converted to it on import.
  geometry::LengthUnit length_unit = geometry::LengthUnit::metre;
  std::filesystem::path output;              ///< default: <case name>-out beside the case file
  /// Write the mesh and the deflected walls after every increment, as ParaView time series
  /// (`output: {series: true}`).
  bool series = false;
  std::optional<geometry::Axis> axis;
  /// The solver's options; `linear` defaults to auto (choose_linear_solver picks by the mesh),
  /// `predictor` to on.
  deform::SolverOptions solver = [] {
    deform::SolverOptions s;
    s.linear = deform::LinearSolverKind::automatic;
    s.predictor = true;
    return s;
  }();
  /// OpenMP threads of the run, 0: hotmesh chooses (parallel::choose_threads). The case file
  /// sets it among the solver's options (solver.threads); it is the process's.
  int threads = 0;
  deform::MaterialOptions material;
  std::vector<PatchSpec> patches;            ///< in the order of the case file
  std::size_t patches_line = 0;              ///< line of the `patches:` key
  std::vector<PictureView> pictures;         ///< close-ups to draw (2D meshes)
  /// The state of a previous run to continue from (its restart.hmr): the next coupling
  /// iteration with new deflections (section 4.3).
  std::optional<std::filesystem::path> restart;

  const PatchSpec* find_patch(std::string_view name) const;
  /// Every file the case reads: the case file, mesh, CAD file, restart file and deflection
  /// tables (CalculiX: the .frd, the .inp and its *INCLUDEs), each once, in that order.
  std::vector<std::filesystem::path> inputs() const;
};

/// Parses and validates a case file given as text; `file` is its path (for messages and to
/// resolve relative paths). Reads the deflection tables it names. Throws hotmesh::InputError
/// listing every problem found, one per line in file order, each as
/// "<file>:<line>: <key path>: <what is wrong>" with <file> the absolute case file path.
Case parse_case(std::string_view text, const std::filesystem::path& file);
Case read_case(const std::filesystem::path& file);

/// Checks the case against the mesh it names: every mesh patch has a role and every case
/// patch exists in the mesh. Throws hotmesh::InputError listing each problem with its line.
void check_case_against_mesh(const Case& c, const mesh::Mesh& mesh);

}  // namespace hotmesh::io
