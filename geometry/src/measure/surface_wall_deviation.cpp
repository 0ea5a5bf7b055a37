// hotmesh geometry: the two-sided distance between a discrete wall and a wall on CAD faces (see
// the second part of wall_deviation.hpp): the wall's faces sampled and projected onto the stage
// of the faces; the faces sampled over the part the wall covers, each sample's nearest wall face
// found in a box tree and samples beyond the wall's rim left out; the local maxima of both
// refined by a pattern search.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "hotmesh/geometry/surface_shape.hpp"
#include "hotmesh/geometry/wall_deviation.hpp"

namespace hotmesh::geometry {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Distances below this, relative to the wall's size, are round-off (as for curves).
constexpr double kRoundOff = 1e-9;
/// A nearest point whose parameters are this close to an edge of its piece is on that edge (the
/// nearest points of edges are clamped onto them exactly).
constexpr double kOnEdge = 1e-9;
/// The pattern search starts at half the sample spacing and stops below this fraction of it.
constexpr double kSearchEnd = 1e-4;
constexpr int kMaxSearchEvaluations = 400;
/// At most this many samples per direction, and in all, of one CAD face.
constexpr double kMaxLineSamples = 16384.0;
constexpr double kMaxFaceSamples = 16777216.0;
/// Pieces per leaf of the box tree.
constexpr std::uint32_t kLeafSize = 4;

struct Box {
  Vec3 lo{kInfinity, kInfinity, kInfinity};
  Vec3 hi{-kInfinity, -kInfinity, -kInfinity};
  void add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(const Box& b) {
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
  Box box;
};

Vec3 piece_point(const Piece& g, double a, double b) {
  if (g.corners == 3) return g.p[0] + a * (g.p[1] - g.p[0]) + b * (g.p[2] - g.p[0]);
  return (1.0 - a) * (1.0 - b) * g.p[0] + a * (1.0 - b) * g.p[1] + a * b * g.p[2] + (1.0 - a) * b * g.p[3];
}

/// (a, b) put into the piece's parameter domain.
std::pair<double, double> clamp_to(const Piece& g, double a, double b) {
  a = std::clamp(a, 0.0, 1.0);
  b = std::clamp(b, 0.0, 1.0);
  if (g.corners == 3 && a + b > 1.0) {
    const double sum = a + b;
    a /= sum;
    b /= sum;
  }
  return {a, b};
}

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

/// Whether the point (a, b) of a piece lies on the wall's rim: on an edge of the piece that is a
/// rim edge, or at a corner that is a rim node.
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

/// A box tree over the pieces (median splits along the longest axis of their centres): the
/// nearest piece to a point, visiting the nearer child first and skipping boxes farther than the
/// nearest piece found.
class PieceTree {
 public:
  struct Nearest {
    double distance = kInfinity;
    std::uint32_t piece = 0;
    double a = 0.0;
    double b = 0.0;
  };

  explicit PieceTree(const std::vector<Piece>& pieces) : pieces_(pieces) {
    order_.reserve(pieces.size());
    for (std::size_t i = 0; i < pieces.size(); ++i) order_.push_back(static_cast<std::uint32_t>(i));
    nodes_.reserve(4 * (pieces.size() / kLeafSize + 1));
    nodes_.emplace_back();
    build(0, 0, static_cast<std::uint32_t>(pieces.size()));
  }

  /// The nearest piece to x; `start`, a piece likely near (the previous query's), gives the first
  /// bound.
  Nearest nearest(const Vec3& x, std::uint32_t start) const {
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

 private:
  /// count > 0: a leaf of order_[first, first + count); else children at first and first + 1.
  struct Node {
    Box box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
  };

  /// Fills node `index` (already in nodes_) with order_[first, first + count), its two
  /// children appended next to each other.
  void build(std::uint32_t index, std::uint32_t first, std::uint32_t count) {
    Box box, centres;
    for (std::uint32_t k = first; k < first + count; ++k) {
      const Box& b = pieces_[order_[k]].box;
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

  const std::vector<Piece>& pieces_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

/// The local maximum of f near (a, b), where f has `value`, by pattern search: the 8 points
/// (a + i h step_a, b + j h step_b), i, j in {-1, 0, 1}, put into the domain by `clamp`; move to
/// the best if it is higher, else halve h; h from 1/2 down to kSearchEnd. Returns the maximum
/// found and moves (a, b) there.
template <class F, class Clamp>
double climb(F&& f, Clamp&& clamp, double& a, double& b, double value, double step_a, double step_b) {
  constexpr std::array<std::array<int, 2>, 8> kDirections{
      {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};
  double h = 0.5;
  int evaluations = 0;
  while (h >= kSearchEnd && evaluations < kMaxSearchEvaluations) {
    double best = value, best_a = a, best_b = b;
    for (const auto& [i, j] : kDirections) {
      const auto [ca, cb] = clamp(a + i * h * step_a, b + j * h * step_b);
      const double fc = f(ca, cb);
      ++evaluations;
      if (fc > best) {
        best = fc;
        best_a = ca;
        best_b = cb;
      }
    }
    if (best > value) {
      value = best;
      a = best_a;
      b = best_b;
    } else {
      h *= 0.5;
    }
  }
  return value;
}

/// A sample that may hide a higher maximum between it and its neighbours.
struct Candidate {
  /// Its value plus half the largest difference to a neighbour: how much higher a tent (a kink)
  /// between the samples can rise at most, twice what a parabola can.
  double bound;
  double value;
  std::size_t index;  ///< the piece, or the CAD face
  double a, b;        ///< its parameters
  double step_a, step_b;  ///< the sample spacing in them
  ShapeParameter hint;    ///< where its projection landed (wall side)
};

/// The largest |value - grid[neighbour]| over the 8 neighbours (i + di, j + dj) of a grid of
/// columns x rows that `valid` accepts.
template <class Valid>
double spread(const std::vector<double>& grid, std::size_t columns, std::size_t rows, std::size_t i, std::size_t j,
              Valid&& valid) {
  const double value = grid[i * rows + j];
  double largest = 0.0;
  for (int di = -1; di <= 1; ++di) {
    for (int dj = -1; dj <= 1; ++dj) {
      if ((di == 0 && dj == 0) || (di < 0 && i == 0) || (dj < 0 && j == 0)) continue;
      const std::size_t ni = i + static_cast<std::size_t>(di), nj = j + static_cast<std::size_t>(dj);
      if (ni >= columns || nj >= rows || !valid(ni, nj)) continue;
      largest = std::max(largest, std::abs(value - grid[ni * rows + nj]));
    }
  }
  return largest;
}

class SurfaceMeasure {
 public:
  SurfaceMeasure(const SurfaceShape& shape, std::span<const Vec3> points, const WallFaces& faces,
                 const SurfaceWallOptions& options)
      : shape_(shape), options_(options) {
    // Every polygon edge (a, b), a < b, to count the faces sharing it: the rim's edges have one.
    std::vector<std::uint64_t> keys;
    const auto key = [](std::int32_t a, std::int32_t b) {
      return (std::uint64_t{static_cast<std::uint32_t>(std::min(a, b))} << 32) |
             static_cast<std::uint32_t>(std::max(a, b));
    };
    std::vector<double> lengths;
    Box all;
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
        lengths.push_back(distance(points[static_cast<std::size_t>(a)], points[static_cast<std::size_t>(b)]));
        all.add(points[static_cast<std::size_t>(a)]);
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
        pieces_.push_back(g);
      };
      if (m == 3) add({corners[0], corners[1], corners[2], 0}, 3);
      if (m == 4) add({corners[0], corners[1], corners[2], corners[3]}, 4);
      for (std::size_t k = 1; m > 4 && k + 1 < m; ++k) add({corners[0], corners[k], corners[k + 1], 0}, 3);
    }
    round_off_ = kRoundOff * (pieces_.empty() ? 1.0 : distance(all.lo, all.hi));
    lengths.erase(std::remove_if(lengths.begin(), lengths.end(), [&](double l) { return !(l > round_off_); }),
                  lengths.end());
    if (!lengths.empty()) {
      std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
      median_edge_ = lengths[lengths.size() / 2];
    }
    for (std::size_t f = 0; f < shape.face_count(); ++f) {
      covered_.push_back({kInfinity, -kInfinity, kInfinity, -kInfinity});
    }
  }

  bool empty() const { return pieces_.empty(); }

  /// mesh_to_shape, and the part of each CAD face the wall's samples project onto.
  void wall_to_shape(WallDeviation& result) {
    const int n = options_.face_samples;
    const auto side = static_cast<std::size_t>(n) + 1;
    const double h = 1.0 / n;
    const double lambda = options_.lambda;
    WallDeviationPoint& worst = result.mesh_to_shape;
    double best = -1.0;
    bool not_finite = false;
    ShapeParameter hint = kNoHint;
    std::vector<double> grid(side * side);
    std::vector<ShapeParameter> where(side * side);
    std::vector<Candidate> candidates;
    for (std::size_t k = 0; k < pieces_.size(); ++k) {
      const Piece& g = pieces_[k];
      const auto valid = [&](std::size_t i, std::size_t j) { return g.corners == 4 || i + j <= side - 1; };
      std::size_t top = 0;  // the piece's highest sample
      double top_value = -kInfinity;
      for (std::size_t i = 0; i < side; ++i) {
        for (std::size_t j = 0; j < side && valid(i, j); ++j) {
          const double a = static_cast<double>(i) * h, b = static_cast<double>(j) * h;
          const ShapePoint q = shape_.project(piece_point(g, a, b), lambda, hint);
          hint = q.parameter;
          grid[i * side + j] = q.distance;
          where[i * side + j] = q.parameter;
          if (std::isnan(q.distance)) not_finite = true;
          cover(q.parameter);
          if (q.distance > top_value) {
            top_value = q.distance;
            top = i * side + j;
          }
          if (q.distance > best) {
            best = q.distance;
            set_wall_point(worst, k, a, b, q);
          }
        }
      }
      const std::size_t ti = top / side, tj = top % side;
      const double value = grid[top];
      const double bound = value + 0.5 * spread(grid, side, side, ti, tj, valid);
      if (bound > best + round_off_) {
        candidates.push_back({bound, value, k, static_cast<double>(ti) * h, static_cast<double>(tj) * h, h, h, where[top]});
      }
    }
    refine(candidates, best, [&](const Candidate& c) {
      const Piece& g = pieces_[c.index];
      ShapeParameter near = c.hint;
      const auto f = [&](double a, double b) {
        const ShapePoint q = shape_.project(piece_point(g, a, b), lambda, near);
        near = q.parameter;
        return q.distance;
      };
      double a = c.a, b = c.b;
      const double value = climb(f, [&](double u, double v) { return clamp_to(g, u, v); }, a, b, c.value, c.step_a, c.step_b);
      if (value > best) {
        best = value;
        set_wall_point(worst, c.index, a, b, shape_.project(piece_point(g, a, b), lambda, near));
      }
    });
    worst.distance = not_finite ? std::numeric_limits<double>::quiet_NaN() : std::max(best, 0.0);
  }

  /// shape_to_mesh over the part of each CAD face that wall_to_shape found covered.
  void shape_to_wall(WallDeviation& result) {
    const PieceTree tree(pieces_);
    const double lambda = options_.lambda;
    const double spacing = median_edge_ > 0.0 ? options_.shape_spacing * median_edge_ : kInfinity;
    WallDeviationPoint& worst = result.shape_to_mesh;
    double best = -1.0;
    bool not_finite = false;
    std::uint32_t near = 0;
    std::vector<Candidate> candidates;
    std::vector<double> grid;
    for (std::size_t face = 0; face < covered_.size(); ++face) {
      const ParameterRectangle r = covered_[face];
      if (!(r.u_first <= r.u_last) || !(r.v_first <= r.v_last)) continue;  // no sample of the wall on it
      const auto at = [&](double t, double s) {
        return shape_.at({t, s, static_cast<int>(face)}, lambda, {}).point;
      };
      // Samples per direction: the face's longest line across r in that direction over the spacing.
      const auto line_length = [&](bool along_t) {
        double longest = 0.0;
        for (int line = 0; line < 5; ++line) {
          double length = 0.0;
          const double other = along_t ? r.v_first + (r.v_last - r.v_first) * (line + 0.5) / 5.0
                                       : r.u_first + (r.u_last - r.u_first) * (line + 0.5) / 5.0;
          Vec3 previous;
          for (int k = 0; k <= 8; ++k) {
            const double p = along_t ? r.u_first + (r.u_last - r.u_first) * k / 8.0
                                     : r.v_first + (r.v_last - r.v_first) * k / 8.0;
            const Vec3 x = along_t ? at(p, other) : at(other, p);
            if (k > 0) length += distance(previous, x);
            previous = x;
          }
          longest = std::max(longest, length);
        }
        return longest;
      };
      const auto count = [&](double length, double range) {
        if (!(range > 0.0)) return 0.0;
        const double c = std::ceil(length / spacing);
        return std::isfinite(c) ? std::clamp(c, 1.0, kMaxLineSamples) : 1.0;
      };
      double nt = count(line_length(true), r.u_last - r.u_first);
      double ns = count(line_length(false), r.v_last - r.v_first);
      if ((nt + 1.0) * (ns + 1.0) > kMaxFaceSamples) {
        const double scale = std::sqrt(kMaxFaceSamples / ((nt + 1.0) * (ns + 1.0)));
        nt = std::floor(nt * scale);
        ns = std::floor(ns * scale);
      }
      const auto columns = static_cast<std::size_t>(nt) + 1, rows = static_cast<std::size_t>(ns) + 1;
      const double dt = nt > 0.0 ? (r.u_last - r.u_first) / nt : 0.0;
      const double ds = ns > 0.0 ? (r.v_last - r.v_first) / ns : 0.0;
      const auto parameter = [](double first, double last, double step, std::size_t k, std::size_t n) {
        return k + 1 == n ? last : first + static_cast<double>(k) * step;
      };
      grid.assign(columns * rows, -kInfinity);
      for (std::size_t i = 0; i < columns; ++i) {
        for (std::size_t j = 0; j < rows; ++j) {
          const double t = parameter(r.u_first, r.u_last, dt, i, columns);
          const double s = parameter(r.v_first, r.v_last, ds, j, rows);
          ++result.shape_samples;
          if (!shape_.holds(face, t, s)) {  // not on the face: beyond its trimming loops
            ++result.uncovered_samples;
            continue;
          }
          const Vec3 x = at(t, s);
          const PieceTree::Nearest w = tree.nearest(x, near);
          near = w.piece;
          if (on_rim(pieces_[w.piece], w.a, w.b)) {
            ++result.uncovered_samples;
            continue;
          }
          grid[i * rows + j] = w.distance;
          if (std::isnan(w.distance) || !is_finite(x)) not_finite = true;
          if (w.distance > best) {
            best = w.distance;
            set_shape_point(worst, face, t, s, x, w);
          }
        }
      }
      const auto covered = [&](std::size_t i, std::size_t j) { return grid[i * rows + j] > -kInfinity; };
      for (std::size_t i = 0; i < columns; ++i) {
        for (std::size_t j = 0; j < rows; ++j) {
          if (!covered(i, j)) continue;
          const double value = grid[i * rows + j];
          // A local maximum: no covered neighbour higher.
          bool peak = true;
          for (int di = -1; di <= 1 && peak; ++di) {
            for (int dj = -1; dj <= 1 && peak; ++dj) {
              if ((di < 0 && i == 0) || (dj < 0 && j == 0)) continue;
              const std::size_t ni = i + static_cast<std::size_t>(di), nj = j + static_cast<std::size_t>(dj);
              if (ni < columns && nj < rows && covered(ni, nj) && grid[ni * rows + nj] > value) peak = false;
            }
          }
          if (!peak) continue;
          const double bound = value + 0.5 * spread(grid, columns, rows, i, j, covered);
          if (bound > best + round_off_) {
            candidates.push_back({bound, value, face, parameter(r.u_first, r.u_last, dt, i, columns),
                                  parameter(r.v_first, r.v_last, ds, j, rows), dt, ds, kNoHint});
          }
        }
      }
    }
    refine(candidates, best, [&](const Candidate& c) {
      const ParameterRectangle r = covered_[c.index];
      const auto clamp = [&](double t, double s) {
        return std::pair{std::clamp(t, r.u_first, r.u_last), std::clamp(s, r.v_first, r.v_last)};
      };
      const auto f = [&](double t, double s) {
        if (!shape_.holds(c.index, t, s)) return -kInfinity;
        const PieceTree::Nearest w = tree.nearest(shape_.at({t, s, static_cast<int>(c.index)}, lambda, {}).point, near);
        near = w.piece;
        return on_rim(pieces_[w.piece], w.a, w.b) ? -kInfinity : w.distance;
      };
      double t = c.a, s = c.b;
      const double value = climb(f, clamp, t, s, c.value, c.step_a, c.step_b);
      if (value > best) {
        best = value;
        const Vec3 x = shape_.at({t, s, static_cast<int>(c.index)}, lambda, {}).point;
        set_shape_point(worst, c.index, t, s, x, tree.nearest(x, near));
      }
    });
    worst.distance = not_finite ? std::numeric_limits<double>::quiet_NaN() : std::max(best, 0.0);
  }

 private:
  /// The part of its CAD face a projection lands on (beyond a free edge: on the edge).
  void cover(const ShapeParameter& p) {
    if (p.face < 0 || static_cast<std::size_t>(p.face) >= covered_.size() || !(p.t == p.t) || !(p.s == p.s)) return;
    const ParameterRectangle domain = shape_.face(static_cast<std::size_t>(p.face)).surface.domain();
    const double t = std::clamp(p.t, domain.u_first, domain.u_last);
    const double s = std::clamp(p.s, domain.v_first, domain.v_last);
    ParameterRectangle& r = covered_[static_cast<std::size_t>(p.face)];
    r = {std::min(r.u_first, t), std::max(r.u_last, t), std::min(r.v_first, s), std::max(r.v_last, s)};
  }

  /// Refines the candidates from the highest bound down while a bound beats the best found
  /// (`best`, which `one` raises).
  template <class Refine>
  void refine(std::vector<Candidate>& candidates, const double& best, Refine&& one) const {
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.bound > b.bound; });
    for (const Candidate& c : candidates) {
      if (!(c.bound > best + round_off_)) break;  // nor any after it
      one(c);
    }
  }

  void set_wall_point(WallDeviationPoint& w, std::size_t piece, double a, double b, const ShapePoint& q) const {
    w.distance = q.distance;
    w.point = piece_point(pieces_[piece], a, b);
    w.nearest = q.point;
    w.parameter = q.parameter.t;
    w.parameter_s = q.parameter.s;
    w.shape_face = q.parameter.face;
    w.edge = {-1, -1};
    w.face = pieces_[piece].face;
  }

  void set_shape_point(WallDeviationPoint& w, std::size_t face, double t, double s, const Vec3& x,
                       const PieceTree::Nearest& n) const {
    w.distance = n.distance;
    w.point = x;
    w.nearest = piece_point(pieces_[n.piece], n.a, n.b);
    w.parameter = t;
    w.parameter_s = s;
    w.shape_face = static_cast<int>(face);
    w.edge = {-1, -1};
    w.face = pieces_[n.piece].face;
  }

  const SurfaceShape& shape_;
  const SurfaceWallOptions& options_;
  std::vector<Piece> pieces_;
  std::vector<ParameterRectangle> covered_;  ///< per CAD face; empty (first > last): not covered
  double round_off_ = 0.0;
  double median_edge_ = 0.0;
};

}  // namespace

WallDeviation wall_deviation(const SurfaceShape& shape, std::span<const Vec3> points, const WallFaces& faces,
                             const SurfaceWallOptions& options) {
  if (options.face_samples < 1 || options.face_samples > 1000) {
    throw std::invalid_argument("wall_deviation: face_samples must be 1 to 1000");
  }
  if (!(options.shape_spacing > 0.0) || !std::isfinite(options.shape_spacing) || !std::isfinite(options.lambda)) {
    throw std::invalid_argument("wall_deviation: shape_spacing must be positive and lambda finite");
  }
  WallDeviation result;
  SurfaceMeasure measure(shape, points, faces, options);
  result.faces = faces.size();
  if (measure.empty()) return result;
  measure.wall_to_shape(result);
  measure.shape_to_wall(result);
  result.take_worst_direction();
  return result;
}

}  // namespace hotmesh::geometry
