// hotmesh api: what the public library's Case and Result hold (hotmesh/hotmesh.hpp's pimpl).
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "hotmesh/api/deform_run.hpp"
#include "hotmesh/hotmesh.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh {

struct Case::State {
  io::Case c;  ///< as read, with the deflections given since
  int threads = 0;
  ProgressCallback progress;
  /// The mesh and CAD file, read by the first deform(); its case is the latest run's.
  std::shared_ptr<api::LoadedCase> loaded;
  std::mutex running;  ///< one motion of a case at a time
};

struct Result::State {
  std::shared_ptr<const api::LoadedCase> loaded;  ///< the mesh moved
  io::Case c;                                     ///< the case as it ran
  setup::CaseSetup setup;
  deform::MotionResult motion;
  mesh::SolverQuality solver;  ///< the flow solver's measures of the moved mesh
  api::RunTimings timings;
  std::vector<Point> points;
  std::vector<std::int64_t> ids;
};

/// Installs the library's logger (stderr, warnings and errors) unless set_verbosity() did.
void start_library_logging();

}  // namespace hotmesh
