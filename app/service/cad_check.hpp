// hotmesh serve (internal): each CAD file the service loads is first read by a child process,
// `hotmesh cad FILE`. A damaged file can make OpenCASCADE fault (turned into an error, see
// geometry's FaultsAsFailures) and, where OpenCASCADE recovers from the fault itself, abandon
// the file's whole model (about 1.5 MB a file): harmless in a command that ends, but a
// long-running service would keep every loss. A child takes the loss, the fault and the time
// (it is stopped after a bound) with it; the service reads only files the child could read.
#pragma once

#include <chrono>
#include <filesystem>

#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::app::serve {

struct CadCheck {
  std::filesystem::path hotmesh;  ///< the executable that reads the file (empty: no check)
  std::chrono::seconds time_limit{120};
};

/// Reads `file` in a child `hotmesh -q cad FILE --unit UNIT`. Throws hotmesh::InputError with
/// the child's message (naming `file`) if it refuses the file, dies or takes longer than the
/// limit; returns if it read the file.
void check_cad_in_child(const CadCheck& check, const std::filesystem::path& file, geometry::LengthUnit unit);

}  // namespace hotmesh::app::serve
