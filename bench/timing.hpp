// hotmesh benchmarks: wall-clock timing and the median of repeated runs.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace hotmesh::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The median of non-empty `v` (the upper one for an even count).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace hotmesh::bench
