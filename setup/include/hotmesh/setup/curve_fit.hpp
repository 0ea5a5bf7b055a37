// hotmesh setup: section 4.2 from what a user gives, shared by `hotmesh curve` and `hotmesh serve`.
// The FEM nodes are taken into the plane of the boundary's curve ((r, z) about the axis of the
// CAD faces, or (x, y) for 2D tables) and the deflected curve is reconstructed (eq. 21) on the
// CAD meridional curve or, without CAD, on the curve the nodes themselves define.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/deflection_samples.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::setup {

/// A reconstruction and what it was made from.
struct CurveRun {
  geometry::Reconstruction fit;
  geometry::CurveSamples nodes;
  std::optional<geometry::Axis> axis;  ///< for (r, z) curves; none for 2D (x, y) curves
  geometry::LengthUnit unit = geometry::LengthUnit::metre;
  std::vector<int> faces;               ///< CAD faces along the curve; empty without CAD
  std::string cad;                      ///< CAD file, empty without CAD
  std::vector<int> edges;               ///< CAD edges along a 2D curve (instead of faces)
};

/// Throws hotmesh::InputError unless the table can lie on a CAD surface of revolution:
/// cartesian (x, y, z) or meridional (r, z); planar (x, y) tables are for 2D cases.
void require_cad_frame(const geometry::DeflectionSamples& samples);

/// With CAD: `curve` is the meridional curve of the boundary's faces (CadModel::meridional_curve)
/// and the nodes are cartesian (x, y, z) or meridional (r, z) about curve.axis. Throws
/// hotmesh::InputError for planar tables and for nodes the reconstruction refuses.
CurveRun fit_on_cad_curve(const geometry::MeridionalCurve& curve, const geometry::DeflectionSamples& samples,
                          const geometry::ReconstructionOptions& options, geometry::LengthUnit unit, std::string cad);

/// A 2D case's wall from CAD: `curve` lies in the mesh's plane (the edges' curve, or a 2D
/// axisymmetric mesh's meridional curve in its (x, y) = (z, r)); the nodes are planar (x, y) or,
/// with `axis` (axisymmetric), meridional (r, z) about it, taken as (z, r). The run has no
/// axis: its curve is a 2D one. Throws hotmesh::InputError for cartesian tables, meridional ones
/// without axis, and nodes the reconstruction refuses.
CurveRun fit_on_plane_cad_curve(const geometry::BSplineCurve2d& curve, const geometry::DeflectionSamples& samples,
                                const std::optional<geometry::Axis>& axis,
                                const geometry::ReconstructionOptions& options, geometry::LengthUnit unit,
                                std::string cad);

/// Without CAD: planar (x, y) tables define a 2D curve; cartesian or meridional tables a
/// meridional one about `axis` (required for cartesian tables, the z axis by default for
/// meridional ones). `axis_name` names the axis option in messages ("--axis", "\"axis\"").
CurveRun fit_without_cad(const geometry::DeflectionSamples& samples, std::optional<geometry::Axis> axis,
                         const geometry::ReconstructionOptions& options, geometry::LengthUnit unit,
                         std::string_view axis_name);

}  // namespace hotmesh::setup
