// hotmesh benchmarks: wall-clock timing and the median of repeated runs.
#pragma once

#include <algorithm>
#include <vector>

#include "hotmesh/core/clock.hpp"

namespace hotmesh::bench {

using hotmesh::Clock;
using hotmesh::seconds_since;

/// The median of non-empty `v` (the upper one for an even count).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace hotmesh::bench
