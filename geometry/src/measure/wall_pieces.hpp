// hotmesh geometry (internal): a discrete wall's faces as pieces, for the measure against CAD
// faces (surface_wall_deviation.cpp): triangles and bilinear quads (a polygon of more corners: a
// fan of triangles) that know which of their edges and corners lie on the wall's rim, and a box
// tree over them that finds the nearest piece to a point.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "hotmesh/geometry/wall_deviation.hpp"

namespace hotmesh::geometry::detail {

/// A box around points of the wall (empty at first).
struct WallBox {
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  Vec3 lo{kInfinity, kInfinity, kInfinity};
  Vec3 hi{-kInfinity, -kInfinity, -kInfinity};
  void add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(const WallBox& b) {
    add(b.lo);
    add(b.hi);
  }
  /// The squared distance from p to the box (0 inside).
  double distance2(const Vec3& p) const {
    const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
    const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
    const double dz = std::max({lo.z - p.z, 0.0, p.z - hi.z});
    return dx * dx + dy * dy + dz * dz;
  }
};

/// A piece of the wall: a triangle, parameters (a, b) with a, b >= 0, a + b <= 1 at
/// p0 + a (p1 - p0) + b (p2 - p0), or a quad, the bilinear patch
/// (1 - a)(1 - b) p0 + a (1 - b) p1 + a b p2 + (1 - a) b p3 over [0, 1]^2. Edge k joins corner k
/// to corner k + 1 (cyclically).
struct Piece {
  std::array<Vec3, 4> p{};
  int corners = 3;
  std::int32_t face = 0;             ///< the wall face it belongs to
  std::array<bool, 4> rim_edge{};    ///< edge k lies on the wall's rim (an edge of one face only)
  std::array<bool, 4> rim_corner{};  ///< corner k is a node of the rim
  WallBox box;
};

inline Vec3 piece_point(const Piece& g, double a, double b) {
  if (g.corners == 3) return g.p[0] + a * (g.p[1] - g.p[0]) + b * (g.p[2] - g.p[0]);
  return (1.0 - a) * (1.0 - b) * g.p[0] + a * (1.0 - b) * g.p[1] + a * b * g.p[2] + (1.0 - a) * b * g.p[3];
}

/// (a, b) put into the piece's parameter domain.
inline std::pair<double, double> clamp_to(const Piece& g, double a, double b) {
  a = std::clamp(a, 0.0, 1.0);
  b = std::clamp(b, 0.0, 1.0);
  if (g.corners == 3 && a + b > 1.0) {
    const double sum = a + b;
    a /= sum;
    b /= sum;
  }
  return {a, b};
}

/// The wall's faces as pieces: a triangle or quad as it is, a polygon of more corners as a fan
/// from corner 0; each piece's rim edges (an edge of one face only) and rim corners. Throws
/// std::invalid_argument for a face of fewer than 3 corners or a corner outside `points`.
std::vector<Piece> wall_pieces(std::span<const Vec3> points, const WallFaces& faces);

/// Whether the point (a, b) of a piece lies on the wall's rim: on an edge of the piece that is a
/// rim edge, or at a corner that is a rim node.
bool on_rim(const Piece& g, double a, double b);

/// A box tree over the pieces (median splits along the longest axis of their centres): the
/// nearest piece to a point, visiting the nearer child first and skipping boxes farther than the
/// nearest piece found.
class PieceTree {
 public:
  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    std::uint32_t piece = 0;
    double a = 0.0;
    double b = 0.0;
  };

  explicit PieceTree(const std::vector<Piece>& pieces);

  /// The nearest piece to x; `start`, a piece likely near (the previous query's), gives the first
  /// bound.
  Nearest nearest(const Vec3& x, std::uint32_t start) const;

 private:
  /// count > 0: a leaf of order_[first, first + count); else children at first and first + 1.
  struct Node {
    WallBox box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
  };

  /// Fills node `index` (already in nodes_) with order_[first, first + count), its two
  /// children appended next to each other.
  void build(std::uint32_t index, std::uint32_t first, std::uint32_t count);

  const std::vector<Piece>& pieces_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace hotmesh::geometry::detail
