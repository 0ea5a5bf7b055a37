// hotmesh geometry: ordering unordered FEM nodes along the curve they sample (2D cases without
// a CAD curve), through the longest path of their Euclidean minimum spanning tree.
#include <algorithm>
#include <limits>
#include <tuple>

#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::geometry {

namespace {

/// Prim's algorithm on the complete graph, O(n^2) time and O(n) memory: parent[i] of every
/// node but the root 0.
std::vector<std::size_t> minimum_spanning_tree(std::span<const Vec2> points) {
  const std::size_t n = points.size();
  std::vector<double> best(n, std::numeric_limits<double>::infinity());
  std::vector<std::size_t> parent(n, 0);
  std::vector<char> done(n, 0);
  best[0] = 0.0;
  for (std::size_t iteration = 0; iteration < n; ++iteration) {
    std::size_t u = n;
    for (std::size_t v = 0; v < n; ++v) {
      if (!done[v] && (u == n || best[v] < best[u])) u = v;
    }
    done[u] = 1;
    for (std::size_t v = 0; v < n; ++v) {
      if (done[v]) continue;
      const Vec2 d = points[v] - points[u];
      const double length2 = dot(d, d);
      if (length2 < best[v]) {
        best[v] = length2;
        parent[v] = u;
      }
    }
  }
  return parent;
}

/// Tree distances from `from` along the edges; `previous` gives the path back.
std::vector<double> tree_distances(std::span<const Vec2> points, const std::vector<std::vector<std::size_t>>& adjacency,
                                   std::size_t from, std::vector<std::size_t>& previous) {
  const std::size_t n = points.size();
  std::vector<double> distance(n, -1.0);
  previous.assign(n, n);
  std::vector<std::size_t> stack{from};
  distance[from] = 0.0;
  while (!stack.empty()) {
    const std::size_t u = stack.back();
    stack.pop_back();
    for (const std::size_t v : adjacency[u]) {
      if (distance[v] >= 0.0) continue;
      distance[v] = distance[u] + geometry::distance(points[u], points[v]);
      previous[v] = u;
      stack.push_back(v);
    }
  }
  return distance;
}

}  // namespace

std::vector<std::size_t> order_along_curve(std::span<const Vec2> points) {
  const std::size_t n = points.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  if (n < 3) {
    if (n == 2 && std::tie(points[1].x, points[1].y) < std::tie(points[0].x, points[0].y)) std::swap(order[0], order[1]);
    return order;
  }
  const std::vector<std::size_t> parent = minimum_spanning_tree(points);
  std::vector<std::vector<std::size_t>> adjacency(n);
  for (std::size_t v = 1; v < n; ++v) {
    adjacency[v].push_back(parent[v]);
    adjacency[parent[v]].push_back(v);
  }
  // The tree's longest path: farthest node a from any node, then farthest b from a.
  std::vector<std::size_t> previous;
  std::vector<double> d = tree_distances(points, adjacency, 0, previous);
  const auto a = static_cast<std::size_t>(std::max_element(d.begin(), d.end()) - d.begin());
  d = tree_distances(points, adjacency, a, previous);
  const auto b = static_cast<std::size_t>(std::max_element(d.begin(), d.end()) - d.begin());
  std::vector<std::size_t> spine;
  for (std::size_t v = b; v != n; v = previous[v]) spine.push_back(v);  // b ... a

  // Every node gets a place (segment, position along it) on the spine polyline.
  std::vector<char> on_spine(n, 0);
  for (const std::size_t v : spine) on_spine[v] = 1;
  struct Place {
    std::size_t segment;
    double position;
    std::size_t node;
  };
  std::vector<Place> places;
  places.reserve(n);
  for (std::size_t i = 0; i < spine.size(); ++i) places.push_back({i, 0.0, spine[i]});
  for (std::size_t v = 0; v < n; ++v) {
    if (on_spine[v]) continue;
    Place best{0, 0.0, v};
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < spine.size(); ++i) {
      const Vec2 s = points[spine[i]];
      const Vec2 e = points[spine[i + 1]] - s;
      const double length2 = dot(e, e);
      const double u = length2 > 0.0 ? std::clamp(dot(points[v] - s, e) / length2, 0.0, 1.0) : 0.0;
      const double dist = geometry::distance(s + u * e, points[v]);
      if (dist < best_distance) {
        best_distance = dist;
        best = {i, u, v};
      }
    }
    places.push_back(best);
  }
  std::stable_sort(places.begin(), places.end(), [](const Place& x, const Place& y) {
    return std::tie(x.segment, x.position) < std::tie(y.segment, y.position);
  });
  for (std::size_t i = 0; i < n; ++i) order[i] = places[i].node;
  const Vec2 first = points[order.front()];
  const Vec2 last = points[order.back()];
  if (std::tie(last.x, last.y) < std::tie(first.x, first.y)) std::reverse(order.begin(), order.end());
  return order;
}

}  // namespace hotmesh::geometry
