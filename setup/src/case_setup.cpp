// hotmesh setup: case + mesh (+ restart state) -> patch motions with their boundary shapes.
#include "hotmesh/setup/case_setup.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/setup/deflected_walls.hpp"

namespace hotmesh::setup {
namespace {

using io::Case;
using io::DeflectionSpec;
using io::PatchRole;
using io::PatchSpec;
using io::RestartPatch;
using io::RestartState;
using io::WallMode;

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

/// The case's CAD model: the one given to set_up_case, else read when first needed.
class CadSource {
 public:
  CadSource(const Case& c, const geometry::CadModel* given) : c_(c), given_(given) {}
  const geometry::CadModel& model() {
    if (given_ != nullptr) return *given_;
    if (!read_) read_ = read_case_cad(c_);
    return *read_;
  }

 private:
  const Case& c_;
  const geometry::CadModel* given_;
  std::optional<geometry::CadModel> read_;
};

/// Builds the curves of a case's patches: undeformed from CAD, FEM nodes or the patch itself,
/// deflected through the tables, rebased on a previous run's curves for a restart.
class CurveBuilder {
 public:
  CurveBuilder(const Case& c, const mesh::Mesh& mesh, CadSource& cad) : c_(c), mesh_(mesh), cad_(cad) {}

  /// The patch's curve as the case describes it (cold undeformed r, deflection D).
  Curve curve(const PatchSpec& spec, const std::optional<DeflectionSpec>& deflection) {
    if (!deflection) return {own_curve(spec), {}};
    const geometry::CurveSamples samples = curve_samples(*deflection);
    const std::optional<geometry::BSplineCurve2d> cad = deflection->faces.empty() && deflection->edges.empty()
                                                            ? std::nullopt
                                                            : std::optional(cad_curve(*deflection));
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

  /// The table in the plane of the patch's curve: (r, z) about the axis in 3D; in 2D the mesh's
  /// (x, y), which a 2D axisymmetric case's meridional table gives as (z, r).
  geometry::CurveSamples curve_samples(const DeflectionSpec& d) const {
    if (mesh_.dimension == 2 && d.samples.frame == geometry::SampleFrame::meridional) {
      return geometry::axial_plane_samples(d.samples, axis());
    }
    return geometry::curve_samples(d.samples, mesh_.dimension == 2 ? nullptr : &axis());
  }

  static geometry::ReconstructionOptions reconstruction_options(const DeflectionSpec& d) {
    geometry::ReconstructionOptions options;
    options.degree = d.degree;
    options.form = d.form;
    return options;
  }

  /// The undeformed wall r(t) from CAD: the faces' meridional curve about the axis (eq. 20) in
  /// 3D; in 2D (plane_cad_curve) errors name the key at fault.
  geometry::BSplineCurve2d cad_curve(const DeflectionSpec& d) {
    if (mesh_.dimension == 3) return cad_.model().meridional_curve(d.faces, {.axis = axis()}).curve;
    try {
      return plane_cad_curve(d);
    } catch (const InputError& e) {
      throw InputError(fmt::format("deflection.{}: {}", d.edges.empty() ? "faces" : "edges", e.what()));
    }
  }

  /// A 2D wall from CAD: the curve of the edges in the plane z = 0; in an axisymmetric case the
  /// faces' meridional curve, in the mesh's (x, y) = (z, r).
  geometry::BSplineCurve2d plane_cad_curve(const DeflectionSpec& d) {
    if (!d.edges.empty()) return cad_.model().planar_curve(d.edges).curve;
    if (!c_.axis) {
      throw InputError("CAD faces in a 2D case need the top-level axis (an axisymmetric case); a planar wall is "
                       "CAD edges, `edges: [...]`");
    }
    return cad_.model().meridional_curve(d.faces, {.axis = *c_.axis}).curve.swapped_coordinates();
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
  CadSource& cad_;
};

/// The 3D walls that are not surfaces of revolution (issue 23): on their CAD faces, a
/// deflection field per face (SurfaceShape); without faces, prescribed walls moved by the table
/// interpolated over them (ScatteredShape). A restart goes from the previous table's wall to
/// the new one's (section 4.3); a patch without a new table goes back to zero deflection.
class SurfaceBuilder {
 public:
  SurfaceBuilder(const Case& c, CadSource& cad) : c_(c), cad_(cad) {}

  struct Wall {
    std::shared_ptr<const geometry::BoundaryShape> shape;
    ShapeReport report;
  };

  Wall wall(const PatchSpec& spec, const DeflectionSpec& deflection, const DeflectionSpec* previous) {
    ShapeReport report{spec.name};
    geometry::ReconstructionOptions options;
    options.degree = deflection.degree;
    options.form = geometry::DeflectionForm::displacement;
    report.reconstruction.nodes = deflection.samples.size();
    report.reconstruction.degree = deflection.degree;
    report.reconstruction.form = options.form;
    if (!deflection.faces.empty()) {
      std::vector<geometry::CadFace> faces;
      for (int id : deflection.faces) faces.push_back(cad_.model().cad_face(id));
      geometry::SurfaceShapeFit fit =
          geometry::make_surface_shape(std::move(faces), deflection.samples, options, previous ? &previous->samples : nullptr);
      report.kind = WallKind::faces;
      report.reconstruction.used_nodes = fit.report.used_nodes;
      report.reconstruction.tolerance = fit.report.tolerance;
      report.reconstruction.max_node_distance_to_cad = fit.report.max_node_distance_to_cad;
      report.reconstruction.max_node_residual = fit.report.max_node_residual;
      report.faces = std::move(fit.report);
      return {std::move(fit.shape), std::move(report)};
    }
    if (spec.role == PatchRole::sliding) {
      throw InputError("a sliding wall that is not a surface of revolution slides over its CAD faces: give them in "
                       "its deflection (`faces: [...]`, with the top-level `cad:`), or the top-level `axis:` if it "
                       "is a surface of revolution");
    }
    check_cartesian(deflection.samples);
    report.kind = WallKind::scattered;
    std::shared_ptr<const geometry::WallField> after, before;
    // The deflected field of the table and, on a restart, the previous one, of one kind.
    const auto fields = [&]<class Field>() {
      auto field = std::make_shared<const Field>(deflection.samples.points, deflection.samples.deflections);
      report.reconstruction.used_nodes = field->report().points;
      report.reconstruction.merged_duplicates = field->report().merged_duplicates;
      if (previous) {
        check_cartesian(previous->samples);
        before = std::make_shared<const Field>(previous->samples.points, previous->samples.deflections);
      }
      return field;
    };
    if (deflection.degree == 1) {
      // linear between the FEM nodes, as a table of linear elements is: no overshoot at kinks
      auto linear = fields.template operator()<geometry::LinearField>();
      report.linear = linear->report();
      after = std::move(linear);
    } else {
      auto smooth = fields.template operator()<geometry::ScatteredField>();
      report.reconstruction.max_node_residual = smooth->report().max_residual;
      report.scattered = smooth->report();
      after = std::move(smooth);
    }
    return {std::make_shared<geometry::ScatteredShape>(std::move(after), std::move(before)), std::move(report)};
  }

  /// Whether a 3D wall is a surface of revolution about the case's axis (module comment of
  /// case_setup.hpp).
  bool meridional(const DeflectionSpec& d) {
    if (d.mode != WallMode::automatic) return d.mode == WallMode::meridional;
    if (d.samples.frame == geometry::SampleFrame::meridional) return true;
    if (!c_.axis) return false;
    if (d.faces.empty()) return true;
    try {
      cad_.model().meridional_curve(d.faces, {.axis = *c_.axis});
      return true;
    } catch (const InputError&) {  // faces not rotational about the axis
      return false;
    }
  }

 private:
  static void check_cartesian(const geometry::DeflectionSamples& samples) {
    if (samples.frame != geometry::SampleFrame::cartesian) {
      throw InputError::in(samples.source, std::string("a wall that is not a surface of revolution needs a cartesian "
                                                       "(x, y, z) table, got a ") +
                                               geometry::to_string(samples.frame) + " one");
    }
  }

  const Case& c_;
  CadSource& cad_;
};

/// A table of the same nodes with zero deflections: where a restarted patch without a new
/// table goes back to.
DeflectionSpec at_rest(const DeflectionSpec& d) {
  DeflectionSpec rest = d;
  for (auto& delta : rest.samples.deflections) delta = {};
  return rest;
}

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

std::optional<geometry::CadModel> read_case_cad(const io::Case& c) {
  if (!c.cad) return std::nullopt;
  return geometry::CadModel::read(*c.cad, {.unit = c.length_unit});
}

CaseSetup set_up_case(const io::Case& c, const mesh::Mesh& mesh, const io::RestartState* previous,
                      const geometry::CadModel* cad) {
  CaseSetup setup;
  CadSource cad_source(c, cad);
  CurveBuilder builder(c, mesh, cad_source);
  SurfaceBuilder surfaces(c, cad_source);
  for (const PatchSpec& spec : c.patches) {
    deform::PatchMotion motion{spec.name, spec.role, nullptr};
    motion.features = spec.features;
    if (spec.role == PatchRole::periodic && spec.angle_deg != 0.0) {  // the side that declares the pair
      motion.partner = spec.partner;
      motion.angle = spec.angle_deg * std::numbers::pi / 180.0;
      motion.axis = *c.axis;
    }
    const bool follows = deform::follows_shape(spec.role);
    const RestartPatch* before = previous ? &previous_patch(*previous, spec, c) : nullptr;
    if (follows) {
      try {
        const DeflectionSpec* earlier = before && before->deflection ? &*before->deflection : nullptr;
        const DeflectionSpec* table = spec.deflection ? &*spec.deflection : earlier;
        if (mesh.dimension == 3 && table != nullptr && !surfaces.meridional(*table)) {
          const DeflectionSpec target = spec.deflection ? *spec.deflection : at_rest(*earlier);
          SurfaceBuilder::Wall wall = surfaces.wall(spec, target, earlier);
          motion.shape = std::move(wall.shape);
          if (spec.deflection) setup.shapes.push_back(std::move(wall.report));
          setup.motions.push_back(std::move(motion));
          continue;
        }
        Curve curve = before && before->deflection ? builder.rebased(spec, *before->deflection, spec.deflection)
                                                   : builder.curve(spec, spec.deflection);
        if (spec.deflection) {
          setup.shapes.push_back({spec.name, WallKind::curve, curve.report, {}, {}, {}, curve_outline(curve.curve, 1.0)});
        }
        motion.shape = builder.shape(std::move(curve.curve));
      } catch (const InputError& e) {  // the message names the file at fault, if one is
        throw InputError::at(c.file.string(), spec.line, fmt::format("patches.{}: {}", spec.name, e.what()));
      }
    }
    setup.motions.push_back(std::move(motion));
  }
  return setup;
}

}  // namespace hotmesh::setup
