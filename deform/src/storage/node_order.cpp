// hotmesh deform: reverse Cuthill-McKee over the cells' node graph.
#include "hotmesh/deform/node_order.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>

namespace hotmesh::deform {
namespace {

/// The number of cells around node n: the degree by which Cuthill-McKee orders neighbours.
std::size_t degree(const NodeCells& around, NodeId n) { return around.of(static_cast<std::size_t>(n)).size(); }

/// Breadth-first levels from `root` over the nodes not yet numbered: the last level's node
/// with the fewest cells around it (the lowest number among equals) and the number of levels.
struct FarNode {
  NodeId node;
  int levels;
};

FarNode farthest_level(const ElementList& cells, const NodeCells& around, NodeId root, std::span<const char> numbered,
                       std::vector<std::int32_t>& seen, std::int32_t stamp, std::vector<NodeId>& queue) {
  queue.assign(1, root);
  seen[static_cast<std::size_t>(root)] = stamp;
  std::size_t level_start = 0;
  int levels = 0;
  while (level_start < queue.size()) {
    const std::size_t level_end = queue.size();
    ++levels;
    for (std::size_t q = level_start; q < level_end; ++q) {
      for (CellId c : around.of(static_cast<std::size_t>(queue[q]))) {
        for (NodeId n : cells.nodes(static_cast<std::size_t>(c))) {
          const auto i = static_cast<std::size_t>(n);
          if (seen[i] == stamp || numbered[i]) continue;
          seen[i] = stamp;
          queue.push_back(n);
        }
      }
    }
    if (queue.size() == level_end) {  // the last level
      NodeId best = queue[level_start];
      for (std::size_t q = level_start; q < level_end; ++q) {
        const NodeId n = queue[q];
        if (degree(around, n) < degree(around, best) || (degree(around, n) == degree(around, best) && n < best)) best = n;
      }
      return {best, levels};
    }
    level_start = level_end;
  }
  return {root, levels};
}

}  // namespace

std::vector<NodeId> reverse_cuthill_mckee(const ElementList& cells, const NodeCells& around) {
  const std::size_t nodes = around.start.size() - 1;
  std::vector<NodeId> order;
  order.reserve(nodes);
  std::vector<char> numbered(nodes, 0);
  std::vector<std::int32_t> seen(nodes, -1);
  std::vector<NodeId> queue, next;
  std::int32_t stamp = 0;
  for (std::size_t first = 0; first < nodes; ++first) {
    if (numbered[first]) continue;
    // A pseudo-peripheral node of this part: from the far end of the levels, while they deepen.
    FarNode far = farthest_level(cells, around, static_cast<NodeId>(first), numbered, seen, stamp++, queue);
    NodeId root = static_cast<NodeId>(first);
    for (int sweep = 0; sweep < 8; ++sweep) {
      const FarNode again = farthest_level(cells, around, far.node, numbered, seen, stamp++, queue);
      root = far.node;
      if (again.levels <= far.levels) break;
      far = again;
    }
    // Cuthill-McKee from the root.
    std::size_t head = order.size();
    order.push_back(root);
    numbered[static_cast<std::size_t>(root)] = 1;
    for (; head < order.size(); ++head) {
      next.clear();
      for (CellId c : around.of(static_cast<std::size_t>(order[head]))) {
        for (NodeId n : cells.nodes(static_cast<std::size_t>(c))) {
          if (numbered[static_cast<std::size_t>(n)]) continue;
          numbered[static_cast<std::size_t>(n)] = 1;
          next.push_back(n);
        }
      }
      std::sort(next.begin(), next.end(), [&](NodeId a, NodeId b) {
        return degree(around, a) != degree(around, b) ? degree(around, a) < degree(around, b) : a < b;
      });
      order.insert(order.end(), next.begin(), next.end());
    }
  }
  std::reverse(order.begin(), order.end());
  return order;
}

double mean_spread(const ElementList& cells, std::span<const NodeId> position) {
  const auto at = [&](NodeId n) {
    return static_cast<double>(position.empty() ? n : position[static_cast<std::size_t>(n)]);
  };
  double sum = 0.0;
  std::size_t pairs = 0;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto corners = cells.nodes(c);
    for (std::size_t a = 0; a < corners.size(); ++a) {
      for (std::size_t b = a + 1; b < corners.size(); ++b, ++pairs) sum += std::abs(at(corners[a]) - at(corners[b]));
    }
  }
  return pairs == 0 ? 0.0 : sum / static_cast<double>(pairs);
}

}  // namespace hotmesh::deform
