// hotmesh geometry: STEP output of a meridional profile revolved about an axis (one face per
// meridian, BRepPrimAPI_MakeRevol), through the serialised OpenCASCADE session.
#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <GC_MakeSegment.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepBasic_Product.hxx>
#include <StepData_StepModel.hxx>
#include <StepShape_AdvancedFace.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Ax1.hxx>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "cad/occt_convert.hpp"
#include "cad/occt_session.hpp"
#include "cad/step_text.hpp"
#include "hotmesh/geometry/revolved_export.hpp"

namespace hotmesh::geometry {

namespace {

/// The meridian placed in the half-plane theta = 0: a line segment if it is straight (so the
/// sweep makes a plane, cylinder or cone), its B-spline otherwise.
Handle(Geom_Curve) placed_meridian(const BSplineCurve2d& meridian, const Axis& axis) {
  const Vec3 radial = axis.meridional_vector(0.0, 1.0, 0.0);
  const auto place = [&](const Vec2& rz) { return detail::to_pnt(axis.origin() + rz.x * radial + rz.y * axis.direction()); };
  if (meridian.degree() == 1 && meridian.poles().size() == 2) {
    const Handle(Geom_TrimmedCurve) segment = GC_MakeSegment(place(meridian.poles().front()), place(meridian.poles().back()));
    return Handle(Geom_Curve)(segment.get());
  }
  return detail::to_occt_3d(meridian, axis.origin(), radial, axis.direction());
}

TopoDS_Face revolved_face(const RevolvedFace& face, const Axis& axis, double angle) {
  const gp_Ax1 line(detail::to_pnt(axis.origin()), detail::to_dir(axis.direction()));
  const TopoDS_Shape edge = BRepBuilderAPI_MakeEdge(placed_meridian(face.meridian, axis)).Edge();
  BRepPrimAPI_MakeRevol sweep(edge, line, angle);
  sweep.Build();
  TopExp_Explorer faces(sweep.Shape(), TopAbs_FACE);
  if (!sweep.IsDone() || !faces.More()) throw std::runtime_error("revolving the meridian '" + face.name + "' failed");
  return TopoDS::Face(faces.Current());
}

void check(const RevolvedModel& model) {
  if (!(model.angle > 0.0 && model.angle <= 2.0 * std::numbers::pi)) {
    throw std::invalid_argument("revolved model: the angle must be in (0, 2 pi] radians");
  }
  if (model.faces.empty()) throw std::invalid_argument("revolved model: no faces");
  for (const RevolvedFace& face : model.faces) {
    for (const Vec2& pole : face.meridian.poles()) {
      if (!(pole.x >= 0.0)) {
        throw std::invalid_argument("revolved model: meridian '" + face.name + "' has a pole at r < 0");
      }
    }
  }
}

}  // namespace

std::string to_step(const RevolvedModel& model) {
  check(model);
  try {
    detail::OcctSession session;
    session.use_unit(model.unit);
    session.set("write.step.unit", detail::occt_unit_name(model.unit));
    // One root per face, in order: CadModel::read finds them in the same order.
    STEPControl_Writer writer;
    for (const RevolvedFace& face : model.faces) {
      if (writer.Transfer(revolved_face(face, model.axis, model.angle), STEPControl_AsIs) != IFSelect_RetDone) {
        throw std::runtime_error("the STEP writer could not transfer the face '" + face.name + "'");
      }
    }
    // Each face became a PRODUCT and an ADVANCED_FACE, in transfer order: both take the face's
    // name (the products would otherwise carry a process-wide counter).
    std::size_t product = 0, advanced = 0;
    const Handle(StepData_StepModel) step = writer.Model();
    for (Standard_Integer i = 1; i <= step->NbEntities(); ++i) {
      const Handle(Standard_Transient) entity = step->Value(i);
      if (entity->IsKind(STANDARD_TYPE(StepBasic_Product)) && product < model.faces.size()) {
        const auto& name = model.faces[product++].name;
        const Handle(TCollection_HAsciiString) text = new TCollection_HAsciiString(name.empty() ? "face" : name.c_str());
        Handle(StepBasic_Product)::DownCast(entity)->SetId(text);
        Handle(StepBasic_Product)::DownCast(entity)->SetName(text);
      } else if (entity->IsKind(STANDARD_TYPE(StepShape_AdvancedFace)) && advanced < model.faces.size()) {
        const auto& name = model.faces[advanced++].name;
        if (!name.empty()) Handle(StepShape_AdvancedFace)::DownCast(entity)->SetName(new TCollection_HAsciiString(name.c_str()));
      }
    }
    if (!model.time_stamp.empty()) {
      APIHeaderSection_MakeHeader header(step);
      header.SetTimeStamp(new TCollection_HAsciiString(model.time_stamp.c_str()));
    }
    return detail::step_text(writer);
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("STEP output failed: ") + e.GetMessageString());
  }
}

}  // namespace hotmesh::geometry
