// hotmesh io: case + mesh -> patch motions with reconstructed deflected shapes.
#include "hotmesh/io/case_setup.hpp"

#include <algorithm>
#include <map>
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

/// The nodes of a 2D patch in order along it, following its edges; closed curves repeat their
/// first node at the end.
std::vector<deform::NodeId> chain_patch(const deform::Patch& patch, const deform::Mesh& mesh) {
  std::map<deform::NodeId, std::vector<deform::NodeId>> next;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto e = patch.faces.nodes(f);
    next[e[0]].push_back(e[1]);
    next[e[1]].push_back(e[0]);
  }
  deform::NodeId start = next.begin()->first;
  for (const auto& [node, neighbours] : next) {
    if (neighbours.size() > 2) {
      throw InputError(fmt::format("patch '{}' branches at node {}: a sliding patch must be a single curve",
                                   patch.name, mesh.node_id(node)));
    }
    if (neighbours.size() == 1) start = node;
  }
  std::vector<deform::NodeId> chain{start};
  deform::NodeId previous = -1, current = start;
  while (true) {
    const auto& neighbours = next[current];
    const auto it = std::find_if(neighbours.begin(), neighbours.end(), [&](deform::NodeId n) { return n != previous; });
    if (it == neighbours.end() || (*it == start && chain.size() > 2)) {
      if (it != neighbours.end()) chain.push_back(start);  // closed
      break;
    }
    previous = current;
    current = *it;
    chain.push_back(current);
    if (chain.size() > next.size() + 1) break;
  }
  const std::size_t distinct = chain.front() == chain.back() ? chain.size() - 1 : chain.size();
  if (distinct != next.size()) {
    throw InputError(fmt::format("patch '{}' is made of several separate curves: give each its own patch to slide on",
                                 patch.name));
  }
  return chain;
}

/// The patch's own undeformed shape, for a sliding patch without deflection table: the
/// polyline through its nodes (2D), or the meridional polyline of its nodes about the axis.
std::shared_ptr<const geometry::BoundaryShape> own_shape(const Case& c, const PatchSpec& spec,
                                                         const deform::Mesh& mesh) {
  const deform::Patch& patch = *mesh.find_patch(spec.name);
  if (mesh.dimension == 2) {
    const auto chain = chain_patch(patch, mesh);
    std::vector<geometry::Vec2> points;
    std::vector<double> parameters{0.0};
    for (deform::NodeId n : chain) {
      const auto& p = mesh.points[static_cast<std::size_t>(n)];
      if (!points.empty()) parameters.push_back(parameters.back() + distance(points.back(), {p.x, p.y}));
      points.push_back({p.x, p.y});
    }
    for (double& t : parameters) t /= parameters.back();
    return std::make_shared<geometry::PlanarCurveShape>(
        geometry::DeflectedCurve(geometry::BSplineCurve2d::polyline(parameters, points)));
  }
  if (!c.axis) {
    throw InputError::in(c.file.string(), fmt::format("patch '{}': a 3D sliding patch slides over a surface of "
                                                      "revolution; give the case's axis",
                                                      spec.name));
  }
  geometry::CurveSamples samples;
  samples.source = fmt::format("the nodes of patch '{}'", spec.name);
  for (deform::NodeId n : patch.nodes) {
    const auto cyl = c.axis->to_cylindrical(mesh.points[static_cast<std::size_t>(n)]);
    samples.points.push_back({cyl.r, cyl.z});
    samples.deflections.push_back({0.0, 0.0});
  }
  auto rebuilt = geometry::reconstruct_from_nodes(samples, {});
  return std::make_shared<geometry::RevolvedShape>(std::move(rebuilt.curve), *c.axis);
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
    } else if (spec.role == PatchRole::sliding) {
      motion.shape = own_shape(c, spec, mesh);
    }
    setup.motions.push_back(std::move(motion));
  }
  return setup;
}

}  // namespace hotmesh::io
