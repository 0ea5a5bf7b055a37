// hotmesh tests: faults injected into a hotmesh process by the test library
// libhotmesh_faults.so (fault_library.cpp), which the command preloads: a real SIGKILL, or
// memory running out, at a known point of a `hotmesh deform` run. K counts the checkpoints the
// process has put in place (one after every accepted increment or piece of one); only the
// process that writes them, rank 0 under mpirun, is hit.
#pragma once

#include <map>
#include <string>

#include "sanitizer_build.hpp"

namespace hotmesh::test {

struct Faults {
  int kill_after_checkpoint = 0;             ///< K > 0: SIGKILL right after the K-th checkpoint
  int fail_allocation_after_checkpoint = 0;  ///< K > 0: std::bad_alloc at the next large allocation after it
  std::string hold_cad_check;                ///< a file: `hotmesh cad` processes wait until it exists
};

/// "NAME=value ... " to put before a command that /bin/sh runs (empty for no faults).
std::string fault_variables(const Faults& faults);

/// The same as a process's environment entries (ServeProcess's).
std::map<std::string, std::string> fault_environment(const Faults& faults);

/// The same as options of Open MPI's mpirun ("-x NAME=value ... "), for the ranks it starts.
std::string mpirun_fault_options(const Faults& faults);

/// Whether an allocation failure injected by the library reaches hotmesh: not under clang's
/// AddressSanitizer, whose runtime is linked into the executable and so keeps operator new
/// before any preloaded library. (GCC's runtime is a shared library, which the test library
/// comes before.)
constexpr bool allocation_faults_reach_hotmesh() {
#if defined(__clang__)
  return !HOTMESH_TEST_UNDER_ASAN;
#else
  return true;
#endif
}

}  // namespace hotmesh::test
