// hotmesh io: from a validated case and its mesh to what the solver needs. For every patch
// its role and, for patches that follow an FEM deflection, the deflected boundary shape
// reconstructed from the table (the paper's section 4.2): in 2D a curve in the x-y plane
// through the FEM nodes; in 3D a surface of revolution about the case's axis, its meridional
// curve r(t) taken from the CAD faces named in the case or, without them, the curve through
// the FEM nodes.
#pragma once

#include <string>
#include <vector>

#include "hotmesh/deform/mesh.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/case_file.hpp"

namespace hotmesh::io {

/// How the deflected shape of one patch was built, for the run's report.
struct ShapeReport {
  std::string patch;
  geometry::ReconstructionReport reconstruction;
  /// The fully deflected curve c(t), densely sampled in its plane ((x, y) in 2D, (r, z) about
  /// the axis in 3D), for pictures.
  std::vector<geometry::Vec2> deflected_outline;
};

struct CaseSetup {
  std::vector<deform::PatchMotion> motions;  ///< one per patch of the case
  std::vector<ShapeReport> shapes;           ///< one per patch with a deflection table
};

/// Throws hotmesh::InputError (naming the patch and the table) when a table cannot describe
/// its patch: wrong frame for the mesh, FEM nodes off the CAD curve, too few nodes, ...
CaseSetup set_up_case(const Case& c, const deform::Mesh& mesh);

}  // namespace hotmesh::io
