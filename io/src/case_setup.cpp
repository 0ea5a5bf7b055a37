// hotmesh io: case + mesh -> patch motions with reconstructed deflected shapes.
#include "hotmesh/io/case_setup.hpp"

#include <memory>

#include <fmt/format.h>

#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/input_error.hpp"

namespace hotmesh::io {
namespace {

geometry::Reconstruction reconstruct(const DeflectionSpec& d, const geometry::CurveSamples& samples) {
  geometry::ReconstructionOptions options;
  options.degree = d.degree;
  return geometry::reconstruct_from_nodes(samples, options);
}

std::vector<geometry::Vec2> outline(const geometry::DeflectedCurve& curve) {
  constexpr int kSamples = 2000;
  std::vector<geometry::Vec2> points;
  const double a = curve.first_parameter(), b = curve.last_parameter();
  for (int i = 0; i <= kSamples; ++i) points.push_back(curve.point(a + (b - a) * i / kSamples, 1.0));
  return points;
}

std::shared_ptr<const geometry::BoundaryShape> deflected_shape(const Case& c, const PatchSpec& spec,
                                                               const deform::Mesh& mesh, ShapeReport& report) {
  const DeflectionSpec& d = *spec.deflection;
  if (mesh.dimension == 2) {
    auto rebuilt = reconstruct(d, geometry::planar_samples(d.samples));
    report.reconstruction = rebuilt.report;
    report.deflected_outline = outline(rebuilt.curve);
    return std::make_shared<geometry::PlanarCurveShape>(std::move(rebuilt.curve));
  }
  if (!c.axis) {
    throw InputError::in(c.file.string(), fmt::format("patch '{}': 3D deflections describe surfaces of revolution; "
                                                      "give the case's axis (axis: {{origin: [...], direction: [...]}})",
                                                      spec.name));
  }
  auto rebuilt = reconstruct(d, geometry::meridional_samples(d.samples, *c.axis));
  report.reconstruction = rebuilt.report;
  report.deflected_outline = outline(rebuilt.curve);
  return std::make_shared<geometry::RevolvedShape>(std::move(rebuilt.curve), *c.axis);
}

}  // namespace

CaseSetup set_up_case(const Case& c, const deform::Mesh& mesh) {
  CaseSetup setup;
  for (const PatchSpec& spec : c.patches) {
    deform::PatchMotion motion{spec.name, spec.role, nullptr, 0.0};
    if (spec.deflection) {
      ShapeReport report{spec.name, {}};
      try {
        motion.shape = deflected_shape(c, spec, mesh, report);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: patch '{}': {}", spec.deflection->file.string(), spec.name, e.what()));
      }
      setup.shapes.push_back(std::move(report));
    }
    setup.motions.push_back(std::move(motion));
  }
  return setup;
}

}  // namespace hotmesh::io
