// hotmesh io: case + mesh (+ restart state) -> patch motions with their boundary shapes.
#include "hotmesh/io/case_setup.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/deflected_walls.hpp"

namespace hotmesh::io {
namespace {

using geometry::DeflectedCurve;

struct Curve {
  DeflectedCurve curve;
  geometry::ReconstructionReport report;
};

/// The nodes of a 2D patch in order along it, following its edges; closed curves repeat their
/// first node at the end.
std::vector<mesh::NodeId> chain_patch(const mesh::Patch& patch, const mesh::Mesh& mesh) {
  std::map<mesh::NodeId, std::vector<mesh::NodeId>> next;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto e = patch.faces.nodes(f);
    next[e[0]].push_back(e[1]);
    next[e[1]].push_back(e[0]);
  }
  mesh::NodeId start = next.begin()->first;
  for (const auto& [node, neighbours] : next) {
    if (neighbours.size() > 2) {
      throw InputError(fmt::format("patch '{}' branches at node {}: a sliding patch must be a single curve",
                                   patch.name, mesh.node_id(node)));
    }
    if (neighbours.size() == 1) start = node;
  }
  std::vector<mesh::NodeId> chain{start};
  mesh::NodeId previous = -1, current = start;
  while (chain.size() <= next.size()) {
    const auto& neighbours = next[current];
    const auto it = std::find_if(neighbours.begin(), neighbours.end(), [&](mesh::NodeId n) { return n != previous; });
    if (it == neighbours.end()) break;
    if (*it == start) {  // closed
      chain.push_back(start);
      break;
    }
    previous = current;
    current = *it;
    chain.push_back(current);
  }
  const std::size_t distinct = chain.size() > 1 && chain.front() == chain.back() ? chain.size() - 1 : chain.size();
  if (distinct != next.size()) {
    throw InputError(fmt::format("patch '{}' is made of several separate curves: give each its own patch to slide on",
                                 patch.name));
  }
  return chain;
}

/// Builds the curves of a case's patches: undeformed from CAD, FEM nodes or the patch itself,
/// deflected through the tables, rebased on a previous run's curves for a restart.
class CurveBuilder {
 public:
  CurveBuilder(const Case& c, const mesh::Mesh& mesh, const geometry::CadModel* cad)
      : c_(c), mesh_(mesh), given_cad_(cad) {}

  /// The patch's curve as the case describes it (cold undeformed r, deflection D).
  Curve curve(const PatchSpec& spec, const std::optional<DeflectionSpec>& deflection) {
    if (!deflection) return {own_curve(spec), {}};
    const geometry::CurveSamples samples = curve_samples(*deflection);
    const std::optional<geometry::BSplineCurve2d> cad =
        deflection->faces.empty() ? std::nullopt : std::optional(cad_curve(*deflection));
    geometry::Reconstruction rebuilt =
        geometry::fit_curve(samples, cad ? &*cad : nullptr, reconstruction_options(*deflection));
    return {std::move(rebuilt.curve), std::move(rebuilt.report)};
  }

  /// Section 4.3, re-start: the curve from `previous`'s deflected state (stage 0) to the
  /// deflection of `next` (stage 1), in the parameter of the undeformed curve. A patch
  /// without table deflects by zero.
  Curve rebased(const PatchSpec& spec, const DeflectionSpec& previous, const std::optional<DeflectionSpec>& next) {
    const Curve before = curve(spec, previous);
    DeflectionSpec target = next ? *next : previous;
    if (!next) {
      for (auto& d : target.samples.deflections) d = {};
    }
    const geometry::CurveSamples samples = curve_samples(target);
    const geometry::CurveProjector cold(DeflectedCurve(before.curve.undeformed()));
    geometry::CurveSamples moved = samples;  // points on the previous deflected curve, deflections from there
    for (std::size_t j = 0; j < samples.size(); ++j) {
      const double t = cold.project(samples.points[j], 0.0).parameter;
      moved.points[j] = before.curve.point(t, 1.0);
      moved.deflections[j] = samples.points[j] + samples.deflections[j] - moved.points[j];
    }
    // With the same nodes and form, the result's stage 1 is the curve a straight run would
    // reconstruct from `next`: interpolation is linear in the data.
    geometry::Reconstruction rebuilt = geometry::reconstruct(before.curve.stage(1.0), moved, reconstruction_options(target));
    return {std::move(rebuilt.curve), std::move(rebuilt.report)};
  }

  std::shared_ptr<const geometry::BoundaryShape> shape(DeflectedCurve curve) const {
    if (mesh_.dimension == 2) return std::make_shared<geometry::PlanarCurveShape>(std::move(curve));
    return std::make_shared<geometry::RevolvedShape>(std::move(curve), axis());
  }

 private:
  const geometry::Axis& axis() const {
    if (!c_.axis) {
      throw InputError::in(c_.file.string(), "3D boundaries are surfaces of revolution: give the case's axis, "
                                             "e.g. axis: {origin: [0, 0, 0], direction: [0, 0, 1]}");
    }
    return *c_.axis;
  }

  geometry::CurveSamples curve_samples(const DeflectionSpec& d) const {
    return geometry::curve_samples(d.samples, mesh_.dimension == 2 ? nullptr : &axis());
  }

  static geometry::ReconstructionOptions reconstruction_options(const DeflectionSpec& d) {
    geometry::ReconstructionOptions options;
    options.degree = d.degree;
    options.form = d.form;
    return options;
  }

  geometry::BSplineCurve2d cad_curve(const DeflectionSpec& d) {
    if (mesh_.dimension == 2) throw InputError("CAD faces describe surfaces of revolution: 3D cases only");
    if (!given_cad_ && !cad_) cad_ = read_case_cad(c_);
    const geometry::CadModel& cad = given_cad_ ? *given_cad_ : *cad_;
    return cad.meridional_curve(d.faces, {.axis = axis()}).curve;
  }

  /// A sliding patch without table slides over its own undeformed shape: the polyline through
  /// its nodes in 2D, their meridional polyline about the axis in 3D.
  DeflectedCurve own_curve(const PatchSpec& spec) const {
    const mesh::Patch& patch = *mesh_.find_patch(spec.name);
    if (mesh_.dimension == 2) {
      std::vector<geometry::Vec2> points;
      std::vector<double> parameters{0.0};
      for (mesh::NodeId n : chain_patch(patch, mesh_)) {
        const auto& p = mesh_.points[static_cast<std::size_t>(n)];
        if (!points.empty()) parameters.push_back(parameters.back() + distance(points.back(), {p.x, p.y}));
        points.push_back({p.x, p.y});
      }
      for (double& t : parameters) t /= parameters.back();
      return DeflectedCurve(geometry::BSplineCurve2d::polyline(parameters, points));
    }
    geometry::CurveSamples samples;
    samples.source = fmt::format("the nodes of patch '{}'", spec.name);
    for (mesh::NodeId n : patch.nodes) {
      const auto cyl = axis().to_cylindrical(mesh_.points[static_cast<std::size_t>(n)]);
      samples.points.push_back({cyl.r, cyl.z});
      samples.deflections.push_back({0.0, 0.0});
    }
    return geometry::reconstruct_from_nodes(samples, {}).curve;
  }

  const Case& c_;
  const mesh::Mesh& mesh_;
  const geometry::CadModel* given_cad_;
  std::optional<geometry::CadModel> cad_;  // read when first needed, if not given
};

const RestartPatch& previous_patch(const RestartState& previous, const PatchSpec& spec, const Case& c) {
  const auto it = std::find_if(previous.patches.begin(), previous.patches.end(),
                               [&](const RestartPatch& p) { return p.name == spec.name; });
  if (it == previous.patches.end()) {
    throw InputError::at(c.file.string(), spec.line, fmt::format("patches.{}: the run being restarted ({}) has no such "
                                                                 "patch",
                                                                 spec.name, previous.case_file));
  }
  if (it->role != spec.role) {
    throw InputError::at(c.file.string(), spec.line,
                         fmt::format("patches.{}: it was {} in the run being restarted ({}); a restart keeps the "
                                     "roles",
                                     spec.name, deform::to_string(it->role), previous.case_file));
  }
  return *it;
}

}  // namespace

std::optional<geometry::CadModel> read_case_cad(const Case& c) {
  if (!c.cad) return std::nullopt;
  return geometry::CadModel::read(*c.cad, {.unit = c.length_unit});
}

CaseSetup set_up_case(const Case& c, const mesh::Mesh& mesh, const RestartState* previous,
                      const geometry::CadModel* cad) {
  CaseSetup setup;
  CurveBuilder builder(c, mesh, cad);
  for (const PatchSpec& spec : c.patches) {
    deform::PatchMotion motion{spec.name, spec.role, nullptr};
    motion.features = spec.features;
    if (spec.role == PatchRole::periodic && spec.angle_deg != 0.0) {  // the side that declares the pair
      motion.partner = spec.partner;
      motion.angle = spec.angle_deg * std::numbers::pi / 180.0;
      motion.axis = *c.axis;
    }
    const bool follows = spec.role == PatchRole::prescribed || spec.role == PatchRole::sliding;
    const RestartPatch* before = previous ? &previous_patch(*previous, spec, c) : nullptr;
    if (follows) {
      try {
        Curve curve = before && before->deflection ? builder.rebased(spec, *before->deflection, spec.deflection)
                                                   : builder.curve(spec, spec.deflection);
        if (spec.deflection) setup.shapes.push_back({spec.name, curve.report, curve_outline(curve.curve, 1.0)});
        motion.shape = builder.shape(std::move(curve.curve));
      } catch (const InputError& e) {  // the message names the file at fault, if one is
        throw InputError::at(c.file.string(), spec.line, fmt::format("patches.{}: {}", spec.name, e.what()));
      }
    }
    setup.motions.push_back(std::move(motion));
  }
  return setup;
}

}  // namespace hotmesh::io
