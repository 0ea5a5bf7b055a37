// hotmesh geometry: STEP and IGES output of B-spline curves and surfaces through
// OpenCASCADE's writers (serialised, in the caller's length unit, written to memory).
#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <Precision.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <StepShape_AdvancedFace.hxx>
#include <StepShape_GeometricCurveSet.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TransferBRep.hxx>
#include <UnitsMethods.hxx>
#include <TransferBRep_ShapeMapper.hxx>
#include <Transfer_FinderProcess.hxx>
#include <XSControl_TransferWriter.hxx>

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "cad/occt_convert.hpp"
#include "cad/occt_session.hpp"
#include "cad/step_text.hpp"
#include "hotmesh/geometry/cad_export.hpp"

namespace hotmesh::geometry {

namespace {

using NamedShapes = std::vector<std::pair<TopoDS_Shape, std::string>>;

NamedShapes shapes_of(const CadExport& content) {
  NamedShapes shapes;
  for (const ExportCurve& c : content.curves) {
    const auto curve = detail::to_occt_3d(c.curve, c.frame.origin, c.frame.u, c.frame.v);
    shapes.emplace_back(BRepBuilderAPI_MakeEdge(curve).Edge(), c.name);
  }
  for (const ExportSurface& s : content.surfaces) {
    shapes.emplace_back(BRepBuilderAPI_MakeFace(detail::to_occt(s.surface), Precision::Confusion()).Face(), s.name);
  }
  return shapes;
}

/// The entity a shape became, found in the writer's transfer record.
Handle(Standard_Transient) entity_of(const Handle(Transfer_FinderProcess)& process, const TopoDS_Shape& shape) {
  if (process.IsNull()) return nullptr;
  const Handle(TransferBRep_ShapeMapper) mapper = TransferBRep::ShapeMapper(process, shape);
  return process->FindTransient(mapper);
}

const char* iges_unit_name(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::metre: return "M";
    case LengthUnit::millimetre: return "MM";
    case LengthUnit::centimetre: return "CM";
    case LengthUnit::micrometre: return "UM";
    case LengthUnit::inch: return "IN";
    case LengthUnit::foot: return "FT";
  }
  return "M";
}

/// The IGES date of a time stamp "YYYY-MM-DDTHH:MM:SS" (the writer stores it as YYMMDD.HHNNSS).
Handle(TCollection_HAsciiString) iges_date(const std::string& time_stamp) {
  int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
  if (std::sscanf(time_stamp.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d", &year, &month, &day, &hour, &minute, &second) != 6) {
    throw std::invalid_argument("time stamp '" + time_stamp + "' is not YYYY-MM-DDTHH:MM:SS");
  }
  return IGESData_GlobalSection::NewDateString(year, month, day, hour, minute, second, 0);
}

}  // namespace

PlaneFrame meridional_frame(const Axis& axis, double theta) {
  return {axis.origin(), axis.meridional_vector(theta, 1.0, 0.0), axis.direction()};
}

std::string to_step(const CadExport& content) {
  try {
    detail::OcctSession session;
    session.use_unit(content.unit);
    session.set("write.step.unit", detail::occt_unit_name(content.unit));
    STEPControl_Writer writer;
    // One root per shape, in order: curves become GEOMETRIC_CURVE_SETs and surfaces
    // ADVANCED_FACEs, found again in the model in the same order to carry the names.
    for (const auto& [shape, name] : shapes_of(content)) {
      if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone) {
        throw std::runtime_error("the STEP writer could not transfer a shape");
      }
    }
    std::size_t curve = 0;
    std::size_t surface = 0;
    const Handle(StepData_StepModel) model = writer.Model();
    for (Standard_Integer i = 1; i <= model->NbEntities(); ++i) {
      const Handle(Standard_Transient) entity = model->Value(i);
      std::string name;
      if (entity->IsKind(STANDARD_TYPE(StepShape_GeometricCurveSet)) && curve < content.curves.size()) {
        name = content.curves[curve++].name;
      } else if (entity->IsKind(STANDARD_TYPE(StepShape_AdvancedFace)) && surface < content.surfaces.size()) {
        name = content.surfaces[surface++].name;
      }
      if (!name.empty()) {
        Handle(StepRepr_RepresentationItem)::DownCast(entity)->SetName(new TCollection_HAsciiString(name.c_str()));
      }
    }
    if (!content.time_stamp.empty()) {
      APIHeaderSection_MakeHeader header(model);
      header.SetTimeStamp(new TCollection_HAsciiString(content.time_stamp.c_str()));
    }
    return detail::step_text(writer);
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("STEP output failed: ") + e.GetMessageString());
  }
}

std::string to_iges(const CadExport& content) {
  try {
    detail::OcctSession session;
    session.use_unit(content.unit);
    IGESControl_Writer writer(iges_unit_name(content.unit), 0);
    // The model keeps its own copy of the shape unit (millimetres unless told otherwise).
    IGESData_GlobalSection global = writer.Model()->GlobalSection();
    global.SetCascadeUnit(UnitsMethods::GetCasCadeLengthUnit());
    if (!content.time_stamp.empty()) {  // a reproducible file: no date or login of its own
      global.SetDate(iges_date(content.time_stamp));
      global.SetLastChangeDate(iges_date(content.time_stamp));
      global.SetAuthorName(new TCollection_HAsciiString("hotmesh"));
    }
    writer.Model()->SetGlobalSection(global);
    const NamedShapes shapes = shapes_of(content);
    for (const auto& [shape, name] : shapes) {
      if (!writer.AddShape(shape)) throw std::runtime_error("the IGES writer could not take a shape");
      const auto entity = Handle(IGESData_IGESEntity)::DownCast(entity_of(writer.TransferProcess(), shape));
      if (!entity.IsNull() && !name.empty()) entity->SetLabel(new TCollection_HAsciiString(name.substr(0, 8).c_str()));
    }
    writer.ComputeModel();
    std::ostringstream text;
    if (!writer.Write(text)) throw std::runtime_error("the IGES writer failed");
    return text.str();
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string("IGES output failed: ") + e.GetMessageString());
  }
}

}  // namespace hotmesh::geometry
