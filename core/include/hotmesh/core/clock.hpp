// hotmesh core: wall-clock time for the timings a run reports (report.json's seconds, the log)
// and the benchmarks measure: a steady clock, never the calendar's.
#pragma once

#include <chrono>

namespace hotmesh {

using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace hotmesh
