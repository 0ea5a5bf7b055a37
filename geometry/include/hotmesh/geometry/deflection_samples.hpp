// hotmesh geometry: deflections computed by an FEM code at its boundary nodes: the points Q_j
// and deflections delta_j of the paper's eq. (21), as read from a deflection table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

/// How the coordinates of a table are to be read.
enum class SampleFrame {
  planar,      ///< x, y (2D cases); stored as (x, y, 0)
  cartesian,   ///< x, y, z
  meridional,  ///< r, z about the case's axis; stored as (r, z, 0)
};

const char* to_string(SampleFrame frame);

struct DeflectionSamples {
  SampleFrame frame = SampleFrame::cartesian;
  std::vector<Vec3> points;       ///< Q_j, undeformed FEM node positions
  std::vector<Vec3> deflections;  ///< delta_j, in the same frame as points
  std::vector<std::int64_t> ids;  ///< FEM node ids from an "id" column; empty if none
  std::vector<std::size_t> lines; ///< 1-based source line of each sample, for messages
  std::string source;             ///< where the samples came from (file name), for messages

  std::size_t size() const { return points.size(); }
  /// "node 17 (line 19)", "node 17", "line 19" or "sample 3" for sample j (0-based).
  std::string label(std::size_t j) const;
};

/// A sample's name in messages from its FEM node id and source line, where known (as
/// DeflectionSamples::label).
std::string sample_label(std::span<const std::int64_t> ids, std::span<const std::size_t> lines, std::size_t j);

}  // namespace hotmesh::geometry
