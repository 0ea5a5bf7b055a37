// hotmesh geometry (internal): how reconstructions name FEM nodes in their messages ("node 17
// (line 19) at distance 0.0012; ..."), shared by curves and surfaces.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::geometry::detail {

/// Nodes listed in a message before "and N more".
inline constexpr std::size_t kListedNodes = 20;

/// A number with 6 significant digits.
inline std::string format(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

/// "node 17 (line 19) at distance 0.0012; node 18 ...; and 4 more".
inline std::string list_nodes(const std::vector<NodeDistance>& nodes) {
  std::string text;
  for (std::size_t i = 0; i < nodes.size() && i < kListedNodes; ++i) {
    if (i > 0) text += "; ";
    text += nodes[i].label + " at distance " + format(nodes[i].distance);
  }
  if (nodes.size() > kListedNodes) text += "; and " + std::to_string(nodes.size() - kListedNodes) + " more";
  return text;
}

}  // namespace hotmesh::geometry::detail
