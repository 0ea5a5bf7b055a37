// hotmesh app: what `hotmesh check` measures each mesh patch against. A patch mapped to CAD
// faces is compared with the faces: with their meridional curve (eq. 20) about the axis when
// they are surfaces of revolution (the way hotmesh deform sees them), else with the faces'
// surfaces themselves. A patch with a deflection table is compared with the deflected shape
// reconstructed through the FEM nodes (section 4.2, eq. 21), on the CAD curve or, without
// faces, on the curve the nodes define; the mesh is then the deformed one.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hotmesh/deform/mesh.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::app {

/// Distance of points to the reference shape of one patch.
class PatchReference {
 public:
  virtual ~PatchReference() = default;
  /// Distance of `p` (mesh coordinates) to the shape.
  virtual double distance(const geometry::Vec3& p) = 0;
  /// What the shape is, for reports: "meridional curve of CAD faces 1, 2 about ...".
  virtual std::string description() const = 0;
};

struct PatchCheckSpec {
  std::string patch;
  std::vector<int> faces;                               ///< CAD faces; empty: none mapped
  std::optional<std::filesystem::path> deflection;      ///< FEM deflection table
};

struct ReferenceOptions {
  std::optional<geometry::Axis> axis;  ///< overrides the faces' axes; needed for tables without CAD in 3D
  geometry::LengthUnit unit = geometry::LengthUnit::metre;
  geometry::ReconstructionOptions reconstruction;
};

/// The reference of one patch. `cad` is null when no CAD file was given (then the spec has no
/// faces). Throws hotmesh::InputError naming the patch for anything that does not fit.
std::unique_ptr<PatchReference> make_patch_reference(const PatchCheckSpec& spec, const geometry::CadModel* cad,
                                                     const deform::Mesh& mesh, const ReferenceOptions& options);

}  // namespace hotmesh::app
