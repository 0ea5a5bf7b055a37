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
/// cyclic order), or for a triangle (corners == 3) the flat triangle p[0..2], with its bounding
/// box.
struct Quad {
  std::array<Vec3, 4> p;
  Vec3 lo, hi;
  int corners = 4;
};

Quad make_quad(const std::array<Vec3, 4>& p, int corners = 4) {
  Quad q{p, p[0], p[0], corners};
  for (int i = 0; i < corners; ++i) {
    const Vec3& c = p[static_cast<std::size_t>(i)];
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

/// The closest point of the triangle a, b, c to x (Ericson, Real-Time Collision Detection,
/// 5.1.5: the Voronoi regions of the vertices, the edges and the face).
Vec3 closest_on_triangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = x - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = x - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = x - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denominator = 1.0 / (va + vb + vc);
  return a + (vb * denominator) * ab + (vc * denominator) * ac;
}

double quad_distance(const Quad& q, const Vec3& x, Vec3& nearest) {
  if (q.corners == 3) {
    nearest = closest_on_triangle(x, q.p[0], q.p[1], q.p[2]);
    return distance(nearest, x);
  }
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
    const auto type = patch->faces.type(f);
    if (type != mesh::ElementType::quad4 && type != mesh::ElementType::tri3) {
      throw std::invalid_argument(fmt::format("patch '{}' has a face that is neither a quad nor a triangle", options.patch));
    }
    const std::size_t n = nodes.size();
    std::array<Vec3, 4> corners;
    std::array<std::array<double, 2>, 4> starts;
    for (std::size_t c = 0; c < n; ++c) {
      corners[c] = m.points[static_cast<std::size_t>(nodes[c])];
      starts[c] = parameters[static_cast<std::size_t>(nodes[c])];
    }
    const Quad q = make_quad(corners, static_cast<int>(n));
    quads.push_back(q);
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; j <= k; ++j) {
        const double a = static_cast<double>(i) / k, b = static_cast<double>(j) / k;
        // The point and the blend of its corners' parameters (start of the closest point):
        // bilinear weights on a quad, barycentric ones (1 - a - b, a, b) on a triangle, where
        // the (k + 1)(k + 2) / 2 points with i + j <= k are sampled.
        std::array<double, 4> w{};
        if (n == 4) {
          w = {(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b};
        } else {
          if (i + j > k) continue;
          w = {1.0 - a - b, a, b, 0.0};
        }
        Vec3 x{0.0, 0.0, 0.0};
        std::array<double, 2> start{0.0, 0.0};
        for (std::size_t c = 0; c < n; ++c) {
          x = x + w[c] * corners[c];
          start[0] += w[c] * starts[c][0];
          start[1] += w[c] * starts[c][1];
        }
        if (n == 4) x = bilinear(q, a, b).x;
        const Closest c = floor.closest(x, start[0], start[1]);
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
