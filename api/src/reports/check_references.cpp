// hotmesh api: the shapes `hotmesh check` measures mesh patches against (see check_references.hpp).
#include "hotmesh/api/check_references.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iterator>
#include <string_view>
#include <utility>

#include "hotmesh/setup/curve_fit.hpp"
#include "hotmesh/setup/faces_mode.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/surface_distance.hpp"
#include "hotmesh/geometry/surface_shape.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/deflection_csv.hpp"

namespace hotmesh::api {

namespace {

std::string axis_text(const geometry::Axis& axis) {
  const geometry::Vec3 o = axis.origin() + geometry::Vec3{0, 0, 0};  // + 0: no "-0"
  const geometry::Vec3 d = axis.direction() + geometry::Vec3{0, 0, 0};
  return fmt::format("the axis ({:.6g}, {:.6g}, {:.6g}) along ({:.6g}, {:.6g}, {:.6g})", o.x, o.y, o.z, d.x, d.y, d.z);
}

/// A boundary shape at one stage: 1, the deflected shape (the undeformed one for a shape
/// without deflection), or 0, the undeformed one. Distances are those of its projection: in the
/// meridional plane through the point for surfaces of revolution (the distance to the surface),
/// in the x-y plane for 2D curves.
class ShapeReference final : public ReferenceShape {
 public:
  ShapeReference(std::shared_ptr<const geometry::BoundaryShape> shape, double stage, std::string description)
      : shape_(std::move(shape)), stage_(stage), description_(std::move(description)) {}
  double distance(const geometry::Vec3& p) override { return shape_->project(p, stage_).distance; }
  std::string description() const override { return description_; }
  WallCheck wall(const mesh::Mesh& mesh, const geometry::WallFaces& faces) override {
    return measure_wall(*shape_, stage_, mesh, mesh.points, faces);
  }

 private:
  std::shared_ptr<const geometry::BoundaryShape> shape_;
  double stage_ = 1.0;
  std::string description_;
};

/// CAD faces that are no surfaces of revolution: nodes measured by their distance to the
/// surfaces within the faces' parameter bounds, the patch's faces against the undeformed wall
/// as hotmesh deform sees it (a SurfaceShape without deflection).
class FaceReference final : public ReferenceShape {
 public:
  FaceReference(std::vector<geometry::CadFace> faces, std::string description)
      : surfaces_(surfaces_of(faces)),
        wall_(geometry::undeformed_surface_shape(std::move(faces))),
        description_(std::move(description)) {}
  double distance(const geometry::Vec3& p) override { return surfaces_.nearest(p).distance; }
  std::string description() const override { return description_; }
  WallCheck wall(const mesh::Mesh& mesh, const geometry::WallFaces& faces) override {
    return measure_wall(*wall_, 0.0, mesh, mesh.points, faces);
  }

 private:
  static geometry::SurfaceDistance surfaces_of(const std::vector<geometry::CadFace>& faces) {
    std::vector<geometry::BSplineSurface> surfaces;
    for (const geometry::CadFace& f : faces) surfaces.push_back(f.surface);
    return geometry::SurfaceDistance(std::move(surfaces));
  }

  geometry::SurfaceDistance surfaces_;
  std::shared_ptr<const geometry::SurfaceShape> wall_;
  std::string description_;
};

PatchReference single(std::unique_ptr<ReferenceShape> shape) {
  PatchReference reference;
  reference.description = shape->description();
  reference.parts.push_back(std::move(shape));
  return reference;
}

std::shared_ptr<const geometry::BoundaryShape> shape_of(const setup::CurveRun& run) {
  if (run.axis) return std::make_shared<geometry::RevolvedShape>(run.fit.curve, *run.axis);
  return std::make_shared<geometry::PlanarCurveShape>(run.fit.curve);
}

/// "face 3", "faces 3, 4" (or edges, with `word` "edge").
std::string face_text(const std::vector<int>& faces, std::string_view word = "face") {
  return fmt::format("{}{} {}", word, faces.size() == 1 ? "" : "s", fmt::join(faces, ", "));
}

/// Faces of revolution, without deflection: their meridional curve, or one part per profile
/// when they form several.
PatchReference revolved_faces(const PatchCheckSpec& spec, const std::vector<geometry::MeridionalCurve>& profiles) {
  PatchReference reference;
  for (const geometry::MeridionalCurve& curve : profiles) {
    std::vector<int> faces;  // in the order given
    std::copy_if(spec.faces.begin(), spec.faces.end(), std::back_inserter(faces), [&](int id) {
      return std::find(curve.faces.begin(), curve.faces.end(), id) != curve.faces.end();
    });
    reference.parts.push_back(std::make_unique<ShapeReference>(
        std::make_shared<geometry::RevolvedShape>(geometry::DeflectedCurve(curve.curve), curve.axis), 1.0,
        fmt::format("CAD {}: {} meridional curve about {}", face_text(faces), faces.size() == 1 ? "its" : "their",
                    axis_text(curve.axis))));
  }
  reference.description =
      profiles.size() == 1
          ? reference.parts.front()->description()
          : fmt::format("CAD {}: {} separate meridional profiles about {}, each node measured against the nearest",
                        face_text(spec.faces), profiles.size(), axis_text(profiles.front().axis));
  return reference;
}

std::vector<geometry::CadFace> cad_faces(const geometry::CadModel& cad, const std::vector<int>& ids) {
  std::vector<geometry::CadFace> faces;
  for (const int id : ids) faces.push_back(cad.cad_face(id));
  return faces;
}

/// Why faces the check measures as surfaces are no surface of revolution, for reports; empty
/// when --mode surface said so.
std::string surface_reason(const setup::FacesMode& chosen) {
  return chosen.reason.empty() ? std::string() : " (not one surface of revolution: " + chosen.reason + ")";
}

/// The faces as --mode and the table ask (faces_mode.hpp): a meridional table makes the wall
/// meridional under auto, as in hotmesh deform. Throws hotmesh::InputError naming --mode when
/// meridional is asked and the faces are not surfaces of revolution about one axis.
setup::FacesMode faces_mode(const PatchCheckSpec& spec, const geometry::CadModel& cad, const ReferenceOptions& options,
                     bool meridional_table) {
  const io::WallMode asked =
      meridional_table && options.mode == io::WallMode::automatic ? io::WallMode::meridional : options.mode;
  try {
    return setup::choose_faces_mode(cad, spec.faces, options.axis, asked);
  } catch (const InputError& e) {
    if (options.mode != io::WallMode::meridional) throw;
    throw InputError(fmt::format("--mode meridional: {}", e.what()));
  }
}

/// A 2D mesh's patch mapped to CAD: its ids are edges, whose curve in the plane z = 0 is the
/// wall; with an axis (an axisymmetric mesh: x along the axis, y the radius) they are faces,
/// whose meridional curve, as (z, r), is. With a table, that wall deflected by it (eq. 21).
PatchReference plane_cad_reference(const PatchCheckSpec& spec, const geometry::CadModel& cad,
                                   const ReferenceOptions& options) {
  std::string what;
  const geometry::BSplineCurve2d curve = [&] {
    if (!options.axis) {
      what = fmt::format("CAD {}: {} curve in the x-y plane", face_text(spec.faces, "edge"),
                         spec.faces.size() == 1 ? "its" : "their");
      return cad.planar_curve(spec.faces).curve;
    }
    const geometry::MeridionalCurve meridional = cad.meridional_curve(spec.faces, {.axis = options.axis});
    what = fmt::format("CAD {}: {} meridional curve about {}, as (z, r) in the mesh's plane", face_text(spec.faces),
                       spec.faces.size() == 1 ? "its" : "their", axis_text(meridional.axis));
    return meridional.curve.swapped_coordinates();
  }();
  if (!spec.deflection) {
    return single(std::make_unique<ShapeReference>(
        std::make_shared<geometry::PlanarCurveShape>(geometry::DeflectedCurve(curve)), 1.0, what));
  }
  const geometry::DeflectionSamples table = io::read_deflection_csv(*spec.deflection);
  const setup::CurveRun run =
      setup::fit_on_plane_cad_curve(curve, table, options.axis, options.reconstruction, options.unit, cad.path().string());
  return single(std::make_unique<ShapeReference>(
      shape_of(run), 1.0,
      fmt::format("{}, deflected by {} (eq. 21, degree {})", what, spec.deflection->string(), run.fit.report.degree)));
}

PatchReference reference(const PatchCheckSpec& spec, const geometry::CadModel* cad, const mesh::Mesh& mesh,
                         const ReferenceOptions& options) {
  if (mesh.dimension == 2 && !spec.faces.empty()) return plane_cad_reference(spec, *cad, options);
  const std::string faces = face_text(spec.faces);
  if (!spec.deflection) {
    const setup::FacesMode chosen = faces_mode(spec, *cad, options, false);
    if (chosen.mode == io::WallMode::meridional) return revolved_faces(spec, chosen.profiles);
    return single(std::make_unique<FaceReference>(cad_faces(*cad, spec.faces),
                                                  fmt::format("CAD {}: their surfaces{}", faces, surface_reason(chosen))));
  }

  const geometry::DeflectionSamples table = io::read_deflection_csv(*spec.deflection);
  const std::string source = spec.deflection->string();
  if (!spec.faces.empty()) {
    setup::require_cad_frame(table);
    if (table.frame == geometry::SampleFrame::meridional && !options.axis) {
      throw InputError::in(source, "meridional (r, z) nodes need --axis: z is measured from the axis origin");
    }
    setup::FacesMode chosen = faces_mode(spec, *cad, options, table.frame == geometry::SampleFrame::meridional);
    if (chosen.mode == io::WallMode::surface) {  // as hotmesh deform: d(t, s) on each face, displacement form
      geometry::ReconstructionOptions fit = options.reconstruction;
      fit.form = geometry::DeflectionForm::displacement;
      geometry::SurfaceShapeFit wall = geometry::make_surface_shape(cad_faces(*cad, spec.faces), table, fit);
      return single(std::make_unique<ShapeReference>(
          std::move(wall.shape), 1.0,
          fmt::format("CAD {} deflected by {} (a field d(t, s) on each face, degree {}, displacement form){}", faces,
                      source, fit.degree, surface_reason(chosen))));
    }
    // One profile: the faces' meridional curve; several: meridional_curve says they do not join.
    const geometry::MeridionalCurve curve = chosen.profiles.size() == 1
                                                ? std::move(chosen.profiles.front())
                                                : cad->meridional_curve(spec.faces, {.axis = options.axis});
    const setup::CurveRun run = setup::fit_on_cad_curve(curve, table, options.reconstruction, options.unit, cad->path().string());
    return single(std::make_unique<ShapeReference>(
        shape_of(run), 1.0,
        fmt::format("CAD {} deflected by {} (eq. 21, degree {}) about {}", faces, source, run.fit.report.degree,
                    axis_text(curve.axis))));
  }
  if (mesh.dimension == 2 && table.frame != geometry::SampleFrame::planar) {
    throw InputError::in(source, "a 2D mesh needs a planar table (x,y,dx,dy)");
  }
  if (mesh.dimension == 3 && table.frame == geometry::SampleFrame::meridional && !options.axis) {
    throw InputError::in(source, "meridional (r, z) nodes need --axis: the mesh is measured about it");
  }
  const setup::CurveRun run = setup::fit_without_cad(table, options.axis, options.reconstruction, options.unit, "--axis");
  const std::string where = run.axis ? " about " + axis_text(*run.axis) : std::string(" in the x-y plane");
  return single(std::make_unique<ShapeReference>(
      shape_of(run), 1.0,
      fmt::format("the curve through the FEM nodes of {} deflected by them (eq. 21, degree {}){}", source,
                  run.fit.report.degree, where)));
}

/// What hotmesh deform makes of a case patch's wall, for reports; paths relative to the case.
/// `kind` is how setup::set_up_case built it (a patch without table: a curve).
std::string case_wall_text(const io::Case& c, const io::PatchSpec& spec, setup::WallKind kind, CaseStage stage,
                           int dimension) {
  const auto name = [&](const std::filesystem::path& file) {
    return file.lexically_relative(c.file.parent_path()).string();
  };
  const bool deflected = stage == CaseStage::deflected;
  std::string what;
  if (!spec.deflection) {
    what = "its own undeformed nodes (a sliding wall without table keeps its shape)";
  } else {
    const io::DeflectionSpec& d = *spec.deflection;
    if (kind == setup::WallKind::faces) {  // always in displacement form (setup::set_up_case)
      what = fmt::format("CAD {} of {}{}", face_text(d.faces), name(*c.cad),
                         deflected ? fmt::format(", deflected by {} (a field d(t, s) on each face, degree {}, "
                                                 "displacement form)",
                                                 name(d.file), d.degree)
                                   : std::string());
    } else if (kind == setup::WallKind::scattered) {
      what = deflected ? fmt::format("the table {} interpolated over the wall ({})", name(d.file),
                                     d.degree == 1 ? "linear over triangles" : "partition-of-unity RBF")
                       : fmt::format("its own undeformed nodes (no surface: the table {} moves them, interpolated "
                                     "over the wall)",
                                     name(d.file));
    } else {
      const std::string fit = fmt::format("(eq. 21, {} form, degree {})", geometry::to_string(d.form), d.degree);
      if (d.faces.empty() && d.edges.empty()) {
        what = fmt::format("the curve through the FEM nodes of {}{}", name(d.file),
                           deflected ? ", deflected by them " + fit : std::string());
      } else {
        what = fmt::format("CAD {} of {}{}", d.edges.empty() ? face_text(d.faces) : face_text(d.edges, "edge"),
                           name(*c.cad), deflected ? fmt::format(", deflected by {} {}", name(d.file), fit) : std::string());
      }
    }
  }
  // A curve lies in the x-y plane (2D; with an axis, the (z, r) plane about it) or is the
  // meridional curve about the case's axis (3D).
  std::string where;
  if (kind == setup::WallKind::curve) {
    if (dimension == 2) {
      where = c.axis ? " in the x-y plane, (z, r) about " + axis_text(*c.axis) : std::string(" in the x-y plane");
    } else if (c.axis) {
      where = " about " + axis_text(*c.axis);
    }
  }
  return fmt::format("the {} wall of the case ({}): {}{}", deflected ? "deflected" : "undeformed",
                     deform::to_string(spec.role), what, where);
}

}  // namespace

PatchReference make_patch_reference(const PatchCheckSpec& spec, const geometry::CadModel* cad,
                                    const mesh::Mesh& mesh, const ReferenceOptions& options) {
  if (!spec.faces.empty() && cad == nullptr) {
    throw InputError(fmt::format("--map {}: needs --cad, the file the faces belong to", spec.patch));
  }
  if (spec.faces.empty() && !spec.deflection) {
    throw InputError(fmt::format("patch '{}': give its CAD faces (--map) or a deflection table (--deflection)", spec.patch));
  }
  try {
    return reference(spec, cad, mesh, options);
  } catch (const InputError& e) {
    throw InputError(fmt::format("patch '{}': {}", spec.patch, e.what()));
  }
}

std::vector<CasePatchReference> case_references(const io::Case& c, const mesh::Mesh& case_mesh, CaseStage stage) {
  io::check_case_against_mesh(c, case_mesh);
  const setup::CaseSetup setup = setup::set_up_case(c, case_mesh);
  std::vector<CasePatchReference> references;
  for (std::size_t i = 0; i < setup.motions.size(); ++i) {
    const deform::PatchMotion& motion = setup.motions[i];
    if (!motion.shape) continue;
    const io::PatchSpec& spec = *c.find_patch(motion.patch);
    // How io built the wall: set_up_case reports it for every patch with a table; without one
    // the wall is a curve.
    const auto built = std::find_if(setup.shapes.begin(), setup.shapes.end(),
                                    [&](const setup::ShapeReport& r) { return r.patch == motion.patch; });
    const setup::WallKind kind = built != setup.shapes.end() ? built->kind : setup::WallKind::curve;
    references.push_back({motion.patch, single(std::make_unique<ShapeReference>(
                                            motion.shape, stage == CaseStage::deflected ? 1.0 : 0.0,
                                            case_wall_text(c, spec, kind, stage, case_mesh.dimension)))});
  }
  return references;
}

}  // namespace hotmesh::api
