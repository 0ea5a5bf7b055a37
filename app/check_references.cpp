// hotmesh app: the shapes `hotmesh check` measures mesh patches against (see check_references.hpp).
#include "check_references.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <utility>

#include "curve_fit.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/geometry/surface_distance.hpp"
#include "hotmesh/io/deflection_csv.hpp"

namespace hotmesh::app {

namespace {

std::string axis_text(const geometry::Axis& axis) {
  const auto& o = axis.origin();
  const auto& d = axis.direction();
  return fmt::format("the axis ({:.6g}, {:.6g}, {:.6g}) along ({:.6g}, {:.6g}, {:.6g})", o.x, o.y, o.z, d.x, d.y, d.z);
}

/// A boundary shape at its stage 1: the deflected shape, or the undeformed one for a shape
/// without deflection. Distances are those of its projection: in the meridional plane through
/// the point for surfaces of revolution (the distance to the surface), in the x-y plane for 2D
/// curves.
class ShapeReference final : public PatchReference {
 public:
  ShapeReference(std::unique_ptr<geometry::BoundaryShape> shape, std::string description)
      : shape_(std::move(shape)), description_(std::move(description)) {}
  double distance(const geometry::Vec3& p) override { return shape_->project(p, 1.0).distance; }
  std::string description() const override { return description_; }

 private:
  std::unique_ptr<geometry::BoundaryShape> shape_;
  std::string description_;
};

/// CAD faces that are no surfaces of revolution: the distance to their surfaces.
class FaceReference final : public PatchReference {
 public:
  FaceReference(geometry::SurfaceDistance surfaces, std::string description)
      : surfaces_(std::move(surfaces)), description_(std::move(description)) {}
  double distance(const geometry::Vec3& p) override { return surfaces_.nearest(p).distance; }
  std::string description() const override { return description_; }

 private:
  geometry::SurfaceDistance surfaces_;
  std::string description_;
};

std::unique_ptr<geometry::BoundaryShape> shape_of(const CurveRun& run) {
  if (run.axis) return std::make_unique<geometry::RevolvedShape>(run.fit.curve, *run.axis);
  return std::make_unique<geometry::PlanarCurveShape>(run.fit.curve);
}

std::unique_ptr<PatchReference> reference(const PatchCheckSpec& spec, const geometry::CadModel* cad,
                                          const deform::Mesh& mesh, const ReferenceOptions& options) {
  const std::string faces = fmt::format("{}", fmt::join(spec.faces, ", "));
  if (!spec.deflection) {
    const bool rotational = options.axis || std::any_of(spec.faces.begin(), spec.faces.end(), [&](int id) {
                              return cad->face(id).axis.has_value();
                            });
    if (rotational) {
      const geometry::MeridionalCurve curve = cad->meridional_curve(spec.faces, {.axis = options.axis});
      return std::make_unique<ShapeReference>(
          std::make_unique<geometry::RevolvedShape>(geometry::DeflectedCurve(curve.curve), curve.axis),
          fmt::format("CAD faces {}: their meridional curve about {}", faces, axis_text(curve.axis)));
    }
    std::vector<geometry::BSplineSurface> surfaces;
    for (const int id : spec.faces) surfaces.push_back(cad->face_bspline(id));
    return std::make_unique<FaceReference>(geometry::SurfaceDistance(surfaces),
                                           fmt::format("CAD faces {}: their surfaces", faces));
  }

  const geometry::DeflectionSamples table = io::read_deflection_csv(*spec.deflection);
  const std::string source = spec.deflection->string();
  if (!spec.faces.empty()) {
    if (mesh.dimension == 2) throw InputError("CAD faces describe surfaces of revolution: map them on 3D meshes only");
    require_cad_frame(table);
    if (table.frame == geometry::SampleFrame::meridional && !options.axis) {
      throw InputError::in(source, "meridional (r, z) nodes need --axis: z is measured from the axis origin");
    }
    const geometry::MeridionalCurve curve = cad->meridional_curve(spec.faces, {.axis = options.axis});
    const CurveRun run = fit_on_cad_curve(curve, table, options.reconstruction, options.unit, cad->path().string());
    return std::make_unique<ShapeReference>(
        shape_of(run), fmt::format("CAD faces {} deflected by {} (eq. 21, degree {}) about {}", faces, source,
                                   run.fit.report.degree, axis_text(curve.axis)));
  }
  if (mesh.dimension == 2 && table.frame != geometry::SampleFrame::planar) {
    throw InputError::in(source, "a 2D mesh needs a planar table (x,y,dx,dy)");
  }
  if (mesh.dimension == 3 && table.frame == geometry::SampleFrame::meridional && !options.axis) {
    throw InputError::in(source, "meridional (r, z) nodes need --axis: the mesh is measured about it");
  }
  const CurveRun run = fit_without_cad(table, options.axis, options.reconstruction, options.unit, "--axis");
  const std::string where = run.axis ? " about " + axis_text(*run.axis) : std::string(" in the x-y plane");
  return std::make_unique<ShapeReference>(
      shape_of(run), fmt::format("the curve through the FEM nodes of {} deflected by them (eq. 21, degree {}){}", source,
                                 run.fit.report.degree, where));
}

}  // namespace

std::unique_ptr<PatchReference> make_patch_reference(const PatchCheckSpec& spec, const geometry::CadModel* cad,
                                                     const deform::Mesh& mesh, const ReferenceOptions& options) {
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

}  // namespace hotmesh::app
