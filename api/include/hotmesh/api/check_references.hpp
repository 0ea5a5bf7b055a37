// hotmesh api: what `hotmesh check` measures each mesh patch against. On a 2D mesh a patch is
// mapped to CAD edges, and compared with their curve in the plane z = 0, or, given an axis (an
// axisymmetric mesh in (z, r)), to CAD faces, compared with their meridional curve as (z, r).
// Otherwise a patch mapped to CAD faces is compared with the faces as hotmesh deform would take
// them (faces_mode.hpp; --mode forces one way): with their meridional curve (eq. 20) about the axis when every face turns
// about one axis, else with the faces' surfaces themselves; faces whose meridional curves form
// several separate profiles (a casing on either side of a blade row) give one part per
// profile, and each node is measured against the nearest part. A patch with a deflection table
// is compared with the deflected shape reconstructed through the FEM nodes: on the CAD curve
// (section 4.2, eq. 21), on CAD faces that are no surface of revolution as a field d(t, s) on
// each face, or, without faces, on the curve the nodes define; the mesh is then the deformed
// one. With a case file the shapes are those hotmesh deform builds for the case
// (setup::set_up_case), undeformed or deflected: curves, CAD faces deflected by a field d(t, s)
// each, or a table interpolated over a wall without CAD faces. Shapes that are curves (in the
// x-y plane, or meridional curves of surfaces of revolution) and walls on CAD faces, deflected
// or not, also measure the patch's faces, both ways (wall_deviation_report.hpp); the table
// interpolated over a wall has no surface to measure them against, and says so.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/api/wall_deviation_report.hpp"

namespace hotmesh::api {

/// One shape some nodes are measured against.
class ReferenceShape {
 public:
  virtual ~ReferenceShape() = default;
  /// Distance of `p` (mesh coordinates) to the shape.
  virtual double distance(const geometry::Vec3& p) = 0;
  /// What the shape is, for reports: "CAD faces 1, 2: their meridional curve about ...".
  virtual std::string description() const = 0;
  /// The two-sided distance between `faces` of `mesh` and the shape (wall_deviation_report.hpp),
  /// or why it is not measured.
  virtual WallCheck wall(const mesh::Mesh& mesh, const geometry::WallFaces& faces) = 0;
};

/// What one patch is measured against: one shape, or one per separate part.
struct PatchReference {
  std::string description;                             ///< the whole, for reports
  std::vector<std::unique_ptr<ReferenceShape>> parts;  ///< at least one
};

struct PatchCheckSpec {
  std::string patch;
  std::vector<int> faces;                               ///< CAD faces (edges on a 2D mesh without axis); empty: none mapped
  std::optional<std::filesystem::path> deflection;      ///< FEM deflection table
};

struct ReferenceOptions {
  /// The axis CAD faces must turn about to be measured meridionally (default: one they share);
  /// needed for tables without CAD in 3D.
  std::optional<geometry::Axis> axis;
  io::WallMode mode = io::WallMode::automatic;  ///< how CAD faces are taken (faces_mode.hpp)
  geometry::LengthUnit unit = geometry::LengthUnit::metre;
  geometry::ReconstructionOptions reconstruction;
};

/// The reference of one patch. `cad` is null when no CAD file was given (then the spec has no
/// faces). Throws hotmesh::InputError naming the patch for anything that does not fit.
PatchReference make_patch_reference(const PatchCheckSpec& spec, const geometry::CadModel* cad,
                                    const mesh::Mesh& mesh, const ReferenceOptions& options);

/// Which shape of a case's boundaries a mesh is compared with.
enum class CaseStage {
  undeformed,  ///< the case's own mesh: its walls as the CAD faces, tables or nodes give them
  deflected,   ///< a mesh deformed by hotmesh deform: the walls the FEM deflections give
};

struct CasePatchReference {
  std::string patch;
  PatchReference reference;
};

/// The references of every patch of a case that follows a boundary (prescribed and sliding
/// patches), in the order of the case file: the shapes hotmesh deform builds for the case from
/// its own (undeformed) mesh `case_mesh`, at the stage asked for. Throws hotmesh::InputError
/// as hotmesh deform's set-up does.
std::vector<CasePatchReference> case_references(const io::Case& c, const mesh::Mesh& case_mesh, CaseStage stage);

}  // namespace hotmesh::api
