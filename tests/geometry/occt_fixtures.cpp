// hotmesh tests: OpenCASCADE-built CAD fixtures (see occt_fixtures.hpp).
#include "occt_fixtures.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <GeomConvert.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Precision.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <BRep_Builder.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <UnitsMethods.hxx>
#include <gp.hxx>
#include <gp_Ax2.hxx>
#include <gp_Ax3.hxx>
#include <gp_Cylinder.hxx>

#include <cmath>
#include <initializer_list>
#include <numbers>
#include <stdexcept>

namespace hotmesh::geometry::test {

namespace {

gp_Pnt pnt(const Vec3& p) { return gp_Pnt(p.x, p.y, p.z); }
gp_Dir dir(const Vec3& d) { return gp_Dir(d.x, d.y, d.z); }

/// The profile as a 3D curve in the meridional half-plane theta = 0 of the axis.
Handle(Geom_BSplineCurve) profile_3d(const Axis& axis) {
  const BSplineCurve2d c = profile();
  TColgp_Array1OfPnt poles(1, static_cast<int>(c.poles().size()));
  for (int i = 1; i <= poles.Upper(); ++i) {
    const Vec2 q = c.poles()[static_cast<std::size_t>(i - 1)];
    poles(i) = pnt(axis.to_cartesian({q.x, 0.0, q.y}));
  }
  TColStd_Array1OfReal knots(1, 3);
  TColStd_Array1OfInteger mults(1, 3);
  knots(1) = 0.0, knots(2) = 0.5, knots(3) = 1.0;
  mults(1) = 4, mults(2) = 1, mults(3) = 4;
  return new Geom_BSplineCurve(poles, knots, mults, 3);
}

TopoDS_Shape build(Primitive primitive, const Axis& axis) {
  const gp_Ax2 frame(pnt(axis.origin()), dir(axis.direction()));
  switch (primitive) {
    case Primitive::cylinder: return BRepPrimAPI_MakeCylinder(frame, 2.0, 5.0).Shape();
    case Primitive::cone: return BRepPrimAPI_MakeCone(frame, 3.0, 1.0, 4.0).Shape();
    case Primitive::torus: return BRepPrimAPI_MakeTorus(frame, 5.0, 1.0).Shape();
    case Primitive::revolved_profile:
      return BRepPrimAPI_MakeRevol(BRepBuilderAPI_MakeEdge(profile_3d(axis)).Edge(),
                                   gp_Ax1(pnt(axis.origin()), dir(axis.direction())))
          .Shape();
    case Primitive::bspline_revolved: {
      const Handle(Geom_Surface) revolved =
          new Geom_SurfaceOfRevolution(profile_3d(axis), gp_Ax1(pnt(axis.origin()), dir(axis.direction())));
      const Handle(Geom_Surface) nurbs = GeomConvert::SurfaceToBSplineSurface(revolved);
      return BRepBuilderAPI_MakeFace(nurbs, Precision::Confusion()).Shape();
    }
    case Primitive::plate_with_hole: {
      const gp_Pnt corner = frame.Location().Translated(-5.0 * gp_Vec(frame.XDirection()) - 5.0 * gp_Vec(frame.YDirection()));
      const TopoDS_Shape plate = BRepPrimAPI_MakeBox(gp_Ax2(corner, frame.Direction(), frame.XDirection()), 10.0, 10.0, 2.0).Shape();
      const gp_Ax2 below(frame.Location().Translated(-gp_Vec(frame.Direction())), frame.Direction());
      return BRepAlgoAPI_Cut(plate, BRepPrimAPI_MakeCylinder(below, 2.0, 4.0).Shape()).Shape();
    }
  }
  throw std::logic_error("unknown primitive");
}

void write_step_or_iges(const std::filesystem::path& path, const TopoDS_Shape& shape) {
  // Writers scale from the process-wide unit that readers leave behind: millimetres here.
  UnitsMethods::SetCasCadeLengthUnit(1.0, UnitsMethods_LengthUnit_Millimeter);
  if (path.extension() == ".igs" || path.extension() == ".iges") {
    IGESControl_Controller::Init();
    IGESControl_Writer writer("MM", 1);
    writer.AddShape(shape);
    writer.ComputeModel();
    if (!writer.Write(path.string().c_str())) throw std::runtime_error("IGES fixture not written");
    return;
  }
  STEPControl_Writer writer;
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  Interface_Static::SetCVal("write.step.unit", "MM");
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone ||
      writer.Write(path.string().c_str()) != IFSelect_RetDone) {
    throw std::runtime_error("STEP fixture not written");
  }
}

/// The planar face bounded by the polygon through `corners`.
TopoDS_Face polygon_face(std::initializer_list<gp_Pnt> corners) {
  BRepBuilderAPI_MakePolygon polygon;
  for (const gp_Pnt& p : corners) polygon.Add(p);
  polygon.Close();
  return BRepBuilderAPI_MakeFace(polygon.Wire(), true).Face();
}

/// The step wall's edges (StepWall), in the plane z = 0 unless the drawing moves them.
std::vector<TopoDS_Edge> step_wall_edges(StepWallDrawing drawing) {
  const std::vector<Vec2> v = StepWall::vertices();
  const auto at = [](const Vec2& p, double z = 0.0) { return gp_Pnt(p.x, p.y, z); };
  const double lift = drawing == StepWallDrawing::lifted ? 0.5 : 0.0;
  const Vec2 c = StepWall::fillet_centre();
  const double r = StepWall::kFilletRadius * std::sqrt(0.5);  // the arc's middle point
  const Handle(Geom_TrimmedCurve) arc =
      GC_MakeArcOfCircle(at(v[2], lift), at({c.x - r, c.y + r}, lift), at(v[3], lift)).Value();
  const Vec2 top_start = drawing == StepWallDrawing::gap ? Vec2{v[3].x + 0.5, v[3].y} : v[3];
  return {BRepBuilderAPI_MakeEdge(at(v[0]), at(v[1])).Edge(), BRepBuilderAPI_MakeEdge(at(v[1]), at(v[2])).Edge(),
          BRepBuilderAPI_MakeEdge(arc).Edge(), BRepBuilderAPI_MakeEdge(at(top_start), at(v[4])).Edge()};
}

TopoDS_Shape step_wall_shape(StepWallDrawing drawing) {
  const std::vector<TopoDS_Edge> wall = step_wall_edges(drawing);
  BRepBuilderAPI_MakeWire wire;
  for (const TopoDS_Edge& e : wall) wire.Add(e);
  if (drawing != StepWallDrawing::face) {
    if (drawing == StepWallDrawing::edges) return wire.Wire();
    TopoDS_Compound loose;  // lifted or broken: no wire joins them
    BRep_Builder builder;
    builder.MakeCompound(loose);
    for (const TopoDS_Edge& e : wall) builder.Add(loose, e);
    return loose;
  }
  const gp_Pnt end(StepWall::kLength, StepWall::kStepHeight, 0), top_end(StepWall::kLength, StepWall::kChannelHeight, 0);
  const gp_Pnt top_start(0, StepWall::kChannelHeight, 0), start(0, 0, 0);
  wire.Add(BRepBuilderAPI_MakeEdge(end, top_end).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(top_end, top_start).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(top_start, start).Edge());
  return BRepBuilderAPI_MakeFace(wire.Wire(), true).Face();
}

}  // namespace

BSplineCurve2d profile() {
  return BSplineCurve2d(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{2, 0}, {3, 1}, {2.5, 2}, {3.5, 2.5}, {4, 3}});
}

void write_primitive(const std::filesystem::path& path, Primitive primitive, const Axis& axis) {
  write_step_or_iges(path, build(primitive, axis));
}

void write_forward_facing_step(const std::filesystem::path& path) {
  constexpr double depth = 4.0;
  const gp_Cylinder fillet(gp_Ax3(gp_Pnt(10, 1, 0), gp::DZ(), gp::DX()), 1.0);
  BRepBuilderAPI_Sewing sewing;
  sewing.Add(polygon_face({gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0), gp_Pnt(10, 0, depth), gp_Pnt(0, 0, depth)}));
  sewing.Add(BRepBuilderAPI_MakeFace(fillet, -std::numbers::pi / 2, 0.0, 0.0, depth).Face());
  sewing.Add(polygon_face({gp_Pnt(11, 1, 0), gp_Pnt(11, 3, 0), gp_Pnt(11, 3, depth), gp_Pnt(11, 1, depth)}));
  sewing.Add(polygon_face({gp_Pnt(11, 3, 0), gp_Pnt(20, 3, 0), gp_Pnt(20, 3, depth), gp_Pnt(11, 3, depth)}));
  sewing.Perform();
  write_step_or_iges(path, sewing.SewedShape());
}

void write_step_wall(const std::filesystem::path& path, StepWallDrawing drawing) {
  write_step_or_iges(path, step_wall_shape(drawing));
}

void write_lone_vertex(const std::filesystem::path& path) {
  write_step_or_iges(path, BRepBuilderAPI_MakeVertex(gp_Pnt(1, 2, 3)).Vertex());
}

std::vector<std::vector<Vec3>> edge_points(const std::filesystem::path& path, int samples) {
  TopoDS_Shape shape;
  if (path.extension() == ".igs") {
    IGESControl_Reader reader;
    Interface_Static::SetCVal("xstep.cascade.unit", "M");
    if (reader.ReadFile(path.string().c_str()) != IFSelect_RetDone) throw std::runtime_error("IGES not read");
    reader.TransferRoots();
    shape = reader.OneShape();
  } else {
    STEPControl_Reader reader;
    Interface_Static::SetCVal("xstep.cascade.unit", "M");
    if (reader.ReadFile(path.string().c_str()) != IFSelect_RetDone) throw std::runtime_error("STEP not read");
    reader.TransferRoots();
    shape = reader.OneShape();
  }
  std::vector<std::vector<Vec3>> result;
  for (TopExp_Explorer it(shape, TopAbs_EDGE); it.More(); it.Next()) {
    const BRepAdaptor_Curve curve(TopoDS::Edge(it.Current()));
    std::vector<Vec3> points;
    for (int i = 0; i <= samples; ++i) {
      const gp_Pnt p = curve.Value(curve.FirstParameter() + (curve.LastParameter() - curve.FirstParameter()) * i / samples);
      points.push_back({p.X(), p.Y(), p.Z()});
    }
    result.push_back(std::move(points));
  }
  return result;
}

}  // namespace hotmesh::geometry::test
