// hotmesh api: the public library (libhotmesh, CMake package `hotmesh`, target hotmesh::hotmesh).
// A coupling loop moves its CFD mesh in memory, as `hotmesh deform` does from files:
//
//   hotmesh::Case c("ramp2d-sliding.yaml");               // mesh, patches, CAD, solver settings
//   c.set_deflection("bottom", nodes, displacements, 2);  // the FEM's deflection of a wall
//   hotmesh::Result r = c.deform();                       // the motion (section 4 of the paper)
//   r.points(); r.min_scaled_jacobian(); r.report();      // the moved mesh, its quality, report.json
//   r.write("out");                                       // the files `hotmesh deform` writes
//   hotmesh::Result next = c.deform(r);                   // the next iteration continues from r (4.3)
//
// The types here are the library's whole interface: none of its dependencies (Eigen,
// OpenCASCADE, PETSc, yaml-cpp) shows. A mistake in what the caller gave (a file, a case key,
// an argument) throws hotmesh::InputError (the command's exit code 2) with the text the
// command prints; a motion that fails is a Result whose success() is false, as the command's
// exit code 1. Reference: docs/library.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "hotmesh/core/input_error.hpp"

#define HOTMESH_PUBLIC __attribute__((visibility("default")))

namespace hotmesh {

/// hotmesh's version, "0.1.0".
HOTMESH_PUBLIC std::string version();

/// How much the library logs on stderr (the command's -q, default and -v).
enum class Verbosity { quiet, warnings, info, debug };
HOTMESH_PUBLIC void set_verbosity(Verbosity verbosity);

/// A node's position.
struct Point {
  double x = 0.0, y = 0.0, z = 0.0;
};

/// How the columns of a deflection's node coordinates are read (as the tables' columns are,
/// docs/case-file.md): planar x, y (2D cases), cartesian x, y, z, or meridional r, z about the
/// case's axis. automatic: planar for two columns of a 2D case, meridional for two columns of
/// a 3D case, cartesian for three.
enum class Frame { automatic, planar, cartesian, meridional };

/// Where the motion is: after each Newton step (`newton_iteration` > 0) and after each
/// increment (`newton_iteration` 0, `min_scaled_jacobian` of the mesh it reached). After the
/// case's `increments`, the corner passes of sliding walls (`corner_pass`; increment
/// increments + 1, + 2, ...).
struct Progress {
  int increment = 0;
  int increments = 0;  ///< the case's
  bool corner_pass = false;
  int newton_iteration = 0;
  double residual_reduction = 0.0;   ///< of the increment's initial residual
  double min_scaled_jacobian = 0.0;  ///< after an increment
  bool accepted = true;              ///< after an increment: false if it was rejected (then split)
};
using ProgressCallback = std::function<void(const Progress&)>;

/// The mesh's quality as a flow solver sees it (report.json's `solver_quality`).
struct Quality {
  double min_scaled_jacobian = 0.0;
  std::size_t inverted_cells = 0;
  double max_non_orthogonality = 0.0;  ///< degrees
  double mean_non_orthogonality = 0.0;
  std::size_t severely_non_orthogonal_faces = 0;  ///< above 70 degrees
  double max_skewness = 0.0;
  double max_volume_ratio = 0.0;
  double max_aspect_ratio = 0.0;
};

class Case;

/// A moved mesh: the outcome of Case::deform().
class HOTMESH_PUBLIC Result {
 public:
  Result(Result&&) noexcept;
  Result& operator=(Result&&) noexcept;
  Result(const Result&) = delete;
  Result& operator=(const Result&) = delete;
  ~Result();

  /// false: the motion failed; points() is the last valid mesh, message() says why.
  bool success() const;
  const std::string& message() const;
  /// The stage the mesh reached: 1 on success.
  double stage() const;
  int dimension() const;  ///< 2 or 3
  /// Every node where the motion left it, in the mesh file's order (z = 0 in 2D).
  std::span<const Point> points() const;
  /// The mesh file's node ids, in the same order.
  std::span<const std::int64_t> node_ids() const;
  /// The scaled Jacobian of each cell.
  std::span<const double> scaled_jacobians() const;
  double min_scaled_jacobian() const;
  Quality quality() const;
  /// report.json as `hotmesh deform` writes it (without the files written: see write()).
  std::string report() const;
  /// Writes what `hotmesh deform` writes into `folder` (created if need be): deformed.msh,
  /// deformed.vtu, pictures of a 2D mesh, the mesh in its own format if read from another,
  /// restart.hmr, report.json. Refuses (InputError) a folder that holds the case's inputs.
  void write(const std::filesystem::path& folder) const;

  struct State;  ///< the library's own (docs/library.md: pimpl)

 private:
  friend class Case;
  explicit Result(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

/// A case: a mesh, the roles of its patches, their deflections and the solver's settings.
class HOTMESH_PUBLIC Case {
 public:
  /// Reads and checks a case file (docs/case-file.md) and the tables it names.
  explicit Case(const std::filesystem::path& case_file);
  /// A case built in code: the mesh file and the role of each of its patches ("fixed",
  /// "sliding", "slip", "passive", ...), moved in `increments` increments; read as the case
  /// file they make, so checked the same way (a `prescribed` patch, whose table is part of its
  /// role, needs a case file). Messages and reports name it <mesh folder>/<mesh name>.yaml.
  static Case from_mesh(const std::filesystem::path& mesh, const std::vector<std::pair<std::string, std::string>>& roles,
                        int increments = 16);
  Case(Case&&) noexcept;
  Case& operator=(Case&&) noexcept;
  Case(const Case&) = delete;
  Case& operator=(const Case&) = delete;
  ~Case();

  const std::filesystem::path& file() const;
  std::filesystem::path mesh_file() const;
  std::vector<std::string> patches() const;
  /// The patch's role ("fixed", "sliding", ...).
  std::string role(const std::string& patch) const;

  /// The deflection of `patch`'s wall, as a table gives it: row j of `nodes` (`columns` values
  /// each) an FEM node of the undeformed wall, row j of `displacements` (as many) its
  /// deflection. Replaces the case file's table, keeping its degree and form. Throws
  /// InputError for a patch that takes no deflection, counts that do not match, values that
  /// are not finite.
  void set_deflection(const std::string& patch, std::span<const double> nodes, std::span<const double> displacements,
                      int columns, Frame frame = Frame::automatic);
  /// The deflection of `patch` from CalculiX results: the .frd, the .inp that defines the node
  /// set `node_set` (or surface) on the wall, as the case file's `calculix:` key reads them.
  void set_calculix_deflection(const std::string& patch, const std::filesystem::path& frd,
                               const std::filesystem::path& inp, const std::string& node_set);

  /// OpenMP threads of the motion; 0 (the default): the case's solver.threads, else
  /// OMP_NUM_THREADS, else as many as the mesh's size pays for. Taken by the first deform().
  void set_threads(int threads);
  /// Called from the motion's thread after each Newton step and increment.
  void set_progress(ProgressCallback progress);

  /// Moves the mesh onto the deflected walls, from the undeformed mesh (or from the case
  /// file's `restart:`).
  Result deform() const;
  /// The next coupling iteration: continues from `previous`, a result of this case's mesh,
  /// to this case's deflections (section 4.3, as the case file's `restart:` does with
  /// previous's restart.hmr).
  Result deform(const Result& previous) const;

 private:
  struct State;
  explicit Case(std::unique_ptr<State> state);
  Result run(const Result* previous) const;
  std::unique_ptr<State> state_;
};

/// One patch's outcome in a check.
struct PatchCheck {
  std::string patch;
  std::size_t nodes = 0;
  double max_distance = 0.0;  ///< of a node from its wall
  double mean_distance = 0.0;
  std::int64_t worst_node = 0;
  double wall_distance = -1.0;  ///< the faces' two-sided distance; < 0: not measured
  bool passed = true;
};

struct CheckResult {
  bool passed = true;
  double tolerance = 0.0;
  std::vector<PatchCheck> patches;
  std::string text;  ///< as `hotmesh check` prints it
  std::string json;  ///< as `hotmesh check --format json` writes it
};

/// `hotmesh check MESH --case CASE`: every patch of the case that follows a wall, measured
/// against the walls hotmesh deform builds (deflected for a mesh the case was deformed into,
/// undeformed for the case's own mesh: `mesh` empty). `tolerance` 0: 1e-6 of the mesh's
/// size; `wall_tolerance` 0: the faces' distance reported only.
HOTMESH_PUBLIC CheckResult check(const std::filesystem::path& mesh, const std::filesystem::path& case_file,
                                 double tolerance = 0.0, double wall_tolerance = 0.0);

}  // namespace hotmesh
