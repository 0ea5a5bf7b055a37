// hotmesh setup: from a validated case and its mesh to what the solver needs. For every patch
// its role and, for patches that follow a boundary, the boundary's shape (the paper's section
// 4.2): in 2D a curve in the x-y plane; in 3D a surface of revolution about the case's axis
// (meridional), or the CAD faces themselves (surface). A curve r(t) comes from CAD: the faces'
// meridional curve, or in 2D the CAD edges named in the case (their curve in the plane z = 0);
// else from the FEM nodes of the table (or, for a sliding patch without table, from the patch's
// own nodes); the deflected curve is reconstructed through the FEM deflections (eq. 21). On
// faces, a deflection field d(t, s) is fitted per face; a prescribed 3D wall without faces or
// axis moves by the table interpolated over it (ScatteredShape).
//
// A 2D case with an axis is axisymmetric: its mesh's (x, y) are (z, r) about the axis, z the
// signed distance along it from its origin and r the distance from it (an OpenFOAM wedge case
// flattened, or a mesh drawn in the meridional half plane). Its walls on CAD faces are their
// meridional curves, and its meridional (r, z) tables are taken, in that plane, as (z, r).
//
// A 3D wall is meridional when its deflection says `mode: meridional`, or by default when its
// table is meridional, or when the case has an axis and the wall's faces (if any) are
// surfaces of revolution about it; otherwise it is a surface.
//
// A restarted run (section 4.3) continues from where the previous one left the boundaries:
// each shape then goes from the previous deflected curve (stage 0) to the new one (stage 1),
// in the parameter of the undeformed curve.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/linear_field.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/geometry/scattered_field.hpp"
#include "hotmesh/geometry/surface_shape.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/restart_file.hpp"

namespace hotmesh::setup {

/// What a patch's deflected wall was built as.
enum class WallKind {
  curve,      ///< a curve: in the x-y plane (2D) or the meridional curve of a surface of revolution
  faces,      ///< CAD faces with a deflection field each
  scattered,  ///< the table interpolated over the wall (prescribed, no CAD faces): linearly (degree 1) or smoothly
};
/// The names report.json uses.
inline constexpr EnumNames<WallKind, 3> kWallKindNames{
    {{{WallKind::curve, "curve"}, {WallKind::faces, "faces"}, {WallKind::scattered, "scattered"}}}};

/// How the deflected shape of one patch was built, for the run's report.
struct ShapeReport {
  std::string patch;
  WallKind kind = WallKind::curve;
  /// Of a curve; of the others, the counts (nodes, used_nodes, degree) and distances that
  /// apply to them.
  geometry::ReconstructionReport reconstruction;
  std::optional<geometry::SurfaceReconstructionReport> faces;  ///< kind faces
  std::optional<geometry::ScatteredFieldReport> scattered;     ///< kind scattered, degree above 1
  std::optional<geometry::LinearFieldReport> linear;           ///< kind scattered, degree 1
  /// A curve's deflected shape at the end of the run, densely sampled in its plane ((x, y) in
  /// 2D, (r, z) about the axis in 3D), for pictures; empty for other kinds.
  std::vector<geometry::Vec2> deflected_outline;
};

struct CaseSetup {
  std::vector<deform::PatchMotion> motions;  ///< one per patch of the case
  std::vector<ShapeReport> shapes;           ///< one per patch with a deflection table
};

/// The case's CAD file read and checked (every face translated, in the case's length unit),
/// or nothing if the case names none. Throws hotmesh::InputError naming the file.
std::optional<geometry::CadModel> read_case_cad(const io::Case& c);

/// Throws hotmesh::InputError (naming the case file's line of the patch, and the table or CAD
/// file at fault) when a table cannot describe its patch: wrong frame for the mesh, FEM nodes
/// off the CAD curve, too few nodes, patch roles that differ from the run being restarted, ...
/// `cad` is the case's CAD model if already read (read_case_cad); else it is read if needed.
CaseSetup set_up_case(const io::Case& c, const mesh::Mesh& mesh, const io::RestartState* previous = nullptr,
                      const geometry::CadModel* cad = nullptr);

}  // namespace hotmesh::setup
