// hotmesh deform (internal): the seconds since a time point, for the run's timings
// (MotionTimings). The one definition in deform, so that a shared one can replace it.
#pragma once

#include <chrono>

namespace hotmesh::deform::detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace hotmesh::deform::detail
