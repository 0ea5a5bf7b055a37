// hotmesh setup: section 4.2 from what a user gives (see curve_fit.hpp).
#include "hotmesh/setup/curve_fit.hpp"

#include <string>
#include <utility>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::setup {

void require_cad_frame(const geometry::DeflectionSamples& samples) {
  if (samples.frame == geometry::SampleFrame::planar) {
    throw InputError::in(samples.source, "a CAD boundary needs cartesian (x,y,z,dx,dy,dz) or meridional "
                                         "(r,z,dr,dz) nodes; planar (x,y) tables are for 2D cases without CAD");
  }
}

CurveRun fit_on_cad_curve(const geometry::MeridionalCurve& curve, const geometry::DeflectionSamples& samples,
                          const geometry::ReconstructionOptions& options, geometry::LengthUnit unit, std::string cad) {
  require_cad_frame(samples);
  geometry::CurveSamples nodes = geometry::curve_samples(samples, &curve.axis);
  geometry::Reconstruction fit = geometry::fit_curve(nodes, &curve.curve, options);
  return {std::move(fit), std::move(nodes), curve.axis, unit, curve.faces, std::move(cad)};
}

CurveRun fit_on_plane_cad_curve(const geometry::BSplineCurve2d& curve, const geometry::DeflectionSamples& samples,
                                const std::optional<geometry::Axis>& axis,
                                const geometry::ReconstructionOptions& options, geometry::LengthUnit unit,
                                std::string cad) {
  geometry::CurveSamples nodes;
  if (samples.frame == geometry::SampleFrame::planar) {
    nodes = geometry::planar_samples(samples);
  } else if (samples.frame == geometry::SampleFrame::meridional && axis) {
    nodes = geometry::axial_plane_samples(samples, *axis);
  } else {
    throw InputError::in(samples.source, "a 2D mesh's CAD wall needs planar (x,y,dx,dy) nodes, or meridional "
                                         "(r,z,dr,dz) ones with the axis of an axisymmetric case");
  }
  geometry::Reconstruction fit = geometry::fit_curve(nodes, &curve, options);
  return {std::move(fit), std::move(nodes), std::nullopt, unit, {}, std::move(cad), {}};
}

CurveRun fit_without_cad(const geometry::DeflectionSamples& samples, std::optional<geometry::Axis> axis,
                         const geometry::ReconstructionOptions& options, geometry::LengthUnit unit,
                         std::string_view axis_name) {
  if (samples.frame == geometry::SampleFrame::planar) {
    if (axis) {
      throw InputError(std::string(axis_name) +
                       " is for axisymmetric boundaries; the node table is planar (x, y)");
    }
  } else {
    if (!axis && samples.frame == geometry::SampleFrame::cartesian) {
      throw InputError::in(samples.source, "cartesian (x, y, z) nodes without CAD need " + std::string(axis_name));
    }
    if (!axis) axis = geometry::Axis();  // (r, z) as given; the z axis places the curves in 3D
  }
  geometry::CurveSamples nodes = geometry::curve_samples(samples, axis ? &*axis : nullptr);
  geometry::Reconstruction fit = geometry::fit_curve(nodes, nullptr, options);
  return {std::move(fit), std::move(nodes), axis, unit, {}, {}};
}

}  // namespace hotmesh::setup
