// hotmesh sample tests: how far a deformed 2D wall is from the exact deflected wall.
//
// The wall as the mesh discretises it is the set of its patch's edges (line2 faces) at the
// deformed node positions; the exact deflected wall of a sample whose FEM table is linear
// between its nodes is the polyline through the table's points Q_j + delta_j, in order along x.
// Their Hausdorff distance (both ways) is what samples/tools/wall_metrics prints for the
// results pages. Here each segment is also sampled between its ends, so a largest distance
// reached inside a segment (midway between two segments of the other line) is not missed.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "hotmesh/core/vec3.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::test {

using Segment = std::pair<geometry::Vec3, geometry::Vec3>;

inline double segment_distance(const geometry::Vec3& p, const Segment& s) {
  const geometry::Vec3 d = s.second - s.first;
  const double len2 = dot(d, d);
  const double t = len2 > 0.0 ? std::clamp(dot(p - s.first, d) / len2, 0.0, 1.0) : 0.0;
  return norm(p - (s.first + t * d));
}

/// Largest distance from a point of `from` (each segment's ends and `samples` - 1 points
/// between them) to the nearest segment of `to`.
inline double directed_distance(std::span<const Segment> from, std::span<const Segment> to, int samples = 32) {
  double worst = 0.0;
  for (const auto& s : from) {
    for (int k = 0; k <= samples; ++k) {
      const double t = static_cast<double>(k) / samples;
      const geometry::Vec3 p = s.first + t * (s.second - s.first);
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& q : to) nearest = std::min(nearest, segment_distance(p, q));
      worst = std::max(worst, nearest);
    }
  }
  return worst;
}

/// Hausdorff distance between two sets of segments.
inline double hausdorff_distance(std::span<const Segment> a, std::span<const Segment> b) {
  return std::max(directed_distance(a, b), directed_distance(b, a));
}

/// The edges of a 2D mesh's patch with its nodes at `points` (e.g. the deformed positions).
inline std::vector<Segment> wall_segments(std::span<const geometry::Vec3> points, const mesh::Patch& patch) {
  std::vector<Segment> segments;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto nodes = patch.faces.nodes(f);
    segments.emplace_back(points[static_cast<std::size_t>(nodes.front())],
                          points[static_cast<std::size_t>(nodes.back())]);
  }
  return segments;
}

/// The exact deflected wall of a 2D table linear between its nodes: the polyline through
/// Q_j + delta_j in order along x.
inline std::vector<Segment> exact_wall_segments(const std::filesystem::path& table_file) {
  const auto table = io::read_deflection_csv(table_file);
  std::vector<geometry::Vec3> deflected;
  for (std::size_t j = 0; j < table.size(); ++j) deflected.push_back(table.points[j] + table.deflections[j]);
  std::sort(deflected.begin(), deflected.end(), [](const auto& p, const auto& q) {
    return p.x < q.x || (p.x == q.x && p.y < q.y);
  });
  std::vector<Segment> segments;
  for (std::size_t j = 0; j + 1 < deflected.size(); ++j) segments.emplace_back(deflected[j], deflected[j + 1]);
  return segments;
}

}  // namespace hotmesh::test
