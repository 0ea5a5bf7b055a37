// hotmesh geometry (internal): a discrete wall's faces as pieces, their nearest points and the
// box tree over them (wall_pieces.hpp).
#include "measure/wall_pieces.hpp"

#include <cmath>
#include <stdexcept>

namespace hotmesh::geometry::detail {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// A nearest point whose parameters are this close to an edge of its piece is on that edge (the
/// nearest points of edges are clamped onto them exactly).
constexpr double kOnEdge = 1e-9;
/// Pieces per leaf of the box tree.
constexpr std::uint32_t kLeafSize = 4;

/// The nearest point of a piece to x: its squared distance and parameters.
struct Foot {
  double distance2 = kInfinity;
  double a = 0.0;
  double b = 0.0;
};

/// The fraction along ab of the point of the segment nearest to x.
double segment_fraction(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double length2 = dot(d, d);
  return length2 > 0.0 ? std::clamp(dot(x - a, d) / length2, 0.0, 1.0) : 0.0;
}

/// The nearest point of the triangle p0 p1 p2 to x, by its Voronoi regions (Ericson, Real-Time
/// Collision Detection, 5.1.5), as p0 + v (p1 - p0) + w (p2 - p0).
Foot triangle_foot(const Piece& g, const Vec3& x) {
  const Vec3 &p0 = g.p[0], &p1 = g.p[1], &p2 = g.p[2];
  const Vec3 ab = p1 - p0, ac = p2 - p0, ap = x - p0;
  const auto foot = [&](double v, double w) {
    const Vec3 r = piece_point(g, v, w) - x;
    return Foot{dot(r, r), v, w};
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return foot(0.0, 0.0);
  const Vec3 bp = x - p1;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return foot(1.0, 0.0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return foot(d1 / (d1 - d3), 0.0);
  const Vec3 cp = x - p2;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return foot(0.0, 1.0);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return foot(0.0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return foot(1.0 - w, w);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // a degenerate triangle (a segment or a point): the nearest of its edges
    Foot best;
    const double s01 = segment_fraction(x, p0, p1), s02 = segment_fraction(x, p0, p2), s12 = segment_fraction(x, p1, p2);
    for (const Foot& f : {foot(s01, 0.0), foot(0.0, s02), foot(1.0 - s12, s12)}) {
      if (f.distance2 < best.distance2) best = f;
    }
    return best;
  }
  return foot(vb / sum, vc / sum);
}

/// The nearest point of the bilinear quad to x: the nearest of its four edges' (its boundary)
/// and of the interior minimum Newton finds from the middle (full Hessian of |B - x|^2, whose
/// only second derivative is the twist B_ab; Gauss-Newton where that is not positive definite;
/// each step clamped into [0, 1]^2). Every candidate is a point of the quad, so the result is its
/// distance wherever Newton reaches the interior minimum, as it does from the middle of the
/// nearly flat faces of a mesh.
Foot quad_foot(const Piece& g, const Vec3& x) {
  const auto& p = g.p;
  const auto foot = [&](double a, double b) {
    const Vec3 r = piece_point(g, a, b) - x;
    return Foot{dot(r, r), a, b};
  };
  Foot best;
  const std::array<Foot, 4> edges{foot(segment_fraction(x, p[0], p[1]), 0.0), foot(1.0, segment_fraction(x, p[1], p[2])),
                                  foot(1.0 - segment_fraction(x, p[2], p[3]), 1.0),
                                  foot(0.0, 1.0 - segment_fraction(x, p[3], p[0]))};
  for (const Foot& f : edges) {
    if (f.distance2 < best.distance2) best = f;
  }
  const Vec3 twist = p[0] - p[1] + p[2] - p[3];
  double a = 0.5, b = 0.5;
  for (int k = 0; k < 20; ++k) {
    const Vec3 r = piece_point(g, a, b) - x;
    const Vec3 ba = (1.0 - b) * (p[1] - p[0]) + b * (p[2] - p[3]);
    const Vec3 bb = (1.0 - a) * (p[3] - p[0]) + a * (p[2] - p[1]);
    const double ga = dot(r, ba), gb = dot(r, bb);
    const double haa = dot(ba, ba), hbb = dot(bb, bb);
    double hab = dot(ba, bb) + dot(r, twist);
    double det = haa * hbb - hab * hab;
    if (!(det > 1e-14 * haa * hbb)) {
      hab = dot(ba, bb);
      det = haa * hbb - hab * hab;
      if (!(det > 1e-14 * haa * hbb)) break;  // a degenerate quad: its edges
    }
    const double na = std::clamp(a - (hbb * ga - hab * gb) / det, 0.0, 1.0);
    const double nb = std::clamp(b - (haa * gb - hab * ga) / det, 0.0, 1.0);
    const double step = std::abs(na - a) + std::abs(nb - b);
    a = na;
    b = nb;
    if (step < 1e-14) break;
  }
  const Foot inside = foot(a, b);
  if (inside.distance2 < best.distance2) best = inside;
  return best;
}

Foot piece_foot(const Piece& g, const Vec3& x) { return g.corners == 3 ? triangle_foot(g, x) : quad_foot(g, x); }

}  // namespace

std::vector<Piece> wall_pieces(std::span<const Vec3> points, const WallFaces& faces) {
  // Every polygon edge (a, b), a < b, to count the faces sharing it: the rim's edges have one.
  std::vector<std::uint64_t> keys;
  const auto key = [](std::int32_t a, std::int32_t b) {
    return (std::uint64_t{static_cast<std::uint32_t>(std::min(a, b))} << 32) |
           static_cast<std::uint32_t>(std::max(a, b));
  };
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto corners = faces.corners(f);
    if (corners.size() < 3) {
      throw std::invalid_argument("wall_deviation: a face of a wall on faces needs 3 or more corners");
    }
    for (const std::int32_t c : corners) {
      if (c < 0 || static_cast<std::size_t>(c) >= points.size()) {
        throw std::invalid_argument("wall_deviation: a face corner is not a point of the wall");
      }
    }
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const std::int32_t a = corners[k], b = corners[(k + 1) % corners.size()];
      keys.push_back(key(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());
  const auto rim = [&](std::int32_t a, std::int32_t b) {
    const auto [lo, hi] = std::equal_range(keys.begin(), keys.end(), key(a, b));
    return hi - lo == 1;  // a fan's diagonal, in no face's list, is inside
  };
  std::vector<std::uint8_t> rim_node(points.size(), 0);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto corners = faces.corners(f);
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const std::int32_t a = corners[k], b = corners[(k + 1) % corners.size()];
      if (rim(a, b)) rim_node[static_cast<std::size_t>(a)] = rim_node[static_cast<std::size_t>(b)] = 1;
    }
  }
  // The pieces: a triangle or quad as it is, a polygon of more corners as a fan from corner 0.
  std::vector<Piece> pieces;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto corners = faces.corners(f);
    const std::size_t m = corners.size();
    const auto add = [&](std::array<std::int32_t, 4> nodes, int count) {
      Piece g;
      g.corners = count;
      g.face = static_cast<std::int32_t>(f);
      for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) {
        const auto n = static_cast<std::size_t>(nodes[k]);
        g.p[k] = points[n];
        g.rim_corner[k] = rim_node[n] != 0;
        g.rim_edge[k] = rim(nodes[k], nodes[(k + 1) % static_cast<std::size_t>(count)]);
        g.box.add(g.p[k]);
      }
      pieces.push_back(g);
    };
    if (m == 3) add({corners[0], corners[1], corners[2], 0}, 3);
    if (m == 4) add({corners[0], corners[1], corners[2], corners[3]}, 4);
    for (std::size_t k = 1; m > 4 && k + 1 < m; ++k) add({corners[0], corners[k], corners[k + 1], 0}, 3);
  }
  return pieces;
}

bool on_rim(const Piece& g, double a, double b) {
  const std::array<bool, 4> on = g.corners == 3
                                     ? std::array<bool, 4>{b <= kOnEdge, a + b >= 1.0 - kOnEdge, a <= kOnEdge, false}
                                     : std::array<bool, 4>{b <= kOnEdge, a >= 1.0 - kOnEdge, b >= 1.0 - kOnEdge, a <= kOnEdge};
  const int m = g.corners;
  for (int k = 0; k < m; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (on[i] && g.rim_edge[i]) return true;
    // Corner k is where edges k - 1 and k meet.
    if (on[i] && on[static_cast<std::size_t>((k + m - 1) % m)] && g.rim_corner[i]) return true;
  }
  return false;
}

PieceTree::PieceTree(const std::vector<Piece>& pieces) : pieces_(pieces) {
  order_.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) order_.push_back(static_cast<std::uint32_t>(i));
  nodes_.reserve(4 * (pieces.size() / kLeafSize + 1));
  nodes_.emplace_back();
  build(0, 0, static_cast<std::uint32_t>(pieces.size()));
}

PieceTree::Nearest PieceTree::nearest(const Vec3& x, std::uint32_t start) const {
  Nearest best;
  double best2 = kInfinity;
  const auto visit = [&](std::uint32_t i) {
    const Piece& g = pieces_[i];
    if (g.box.distance2(x) >= best2) return;
    const Foot f = piece_foot(g, x);
    if (f.distance2 < best2) {
      best2 = f.distance2;
      best = {0.0, i, f.a, f.b};
    }
  };
  if (start < pieces_.size()) visit(start);
  std::array<std::uint32_t, 128> stack{};
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.box.distance2(x) >= best2) continue;
    if (node.count > 0) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) visit(order_[k]);
      continue;
    }
    const std::uint32_t near = node.first, far = node.first + 1;
    const double dn = nodes_[near].box.distance2(x), df = nodes_[far].box.distance2(x);
    const bool swap = df < dn;
    if (top + 2 > stack.size()) throw std::logic_error("PieceTree: too deep");
    stack[top++] = swap ? near : far;  // the farther first, so that the nearer is visited next
    stack[top++] = swap ? far : near;
  }
  best.distance = std::sqrt(best2);
  return best;
}

void PieceTree::build(std::uint32_t index, std::uint32_t first, std::uint32_t count) {
  WallBox box, centres;
  for (std::uint32_t k = first; k < first + count; ++k) {
    const WallBox& b = pieces_[order_[k]].box;
    box.add(b);
    centres.add(0.5 * (b.lo + b.hi));
  }
  nodes_[index].box = box;
  if (count <= kLeafSize) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return;
  }
  const Vec3 extent = centres.hi - centres.lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t half = count / 2;
  const auto centre = [&](std::uint32_t i) { return pieces_[i].box.lo[axis] + pieces_[i].box.hi[axis]; };
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](std::uint32_t i, std::uint32_t j) { return centre(i) < centre(j); });
  const auto children = static_cast<std::uint32_t>(nodes_.size());
  nodes_.resize(nodes_.size() + 2);
  nodes_[index].first = children;
  nodes_[index].count = 0;
  build(children, first, half);
  build(children + 1, first + half, count - half);
}

}  // namespace hotmesh::geometry::detail
