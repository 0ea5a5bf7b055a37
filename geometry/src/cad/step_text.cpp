// hotmesh geometry (internal): STEP text of a writer's model (see step_text.hpp).
#include "cad/step_text.hpp"

#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <XSControl_WorkSession.hxx>

#include <sstream>
#include <stdexcept>

namespace hotmesh::geometry::detail {

std::string step_text(STEPControl_Writer& writer) {
  StepData_StepWriter out(writer.Model());
  out.SendModel(Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol()));
  std::ostringstream text;
  if (!out.Print(text)) throw std::runtime_error("the STEP writer failed");
  return text.str();
}

}  // namespace hotmesh::geometry::detail
