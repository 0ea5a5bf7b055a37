// hotmesh geometry (internal): the CAD faces of a wall seen together, for the reconstruction
// of its deflection (face_reconstruction.cpp) and its shape (surface_shape.cpp, its creases
// surface_creases.cpp): which sides of the faces' parameter rectangles they share, which
// collapse to a point, and the groups of faces joined through shared sides.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "hotmesh/geometry/surface_shape.hpp"
#include "reconstruct/trace_joins.hpp"

namespace hotmesh::geometry::detail {

struct Box {
  Vec3 lo;
  Vec3 hi;
  bool holds(const Vec3& p, double margin) const {
    return p.x >= lo.x - margin && p.x <= hi.x + margin && p.y >= lo.y - margin && p.y <= hi.y + margin &&
           p.z >= lo.z - margin && p.z <= hi.z + margin;
  }
};

/// The box of a face's poles, which holds the face (convex hull property, positive weights).
Box pole_box(const BSplineSurface& s);


/// The point at fraction f along side 0..3 of a rectangle (v first, v last, u first, u last).
inline std::pair<double, double> on_side(const ParameterRectangle& r, int side, double f) {
  const double u = side < 2 ? r.u_first + f * (r.u_last - r.u_first) : (side == 2 ? r.u_first : r.u_last);
  const double v = side < 2 ? (side == 0 ? r.v_first : r.v_last) : r.v_first + f * (r.v_last - r.v_first);
  return {u, v};
}

/// The faces joined through the shared sides `neighbours` lists (per face and side, the face
/// sharing it or -1: a side found to lie on the other face, which may not find its own side on
/// the first, so the edges are taken both ways) and the `crossing` edges, where `joined(a, b)`
/// accepts the edge: a flood fill from each face not yet in a group, so the groups come in
/// order of their lowest face.
template <class Joined>
std::vector<std::vector<std::size_t>> face_groups(std::span<const std::array<int, 4>> neighbours, Joined joined,
                                                  std::span<const TracedEdge> crossing = {}) {
  std::vector<std::vector<std::size_t>> next(neighbours.size());
  const auto link = [&](std::size_t a, std::size_t b) {
    next[a].push_back(b);
    next[b].push_back(a);
  };
  for (std::size_t f = 0; f < neighbours.size(); ++f) {
    for (const int n : neighbours[f]) {
      if (n >= 0) link(f, static_cast<std::size_t>(n));
    }
  }
  for (const TracedEdge& e : crossing) link(e.a, e.b);
  std::vector<int> group(neighbours.size(), -1);
  std::vector<std::vector<std::size_t>> out;
  for (std::size_t start = 0; start < neighbours.size(); ++start) {
    if (group[start] >= 0) continue;
    out.emplace_back();
    std::vector<std::size_t> stack{start};
    group[start] = static_cast<int>(out.size() - 1);
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      out.back().push_back(f);
      for (const std::size_t n : next[f]) {
        if (group[n] < 0 && joined(f, n)) {
          group[n] = group[start];
          stack.push_back(n);
        }
      }
    }
  }
  return out;
}

/// The faces of a wall seen together: each on its own (undeformed) projector, their common
/// size, for each side of each face's rectangle (v first, v last, u first, u last) the face
/// it is shared with (-1: a free edge) and whether it collapses to a point, and the edges the
/// CAD file says two faces share that cross a face's rectangle (trimming curves).
struct FaceSet {
  std::vector<SurfaceProjector> projectors;
  std::vector<Box> boxes;
  double size = 0.0;
  std::vector<std::array<int, 4>> neighbours;
  std::vector<std::array<bool, 4>> collapsed;
  std::vector<TracedEdge> crossing;

  explicit FaceSet(std::span<const CadFace> faces);

  /// Groups of faces joined through shared edges.
  std::vector<std::vector<std::size_t>> groups() const {
    return face_groups(neighbours, [](std::size_t, std::size_t) { return true; }, crossing);
  }
  /// Whether a crossing edge joins faces a and b.
  bool crossed(std::size_t a, std::size_t b) const {
    return std::any_of(crossing.begin(), crossing.end(),
                       [&](const TracedEdge& e) { return (e.a == a && e.b == b) || (e.a == b && e.b == a); });
  }

 private:
  /// A side is shared when 5 points along it lie on one other face (within 1e-6 of the size),
  /// collapsed when they are one point.
  void find_edges(std::span<const CadFace> faces, std::size_t a);
};

}  // namespace hotmesh::geometry::detail
