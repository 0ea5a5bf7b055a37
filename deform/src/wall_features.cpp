// hotmesh deform: the corners of a sliding wall held by mesh nodes (wall_features.hpp).
#include "wall_features.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <utility>

#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform::detail {
namespace {

/// A node given a corner keeps each of its wall edges at least this share of its length.
constexpr double kMinEdgeShare = 0.25;

/// A wall edge whose ends lie on either side of a corner (or on it).
struct Crossing {
  std::size_t feature;
  std::size_t a;  ///< ends, as indices into Patch::nodes
  std::size_t b;
  double nearest;  ///< distance of the nearer end to the corner
};

/// The wall's edges (the faces' sides), as pairs of indices into Patch::nodes.
std::vector<std::pair<std::size_t, std::size_t>> wall_edges(const Patch& patch,
                                                            const std::unordered_map<NodeId, std::size_t>& index) {
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto face = patch.faces.nodes(f);
    const std::size_t sides = face.size() == 2 ? 1 : face.size();
    for (std::size_t i = 0; i < sides; ++i) {
      std::size_t a = index.at(face[i]);
      std::size_t b = index.at(face[(i + 1) % face.size()]);
      if (a > b) std::swap(a, b);
      edges.emplace_back(a, b);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace

WallFeaturePlan plan_wall_features(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch,
                                   const geometry::BoundaryShape& shape, double min_angle, const CanHold& can_hold) {
  WallFeaturePlan plan;
  const std::vector<geometry::ShapeFeature> corners = shape.features(min_angle);
  const std::size_t count = patch.nodes.size();
  plan.segments.assign(count, {});
  if (corners.empty() || count == 0) return plan;
  for (const auto& c : corners) plan.features.push_back({c, {}, {}, 0.0, 0, {}});

  // Where each node of the wall lies on the shape before the motion.
  plan.parameters.resize(count);
  mesh::LoopExceptions errors;  // the projections run behind geometry's BoundaryShape interface
#pragma omp parallel for schedule(dynamic, 64) if (static_cast<std::ptrdiff_t>(count) >= mesh::kParallelProjections)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(count); ++i) {
    errors.run([&] {
      const auto k = static_cast<std::size_t>(i);
      plan.parameters[k] = shape.project(x0[static_cast<std::size_t>(patch.nodes[k])], 0.0).parameter;
    });
  }
  errors.rethrow();

  std::unordered_map<NodeId, std::size_t> index;
  for (std::size_t k = 0; k < count; ++k) index[patch.nodes[k]] = k;
  const auto edges = wall_edges(patch, index);
  std::vector<std::vector<std::size_t>> neighbours(count);
  for (const auto& [a, b] : edges) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }

  const auto x = [&](std::size_t k) { return x0[static_cast<std::size_t>(patch.nodes[k])]; };
  // The corner's point in the meridional plane of node k (in 2D: the point).
  const auto corner_at = [&](std::size_t f, std::size_t k) {
    return shape.at(plan.features[f].feature.parameter, 0.0, x(k)).point;
  };
  std::vector<double> corner_parameters;
  for (const auto& c : corners) corner_parameters.push_back(c.parameter);

  std::vector<Crossing> crossings;
  for (const auto& [a, b] : edges) {
    const double lo = std::min(plan.parameters[a], plan.parameters[b]);
    const double hi = std::max(plan.parameters[a], plan.parameters[b]);
    auto it = std::lower_bound(corner_parameters.begin(), corner_parameters.end(), lo);
    for (; it != corner_parameters.end() && *it <= hi; ++it) {
      const auto f = static_cast<std::size_t>(it - corner_parameters.begin());
      crossings.push_back({f, a, b, std::min(distance(x(a), corner_at(f, a)), distance(x(b), corner_at(f, b)))});
    }
  }
  std::stable_sort(crossings.begin(), crossings.end(),
                   [](const Crossing& l, const Crossing& r) { return l.nearest < r.nearest; });

  const double on_corner = 1e-6 * bounding_diagonal(mesh.points, patch.nodes);
  std::vector<int> holds(count, -1);  // the corner each node holds
  std::vector<Vec3> moved(count);     // where a node holding a corner goes at stage 0
  const auto position = [&](std::size_t k) { return holds[k] >= 0 ? moved[k] : x(k); };
  // Giving node k the corner point q shrinks none of its wall edges below kMinEdgeShare.
  const auto keeps_edges = [&](std::size_t k, const Vec3& q) {
    return std::all_of(neighbours[k].begin(), neighbours[k].end(), [&](std::size_t j) {
      return distance(q, position(j)) >= kMinEdgeShare * distance(x(k), position(j));
    });
  };
  for (const Crossing& c : crossings) {
    HeldFeature& held = plan.features[c.feature];
    const auto f = static_cast<int>(c.feature);
    if (holds[c.a] == f || holds[c.b] == f) continue;
    std::array<std::size_t, 2> ends{c.a, c.b};
    if (distance(x(c.b), corner_at(c.feature, c.b)) < distance(x(c.a), corner_at(c.feature, c.a))) {
      std::swap(ends[0], ends[1]);
    }
    bool done = false;
    for (const std::size_t k : ends) {
      const NodeId n = patch.nodes[k];
      const Vec3 q = corner_at(c.feature, k);
      const double offset = distance(x(k), q);
      if (!can_hold(n, q)) {
        if (offset > on_corner) continue;
        held.held_by_role.push_back(n);  // a node of another role already on the corner
      } else if (holds[k] >= 0 || !keeps_edges(k, q)) {
        continue;
      } else {
        held.nodes.push_back(n);
        held.largest_offset = std::max(held.largest_offset, offset);
        moved[k] = q;
      }
      holds[k] = f;
      done = true;
      break;
    }
    if (!done) ++held.unheld_edges;
  }

  for (HeldFeature& held : plan.features) {
    if (held.unheld_edges == 0) continue;
    const Vec3 p = shape.at(held.feature.parameter, 1.0, x(0)).point;
    held.note = fmt::format(
        "patch '{}': the corner at ({:.6g}, {:.6g}, {:.6g}) (turning {:.1f} degrees) has no node on {} of the wall "
        "edges that cross it: their ends hold other corners, lie on other patches, or would squash a wall cell (two "
        "corners within one cell); the wall cuts the corner there",
        patch.name, p.x, p.y, p.z, held.feature.angle * 180.0 / std::numbers::pi, held.unheld_edges);
  }

  // Segments: the parameter interval between the corners on either side of each node.
  for (std::size_t k = 0; k < count; ++k) {
    const double t = plan.parameters[k];
    const auto after = std::upper_bound(corner_parameters.begin(), corner_parameters.end(), t);
    geometry::ParameterRange& segment = plan.segments[k];
    if (after != corner_parameters.begin()) segment.first = *(after - 1);
    if (after != corner_parameters.end()) segment.last = *after;
  }
  return plan;
}

}  // namespace hotmesh::deform::detail
