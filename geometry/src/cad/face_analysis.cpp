// hotmesh geometry (internal): surface kinds, bounds, axes of revolution (the file's for
// analytic surfaces, fitted for free-form ones) and sampling of CAD faces.
#include "cad/face_analysis.hpp"

#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_ElementarySurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <gp_Pnt2d.hxx>

#include "cad/occt_convert.hpp"
#include "cad/rotation_axis_fit.hpp"

namespace hotmesh::geometry::detail {

namespace {

Handle(Geom_Surface) basis_surface(const TopoDS_Face& face) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  for (auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface); !trimmed.IsNull();
       trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface)) {
    surface = trimmed->BasisSurface();
  }
  return surface;
}

Axis to_axis(const gp_Ax1& axis) { return Axis(to_vec3(axis.Location()), to_vec3(axis.Direction())); }

}  // namespace

SurfaceKind surface_kind(const TopoDS_Face& face) {
  switch (GeomAdaptor_Surface(BRep_Tool::Surface(face)).GetType()) {
    case GeomAbs_Plane: return SurfaceKind::plane;
    case GeomAbs_Cylinder: return SurfaceKind::cylinder;
    case GeomAbs_Cone: return SurfaceKind::cone;
    case GeomAbs_Sphere: return SurfaceKind::sphere;
    case GeomAbs_Torus: return SurfaceKind::torus;
    case GeomAbs_SurfaceOfRevolution: return SurfaceKind::revolution;
    case GeomAbs_SurfaceOfExtrusion: return SurfaceKind::extrusion;
    case GeomAbs_BSplineSurface: return SurfaceKind::bspline;
    case GeomAbs_BezierSurface: return SurfaceKind::bezier;
    case GeomAbs_OffsetSurface: return SurfaceKind::offset;
    case GeomAbs_OtherSurface: return SurfaceKind::other;
  }
  return SurfaceKind::other;
}

Box3 face_bounds(const TopoDS_Face& face) {
  Bnd_Box box;
  BRepBndLib::AddOptimal(face, box, false, false);
  if (box.IsVoid()) return {};
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  return {{x0, y0, z0}, {x1, y1, z1}};
}

double diagonal(const Box3& box) { return distance(box.min, box.max); }

FaceAxis face_axis(const TopoDS_Face& face, SurfaceKind kind) {
  const Handle(Geom_Surface) surface = basis_surface(face);
  switch (kind) {
    case SurfaceKind::cylinder:
    case SurfaceKind::cone:
    case SurfaceKind::sphere:
    case SurfaceKind::torus:
      return {to_axis(Handle(Geom_ElementarySurface)::DownCast(surface)->Axis()), AxisSource::analytic};
    case SurfaceKind::revolution:
      return {to_axis(Handle(Geom_SurfaceOfRevolution)::DownCast(surface)->Axis()), AxisSource::analytic};
    case SurfaceKind::plane:
      return {};
    case SurfaceKind::extrusion:
    case SurfaceKind::bspline:
    case SurfaceKind::bezier:
    case SurfaceKind::offset:
    case SurfaceKind::other:
      break;
  }
  const SurfaceSamples samples = sample_face(face, 16, false);
  const std::optional<Axis> axis = fit_rotation_axis(samples.points, samples.normals, kRotationAngleTolerance);
  if (!axis) return {};
  return {axis, AxisSource::fitted};
}

SurfaceSamples sample_face(const TopoDS_Face& face, int n, bool inside_only) {
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  const double tolerance = BRep_Tool::Tolerance(face);
  std::optional<BRepTopAdaptor_FClass2d> classifier;
  if (inside_only) classifier.emplace(face, tolerance);
  GeomLProp_SLProps props(surface, 1, tolerance);
  SurfaceSamples samples;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = u0 + (u1 - u0) * (i + 0.5) / n;
      const double v = v0 + (v1 - v0) * (j + 0.5) / n;
      if (classifier && classifier->Perform(gp_Pnt2d(u, v)) != TopAbs_IN) continue;
      props.SetParameters(u, v);
      if (!props.IsNormalDefined()) continue;
      samples.points.push_back(to_vec3(props.Value()));
      samples.normals.push_back(to_vec3(props.Normal()));
    }
  }
  return samples;
}

}  // namespace hotmesh::geometry::detail
