// hotmesh geometry (internal): exclusive use of OpenCASCADE's data-exchange layer. STEP and
// IGES readers and writers keep their parameters in process-wide statics (Interface_Static)
// and print through the process-wide messenger, so every use holds one mutex, silences the
// messenger (hotmesh reports problems itself; stdout may carry JSON) and restores every
// parameter it changed when it ends (RAII). The session registers the STEP and IGES
// parameters first, so they can be set before a reader or writer is made.
#pragma once

#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <Message_SequenceOfPrinters.hxx>

#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::geometry::detail {

class OcctSession {
 public:
  OcctSession();
  ~OcctSession();
  OcctSession(const OcctSession&) = delete;
  OcctSession& operator=(const OcctSession&) = delete;

  /// Sets a string parameter (e.g. "write.step.unit") until the session ends. Throws
  /// std::logic_error if OpenCASCADE has no such parameter or refuses the value.
  void set(const char* name, const char* value);

  /// The unit of shape coordinates for readers and writers until the session ends: the
  /// "xstep.cascade.unit" parameter and the process-wide unit that writers scale from
  /// (UnitsMethods), which readers set as a side effect.
  void use_unit(LengthUnit unit);

 private:
  std::unique_lock<std::mutex> lock_;
  Message_SequenceOfPrinters printers_;
  std::vector<std::pair<std::string, std::string>> saved_;
  double saved_unit_in_mm_ = 0.0;
};

/// OpenCASCADE's name of a length unit ("M", "MM", "INCH", ...).
const char* occt_unit_name(LengthUnit unit);

}  // namespace hotmesh::geometry::detail
