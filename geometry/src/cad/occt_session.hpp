// hotmesh geometry (internal): exclusive use of OpenCASCADE's data-exchange layer. STEP and
// IGES readers and writers keep their parameters in process-wide statics (Interface_Static)
// and print through the process-wide messenger, so every use holds one mutex, silences the
// messenger (hotmesh reports problems itself; stdout may carry JSON) and restores every
// parameter it changed when it ends (RAII). The session registers the STEP and IGES
// parameters first, so they can be set before a reader or writer is made.
#pragma once

#include <signal.h>

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

/// While alive, a segmentation fault, bus error, illegal instruction or bad system call in
/// OpenCASCADE's code (a damaged STEP file can make its translation follow a null reference)
/// raises a Standard_Failure at the innermost OCC_CATCH_SIGNALS of the thread, instead of
/// killing the process. OpenCASCADE's own mechanism (OSD::SetSignal), limited to the faults
/// and to the object's lifetime: the process's handlers (interrupt, hang-up, quit, floating
/// point, and a sanitizer's) are restored when it ends. Use it inside an OcctSession and write
///   detail::FaultsAsFailures faults;
///   try { OCC_CATCH_SIGNALS ... } catch (const Standard_Failure&) { ... }
/// Objects made between OCC_CATCH_SIGNALS and the fault are abandoned, not destroyed.
class FaultsAsFailures {
 public:
  FaultsAsFailures();
  ~FaultsAsFailures();
  FaultsAsFailures(const FaultsAsFailures&) = delete;
  FaultsAsFailures& operator=(const FaultsAsFailures&) = delete;

 private:
  std::vector<std::pair<int, struct sigaction>> saved_;
  // A reference cycle in a file makes the translation recurse until the stack overflows:
  // the fault's handler runs on a stack of its own.
  std::vector<char> handler_stack_;
  stack_t saved_stack_{};
};

/// OpenCASCADE's name of a length unit ("M", "MM", "INCH", ...).
const char* occt_unit_name(LengthUnit unit);

}  // namespace hotmesh::geometry::detail
