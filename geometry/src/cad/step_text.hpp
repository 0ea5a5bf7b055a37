// hotmesh geometry (internal): the text of the STEP file an OpenCASCADE writer holds, written to
// memory so that callers can write files atomically. Call it inside the OcctSession that made
// the writer's model.
#pragma once

#include <string>

#include <STEPControl_Writer.hxx>

namespace hotmesh::geometry::detail {

/// The writer's model as STEP text. Throws std::runtime_error if OpenCASCADE cannot print it.
std::string step_text(STEPControl_Writer& writer);

}  // namespace hotmesh::geometry::detail
