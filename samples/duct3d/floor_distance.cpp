// hotmesh sample duct3d: distances between a mesh's floor and the exact deflected floor
// (floor_distance.hpp says which).
#include "floor_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "closest_point.hpp"

namespace hotmesh::samples::duct3d {

namespace {

/// A floor face of the mesh: the bilinear patch through its corners p[0..3] (in the face's
/// cyclic order), with its bounding box.
struct Quad {
  std::array<Vec3, 4> p;
  Vec3 lo, hi;
};

Quad make_quad(const std::array<Vec3, 4>& p) {
  Quad q{p, p[0], p[0]};
  for (const Vec3& c : p) {
    q.lo = {std::min(q.lo.x, c.x), std::min(q.lo.y, c.y), std::min(q.lo.z, c.z)};
    q.hi = {std::max(q.hi.x, c.x), std::max(q.hi.y, c.y), std::max(q.hi.z, c.z)};
  }
  return q;
}

/// The bilinear patch at (a, b) in [0, 1]^2 and its derivatives.
FloorPoint bilinear(const Quad& q, double a, double b) {
  const auto& p = q.p;
  return {(1.0 - a) * (1.0 - b) * p[0] + a * (1.0 - b) * p[1] + a * b * p[2] + (1.0 - a) * b * p[3],
          (1.0 - b) * (p[1] - p[0]) + b * (p[2] - p[3]), (1.0 - a) * (p[3] - p[0]) + a * (p[2] - p[1])};
}

double quad_distance(const Quad& q, const Vec3& x, Vec3& nearest) {
  const auto evaluate = [&q](double a, double b) { return bilinear(q, a, b); };
  const Closest c = detail::closest_on_patch(evaluate, x, 0.5, 0.5, {0.0, 1.0, 0.0, 1.0});
  nearest = c.point;
  return c.distance;
}

/// A lower bound of the distance from x to anything in the box.
double box_distance(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  const double dx = std::max({lo.x - x.x, 0.0, x.x - hi.x});
  const double dy = std::max({lo.y - x.y, 0.0, x.y - hi.y});
  const double dz = std::max({lo.z - x.z, 0.0, x.z - hi.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// Keeps the larger; a WorstPoint starts at distance -1, so the first point is always kept.
void keep_worst(WorstPoint& worst, double distance, const Vec3& point, const Vec3& nearest, std::int64_t node = 0) {
  if (distance > worst.distance) worst = {distance, point, nearest, node};
}

}  // namespace

FloorDistance floor_distance(const mesh::Mesh& m, const DeflectedFloor& floor, const FloorDistanceOptions& options,
                             const mesh::Mesh* undeformed) {
  const mesh::Patch* patch = m.find_patch(options.patch);
  if (!patch) throw std::invalid_argument(fmt::format("the mesh has no patch '{}'", options.patch));
  if (undeformed && undeformed->node_count() != m.node_count()) {
    throw std::invalid_argument(fmt::format("the undeformed mesh has {} nodes, the mesh {}", undeformed->node_count(),
                                            m.node_count()));
  }
  if (patch->faces.empty()) throw std::invalid_argument(fmt::format("patch '{}' has no faces", options.patch));
  if (options.samples < 1) throw std::invalid_argument("samples must be at least 1");
  FloorDistance d;
  d.nodes = patch->nodes.size();
  d.faces = patch->faces.size();
  d.node.distance = d.mesh_to_floor.distance = d.floor_to_mesh.distance = -1.0;

  // 1. The nodes, and their parameters on X (the starts of the quads' points).
  std::vector<std::array<double, 2>> parameters(m.node_count(), {0.0, 0.0});
  for (const mesh::NodeId n : patch->nodes) {
    const Vec3& p = m.points[static_cast<std::size_t>(n)];
    const Closest c = floor.closest(p);
    parameters[static_cast<std::size_t>(n)] = {c.t, c.s};
    keep_worst(d.node, c.distance, p, c.point, m.node_id(n));
  }
  if (undeformed) {
    const DeflectedFloor cold(floor.floor(), kCold);
    d.material_point = WorstPoint{.distance = -1.0};
    for (const mesh::NodeId n : patch->nodes) {
      const Closest c0 = cold.closest(undeformed->points[static_cast<std::size_t>(n)]);
      const Vec3 target = floor.evaluate(c0.t, c0.s).x;
      const Vec3& p = m.points[static_cast<std::size_t>(n)];
      keep_worst(*d.material_point, distance(p, target), p, target, m.node_id(n));
    }
  }

  // 2. The quads' points to X, each started from the bilinear blend of its corners' parameters.
  const int k = options.samples;
  std::vector<Quad> quads;
  for (std::size_t f = 0; f < patch->faces.size(); ++f) {
    const auto nodes = patch->faces.nodes(f);
    if (patch->faces.type(f) != mesh::ElementType::quad4) {
      throw std::invalid_argument(fmt::format("patch '{}' has a face that is not a quad", options.patch));
    }
    std::array<Vec3, 4> corners;
    std::array<std::array<double, 2>, 4> starts;
    for (std::size_t c = 0; c < 4; ++c) {
      corners[c] = m.points[static_cast<std::size_t>(nodes[c])];
      starts[c] = parameters[static_cast<std::size_t>(nodes[c])];
    }
    const Quad q = make_quad(corners);
    quads.push_back(q);
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; j <= k; ++j) {
        const double a = static_cast<double>(i) / k, b = static_cast<double>(j) / k;
        const Vec3 x = bilinear(q, a, b).x;
        const auto blend = [&](std::size_t w) {
          return (1 - a) * (1 - b) * starts[0][w] + a * (1 - b) * starts[1][w] + a * b * starts[2][w] +
                 (1 - a) * b * starts[3][w];
        };
        const Closest c = floor.closest(x, blend(0), blend(1));
        keep_worst(d.mesh_to_floor, c.distance, x, c.point);
      }
    }
  }

  // 3. X's points to the nearest quad: a grid in (t, s) about k times as fine as the quads.
  const double faces = static_cast<double>(quads.size());
  const int nt = k * static_cast<int>(std::ceil(std::sqrt(faces * kLength / kWidth)));
  const int ns = k * static_cast<int>(std::ceil(std::sqrt(faces * kWidth / kLength)));
  std::vector<double> boxes(quads.size());
  for (int i = 0; i <= nt; ++i) {
    for (int j = 0; j <= ns; ++j) {
      const Vec3 x = floor.evaluate(kLength * i / nt, kWidth * j / ns).x;
      std::size_t first = 0;
      for (std::size_t q = 0; q < quads.size(); ++q) {
        boxes[q] = box_distance(x, quads[q].lo, quads[q].hi);
        if (boxes[q] < boxes[first]) first = q;
      }
      Vec3 nearest, candidate;
      double best = quad_distance(quads[first], x, nearest);
      for (std::size_t q = 0; q < quads.size(); ++q) {
        if (q == first || boxes[q] >= best) continue;
        const double dq = quad_distance(quads[q], x, candidate);
        if (dq < best) {
          best = dq;
          nearest = candidate;
        }
      }
      keep_worst(d.floor_to_mesh, best, x, nearest);
    }
  }
  return d;
}

NodesApart nodes_apart(const mesh::Mesh& a, const mesh::Mesh& b, const std::string& patch) {
  if (a.node_count() != b.node_count()) {
    throw std::invalid_argument(fmt::format("the meshes have {} and {} nodes", a.node_count(), b.node_count()));
  }
  const auto* p = a.find_patch(patch);
  if (!p) throw std::invalid_argument(fmt::format("the mesh has no patch '{}'", patch));
  NodesApart apart{.all = {.distance = -1.0}, .patch = {.distance = -1.0}};
  for (std::size_t n = 0; n < a.node_count(); ++n) {
    keep_worst(apart.all, distance(a.points[n], b.points[n]), a.points[n], b.points[n], a.node_id(static_cast<mesh::NodeId>(n)));
  }
  for (const auto n : p->nodes) {
    const auto i = static_cast<std::size_t>(n);
    keep_worst(apart.patch, distance(a.points[i], b.points[i]), a.points[i], b.points[i], a.node_id(n));
  }
  return apart;
}

std::vector<Vec3> floor_section(const DeflectedFloor& floor, int axis, double value, int n) {
  if ((axis != 0 && axis != 1) || n < 1) throw std::invalid_argument("floor_section: axis 0 (x) or 1 (y), n >= 1");
  const double along = axis == 0 ? kWidth : kLength, across = axis == 0 ? kLength : kWidth;
  const auto at = [&](double p, double other) { return axis == 0 ? floor.evaluate(p, other) : floor.evaluate(other, p); };
  std::vector<Vec3> points;
  for (int i = 0; i <= n; ++i) {
    const double other = along * i / n;
    double p = value;  // the parameter of the plane's coordinate
    for (int k = 0; k < 50; ++k) {
      const FloorPoint x = at(p, other);
      const double miss = (axis == 0 ? x.x.x : x.x.y) - value;
      if (std::abs(miss) < 1e-13 * kH) break;
      p = std::clamp(p - miss / (axis == 0 ? x.xt.x : x.xs.y), 0.0, across);
    }
    points.push_back(at(p, other).x);
  }
  return points;
}

namespace {

std::string worst_json(const WorstPoint& w, bool node) {
  const auto vec = [](const Vec3& v) { return fmt::format("[{:.9g}, {:.9g}, {:.9g}]", v.x, v.y, v.z); };
  std::string s = fmt::format("{{\"distance\": {:.6g}, \"over_h\": {:.6g}, ", w.distance, w.distance / kH);
  if (node) s += fmt::format("\"node\": {}, ", w.node);
  return s + fmt::format("\"point\": {}, \"nearest\": {}}}", vec(w.point), vec(w.nearest));
}

}  // namespace

std::string to_json(const NodesApart& apart, const std::string& patch) {
  return fmt::format("{{\"all\": {}, \"{}\": {}}}", worst_json(apart.all, true), patch, worst_json(apart.patch, true));
}

std::string to_json(const FloorDistance& d) {
  const auto worst = worst_json;
  std::string s = fmt::format("{{\n  \"unit\": \"mm\",\n  \"h\": {},\n  \"nodes\": {},\n  \"faces\": {},\n", kH, d.nodes, d.faces);
  s += fmt::format("  \"node_distance\": {},\n", worst(d.node, true));
  s += fmt::format("  \"mesh_to_floor\": {},\n", worst(d.mesh_to_floor, false));
  s += fmt::format("  \"floor_to_mesh\": {},\n", worst(d.floor_to_mesh, false));
  s += fmt::format("  \"hausdorff\": {:.6g},\n  \"hausdorff_over_h\": {:.6g}", d.hausdorff(), d.hausdorff() / kH);
  if (d.material_point) s += fmt::format(",\n  \"material_point_error\": {}", worst(*d.material_point, true));
  return s + "\n}\n";
}

}  // namespace hotmesh::samples::duct3d
