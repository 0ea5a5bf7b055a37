// hotmesh deform: the corners of a sliding wall held by mesh nodes (wall_features.hpp).
#include "constraints/wall_features.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
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

namespace {

/// plan_wall_features, phase by phase; each phase reads what the ones before it decided.
class CornerPlanner {
 public:
  CornerPlanner(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch, const geometry::BoundaryShape& shape,
                std::vector<geometry::ShapeFeature> corners, std::vector<geometry::ShapeCrease> creases,
                PlanesOf planes_of)
      : mesh_(mesh), x0_(x0), patch_(patch), shape_(shape), planes_of_(std::move(planes_of)), count_(patch.nodes.size()) {
    for (const auto& c : corners) {
      plan_.features.push_back({c, {}, {}, {}, 0.0, 0, {}});
      corner_parameters_.push_back(c.parameter);
    }
    for (const auto& c : creases) {
      crease_of_[face_pair(c.faces[0], c.faces[1])] = plan_.features.size();
      plan_.features.push_back({{0.0, c.angle}, c, {}, {}, 0.0, 0, {}});
    }
    plan_.segments.assign(count_, {});
    holds_.assign(count_, -1);
    moved_.resize(count_);
  }

  /// Where each node of the wall lies on the shape before the motion.
  void locate_nodes() {
    plan_.parameters.resize(count_);
    faces_.resize(count_);
    mesh::LoopExceptions errors;  // the projections run behind geometry's BoundaryShape interface
#pragma omp parallel for schedule(dynamic, 64) if (static_cast<std::ptrdiff_t>(count_) >= mesh::kParallelProjections)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(count_); ++i) {
      errors.run([&] {
        const auto k = static_cast<std::size_t>(i);
        const geometry::ShapeParameter where = shape_.project(x(k), 0.0).parameter;
        plan_.parameters[k] = where.t;
        faces_[k] = where.face;
      });
    }
    errors.rethrow();
  }

  /// The wall's edges, and those that cross a corner (ends on either side of its parameter)
  /// or a crease (ends on its two faces), nearest first.
  void find_crossings() {
    std::unordered_map<NodeId, std::size_t> index;
    for (std::size_t k = 0; k < count_; ++k) index[patch_.nodes[k]] = k;
    const auto edges = wall_edges(patch_, index);
    neighbours_.assign(count_, {});
    for (const auto& [a, b] : edges) {
      neighbours_[a].push_back(b);
      neighbours_[b].push_back(a);
      const double lo = std::min(plan_.parameters[a], plan_.parameters[b]);
      const double hi = std::max(plan_.parameters[a], plan_.parameters[b]);
      auto it = std::lower_bound(corner_parameters_.begin(), corner_parameters_.end(), lo);
      for (; it != corner_parameters_.end() && *it <= hi; ++it) {
        const auto f = static_cast<std::size_t>(it - corner_parameters_.begin());
        crossings_.push_back({f, a, b, std::min(offset(f, a), offset(f, b))});
      }
      if (faces_[a] == faces_[b]) continue;
      const auto crease = crease_of_.find(face_pair(faces_[a], faces_[b]));
      if (crease != crease_of_.end()) {
        crossings_.push_back({crease->second, a, b, std::min(offset(crease->second, a), offset(crease->second, b))});
      }
    }
    std::stable_sort(crossings_.begin(), crossings_.end(),
                     [](const Crossing& l, const Crossing& r) { return l.nearest < r.nearest; });
  }

  /// One end of every crossing edge gets its corner: the nearer one if it can take it. An edge
  /// neither of whose ends can is held through a periodic slave end whose master holds the
  /// corner (the slave follows it onto the corner); else it is left cutting the corner.
  void give_corners(const CanHold& can_hold, const MasterOf& master_of) {
    std::vector<const Crossing*> left;
    const double on_corner = 1e-6 * bounding_diagonal(mesh_.points, patch_.nodes);
    for (const Crossing& c : crossings_) {
      HeldFeature& held = plan_.features[c.feature];
      const auto f = static_cast<int>(c.feature);
      if (holds_[c.a] == f || holds_[c.b] == f) continue;
      std::array<std::size_t, 2> ends{c.a, c.b};
      if (offset(c.feature, c.b) < offset(c.feature, c.a)) std::swap(ends[0], ends[1]);
      bool done = false;
      for (const std::size_t k : ends) {
        const NodeId n = patch_.nodes[k];
        const Vec3 q = corner_at(c.feature, k);
        if (!can_hold(n, q)) {
          if (distance(x(k), q) > on_corner) continue;
          held.held_by_role.push_back(n);  // a node of another role already on the corner
        } else if (holds_[k] >= 0 || !keeps_edges(k, q)) {
          continue;
        } else {
          held.nodes.push_back(n);
          held.largest_offset = std::max(held.largest_offset, distance(x(k), q));
          moved_[k] = q;
        }
        holds_[k] = f;
        done = true;
        break;
      }
      if (!done) left.push_back(&c);
    }
    std::unordered_map<NodeId, std::size_t> index;
    for (std::size_t k = 0; k < count_; ++k) index[patch_.nodes[k]] = k;
    for (const Crossing* c : left) {
      const auto held_by_master = [&](std::size_t k) {
        const auto master = index.find(master_of(patch_.nodes[k]));
        return master != index.end() && holds_[master->second] == static_cast<int>(c->feature);
      };
      if (!held_by_master(c->a) && !held_by_master(c->b)) ++plan_.features[c->feature].unheld_edges;
    }
  }

  /// Only the nodes that lie on a corner get it (plan_corners_on_nodes): the nearer end of a
  /// crossing edge, if it is within reach of the corner.
  void give_corners_to_nodes_on_them(const CanHold& can_hold, double min_angle, bool drawn_corners) {
    const double on_corner = 1e-6 * bounding_diagonal(mesh_.points, patch_.nodes);
    for (const Crossing& c : crossings_) {
      HeldFeature& held = plan_.features[c.feature];
      const auto f = static_cast<int>(c.feature);
      const std::size_t k = offset(c.feature, c.a) <= offset(c.feature, c.b) ? c.a : c.b;
      if (holds_[k] >= 0) continue;
      const bool drawn = drawn_corners && held.feature.undeformed_angle >= min_angle;
      const double share = drawn ? kOnCornerShare : kOnCornerRounding;
      const Vec3 q = corner_at(c.feature, k);
      const NodeId n = patch_.nodes[k];
      if (distance(x(k), q) > share * shortest_edge(k)) continue;
      if (can_hold(n, q)) {
        held.nodes.push_back(n);
        held.largest_offset = std::max(held.largest_offset, distance(x(k), q));
      } else if (distance(x(k), q) <= on_corner) {
        held.held_by_role.push_back(n);  // a node of another role already on the corner
      } else {
        continue;
      }
      holds_[k] = f;
    }
  }

  /// Leaves out the corners that no node holds: the segments are those between the others.
  void keep_held_corners() {
    std::vector<HeldFeature> kept;
    corner_parameters_.clear();
    for (HeldFeature& held : plan_.features) {
      if (held.nodes.empty() && held.held_by_role.empty()) continue;
      held.from_start = true;
      corner_parameters_.push_back(held.feature.parameter);
      kept.push_back(std::move(held));
    }
    plan_.features = std::move(kept);
  }

  /// Where a corner kept edges without a node on it, say so.
  void note_unheld_corners() {
    for (HeldFeature& held : plan_.features) {
      if (held.unheld_edges == 0) continue;
      const Vec3 p = held.crease ? shape_.crease_point(*held.crease, x(0), 1.0).point
                                 : shape_.at({.t = held.feature.parameter}, 1.0, x(0)).point;
      held.note = fmt::format(
          "patch '{}': the {} at ({:.6g}, {:.6g}, {:.6g}) (turning {:.1f} degrees) has no node on {} of the wall "
          "edges that cross it: their ends hold other corners, lie on other patches, or would squash a wall cell "
          "(two corners within one cell); the wall cuts the corner there",
          patch_.name, held.crease ? "crease between two faces nearest" : "corner", p.x, p.y, p.z, held.feature.angle * 180.0 / std::numbers::pi, held.unheld_edges);
    }
  }

  /// Each node's segment: the parameter interval between the corners on either side of it; on
  /// a wall with creases, the region between them that holds its face.
  WallFeaturePlan segments(double min_angle) && {
    for (std::size_t k = 0; k < count_; ++k) {
      if (!crease_of_.empty()) plan_.segments[k].region = shape_.crease_region(faces_[k], min_angle);
      const auto after = std::upper_bound(corner_parameters_.begin(), corner_parameters_.end(), plan_.parameters[k]);
      geometry::ParameterRange& segment = plan_.segments[k];
      if (after != corner_parameters_.begin()) segment.first = *(after - 1);
      if (after != corner_parameters_.end()) segment.last = *after;
    }
    return std::move(plan_);
  }

 private:
  const Vec3& x(std::size_t k) const { return x0_[static_cast<std::size_t>(patch_.nodes[k])]; }
  /// Corner f's point in the meridional plane of node k (in 2D: the point); a crease's point
  /// nearest node k, or where the crease crosses the slip plane node k is held on.
  Vec3 corner_at(std::size_t f, std::size_t k) const {
    const HeldFeature& held = plan_.features[f];
    if (!held.crease) return shape_.at({.t = held.feature.parameter}, 0.0, x(k)).point;
    geometry::CreasePoint c = shape_.crease_point(*held.crease, x(k), 0.0);
    const std::vector<SlipPlane> planes = planes_of_(patch_.nodes[k]);
    if (planes.empty()) return c.point;
    // Along the crease's tangent onto the plane, and back onto the crease: Newton's method
    // for the crossing, exact in a few steps where the crease is smooth.
    constexpr int kSteps = 8;
    const SlipPlane& plane = planes.front();
    for (int step = 0; step < kSteps; ++step) {
      const Vec3 along = cross(c.normals[0], c.normals[1]);
      const double slope = dot(along, plane.normal);
      const double off = dot(plane.origin - c.point, plane.normal);
      if (std::abs(slope) <= 1e-3 * norm(along)) break;  // the crease runs along the plane
      c = shape_.crease_point(*held.crease, c.point + (off / slope) * along, 0.0);
    }
    return c.point;
  }
  static std::uint64_t face_pair(int a, int b) {
    return (std::uint64_t{static_cast<std::uint32_t>(std::min(a, b))} << 32) | static_cast<std::uint32_t>(std::max(a, b));
  }
  double offset(std::size_t f, std::size_t k) const { return distance(x(k), corner_at(f, k)); }
  double shortest_edge(std::size_t k) const {
    double shortest = std::numeric_limits<double>::infinity();
    for (const std::size_t j : neighbours_[k]) shortest = std::min(shortest, distance(x(k), x(j)));
    return shortest;
  }
  Vec3 position(std::size_t k) const { return holds_[k] >= 0 ? moved_[k] : x(k); }
  /// Giving node k the corner point q shrinks none of its wall edges below kMinEdgeShare.
  bool keeps_edges(std::size_t k, const Vec3& q) const {
    return std::all_of(neighbours_[k].begin(), neighbours_[k].end(), [&](std::size_t j) {
      return distance(q, position(j)) >= kMinEdgeShare * distance(x(k), position(j));
    });
  }

  const Mesh& mesh_;
  std::span<const Vec3> x0_;
  const Patch& patch_;
  const geometry::BoundaryShape& shape_;
  PlanesOf planes_of_;
  std::size_t count_;
  WallFeaturePlan plan_;
  std::vector<double> corner_parameters_;  ///< of the curve's corners, the first features
  std::unordered_map<std::uint64_t, std::size_t> crease_of_;  ///< face pair: its crease's feature
  std::vector<int> faces_;  ///< per node (index in the patch): the face it lies on
  std::vector<std::vector<std::size_t>> neighbours_;  ///< per node (index in the patch): its wall neighbours
  std::vector<Crossing> crossings_;
  std::vector<int> holds_;    ///< per node: the corner it holds, or -1
  std::vector<Vec3> moved_;   ///< per node holding a corner: where it goes at stage 0
};

}  // namespace

WallFeaturePlan plan_wall_features(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch,
                                   const geometry::BoundaryShape& shape, double min_angle, const CanHold& can_hold,
                                   const PlanesOf& planes_of, const MasterOf& master_of) {
  std::vector<geometry::ShapeFeature> corners = shape.features(min_angle);
  std::vector<geometry::ShapeCrease> lines = shape.creases(min_angle);
  if ((corners.empty() && lines.empty()) || patch.nodes.empty()) {
    return {{}, {}, std::vector<geometry::ParameterRange>(patch.nodes.size())};
  }
  CornerPlanner planner(mesh, x0, patch, shape, std::move(corners), std::move(lines), planes_of);
  planner.locate_nodes();
  planner.find_crossings();
  planner.give_corners(can_hold, master_of);
  planner.note_unheld_corners();
  return std::move(planner).segments(min_angle);
}

WallFeaturePlan plan_corners_on_nodes(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch,
                                      const geometry::BoundaryShape& shape, double min_angle, bool drawn_corners,
                                      const CanHold& can_hold) {
  std::vector<geometry::ShapeFeature> corners = shape.features(min_angle);
  if (corners.empty() || patch.nodes.empty()) return {{}, {}, std::vector<geometry::ParameterRange>(patch.nodes.size())};
  CornerPlanner planner(mesh, x0, patch, shape, std::move(corners), {}, [](NodeId) { return std::vector<SlipPlane>{}; });
  planner.locate_nodes();
  planner.find_crossings();
  planner.give_corners_to_nodes_on_them(can_hold, min_angle, drawn_corners);
  planner.keep_held_corners();
  return std::move(planner).segments(min_angle);
}

namespace {
/// How far from a corner (relative to its parameter) the wall's one-sided normals are taken.
constexpr double kOneSided = 1e-9;
}  // namespace

CornerPath::CornerPath(const geometry::BoundaryShape& wall, CornerLine line, const Vec3& start, int direction)
    : wall_(wall), line_(std::move(line)), direction_(direction) {
  const Section s = section(start, 0.0);
  for (std::size_t i = 0; i < 2; ++i) offset_[i] = dot(start - s.corner, s.axes[i]);
}

CornerPath::Section CornerPath::section(const Vec3& p, double lambda) const {
  Section s;
  Vec3 a, b;
  // The wall's normals on either side of the line span its cross-section (they differ by the
  // corner's angle); Gram-Schmidt makes them an orthonormal pair.
  if (line_.crease) {
    const geometry::CreasePoint c = wall_.crease_point(*line_.crease, p, lambda);
    s.corner = c.point;
    a = c.normals[0];
    b = c.normals[1];
  } else {
    const double corner = line_.corner;
    s.corner = wall_.at({.t = corner}, lambda, p).point;
    const double step = kOneSided * (1.0 + std::abs(corner));
    a = wall_.at({.t = corner - step}, lambda, p).normal;
    b = wall_.at({.t = corner + step}, lambda, p).normal;
  }
  s.axes[0] = a / norm(a);
  const Vec3 c = b - dot(b, s.axes[0]) * s.axes[0];
  s.axes[1] = c / norm(c);
  return s;
}

geometry::ShapePoint CornerPath::project(const Vec3& p, double lambda, const geometry::ShapeParameter& /*hint*/,
                                         const geometry::ParameterRange& /*range*/) const {
  const Section s = section(p, lambda);
  const double fade = 1.0 - lambda;
  geometry::ShapePoint q;
  q.point = s.corner + fade * (offset_[0] * s.axes[0] + offset_[1] * s.axes[1]);
  q.distance = distance(p, q.point);
  q.normal = s.axes[static_cast<std::size_t>(direction_)];
  q.parameter = {.t = line_.corner};
  return q;
}

geometry::ShapePoint CornerPath::at(const geometry::ShapeParameter& /*where*/, double lambda,
                                    const Vec3& reference) const {
  return project(reference, lambda);
}

}  // namespace hotmesh::deform::detail
