// hotmesh geometry (internal): a discrete wall's edges in the plane of its curve and the grid
// that finds the nearest of them (wall_segments.hpp).
#include "measure/wall_segments.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hotmesh::geometry::detail {

namespace {

/// Distance from p to the segment ab, and the fraction s of its nearest point.
double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b, double& s) {
  const Vec2 d = b - a;
  const double length2 = dot(d, d);
  s = length2 > 0.0 ? std::clamp(dot(p - a, d) / length2, 0.0, 1.0) : 0.0;
  return distance(p, lerp(a, b, s));
}

}  // namespace

SegmentGrid::SegmentGrid(std::span<const Segment> segments, double cell) : segments_(segments) {
  lo_ = segments.front().a;
  Vec2 hi = lo_;
  for (const Segment& g : segments) {
    for (const Vec2& p : {g.a, g.b}) {
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
  }
  const double width = hi.x - lo_.x, height = hi.y - lo_.y;
  const double target = 2.0 * static_cast<double>(segments.size());
  cell_ = std::max({cell, std::sqrt(width * height / target), std::max(width, height) / target});
  if (!(cell_ > 0.0) || !std::isfinite(cell_)) cell_ = 1.0;  // every point the same (or not finite)
  nx_ = static_cast<std::size_t>(width / cell_) + 1;
  ny_ = static_cast<std::size_t>(height / cell_) + 1;

  // Each edge in the cells of its pieces no longer than a cell (each piece's box spans at
  // most 2 x 2 cells): linear in the edge's length, where its box could be quadratic.
  std::vector<std::pair<std::size_t, std::uint32_t>> entries;  // (cell, segment)
  std::vector<std::size_t> cells;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& g = segments[i];
    const double length = distance(g.a, g.b);
    const auto pieces = static_cast<std::size_t>(std::min(std::ceil(length / cell_), 1e7)) + 1;
    cells.clear();
    for (std::size_t k = 0; k < pieces; ++k) {
      const Vec2 p = lerp(g.a, g.b, static_cast<double>(k) / static_cast<double>(pieces));
      const Vec2 q = lerp(g.a, g.b, static_cast<double>(k + 1) / static_cast<double>(pieces));
      const auto [i0, j0] = index({std::min(p.x, q.x), std::min(p.y, q.y)});
      const auto [i1, j1] = index({std::max(p.x, q.x), std::max(p.y, q.y)});
      for (std::size_t ix = i0; ix <= i1; ++ix) {
        for (std::size_t iy = j0; iy <= j1; ++iy) cells.push_back(iy * nx_ + ix);
      }
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    for (const std::size_t c : cells) entries.emplace_back(c, static_cast<std::uint32_t>(i));
  }
  std::sort(entries.begin(), entries.end());
  start_.assign(nx_ * ny_ + 1, 0);
  for (const auto& e : entries) ++start_[e.first + 1];
  for (std::size_t c = 0; c < nx_ * ny_; ++c) start_[c + 1] += start_[c];
  items_.reserve(entries.size());
  for (const auto& e : entries) items_.push_back(e.second);
}

SegmentGrid::Nearest SegmentGrid::nearest(const Vec2& p) const {
  Nearest best;
  const auto [ci, cj] = index(p);
  const auto ring_limit = std::max({ci, nx_ - 1 - ci, cj, ny_ - 1 - cj});
  for (std::size_t k = 0; k <= ring_limit; ++k) {
    // The cells at Chebyshev distance k from (ci, cj) that lie in the grid.
    const std::size_t i0 = ci >= k ? ci - k : 0, i1 = std::min(ci + k, nx_ - 1);
    const std::size_t j0 = cj >= k ? cj - k : 0, j1 = std::min(cj + k, ny_ - 1);
    for (std::size_t j = j0; j <= j1; ++j) {
      const bool edge_row = j + k == cj || j == cj + k;
      for (std::size_t i = i0; i <= i1; ++i) {
        if (!edge_row && i + k != ci && i != ci + k) continue;  // inside the ring: done before
        visit(j * nx_ + i, p, best);
      }
    }
    // Cells of rings beyond k are at least k cells from the clamped point, which is the
    // nearest point of the grid's box to p: no edge there can be nearer than k * cell.
    if (best.distance <= static_cast<double>(k) * cell_) break;
  }
  return best;
}

std::pair<std::size_t, std::size_t> SegmentGrid::index(const Vec2& p) const {
  const auto clamp = [](double u, std::size_t n) {
    if (!(u > 0.0)) return std::size_t{0};  // NaN too
    return std::min(static_cast<std::size_t>(std::min(u, 1e18)), n - 1);
  };
  return {clamp((p.x - lo_.x) / cell_, nx_), clamp((p.y - lo_.y) / cell_, ny_)};
}

void SegmentGrid::visit(std::size_t cell, const Vec2& p, Nearest& best) const {
  for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
    const Segment& g = segments_[items_[k]];
    double s = 0.0;
    const double d = segment_distance(p, g.a, g.b, s);
    if (d < best.distance) best = {d, items_[k], s};
  }
}

/// The distinct edges of the faces (an edge shared by two faces once), in the curve's plane.
std::vector<Segment> plane_segments(std::span<const Vec3> points, const WallFaces& faces,
                                    const std::optional<Axis>& axis) {
  std::vector<std::uint64_t> keys;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto corners = faces.corners(f);
    const std::size_t n = corners.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::int32_t a = corners[k], b = corners[(k + 1) % n];
      for (const std::int32_t c : {a, b}) {
        if (c < 0 || static_cast<std::size_t>(c) >= points.size()) {
          throw std::invalid_argument("wall_deviation: a face corner is not a point of the wall");
        }
      }
      if (a == b) continue;
      keys.push_back((std::uint64_t{static_cast<std::uint32_t>(std::min(a, b))} << 32) |
                     static_cast<std::uint32_t>(std::max(a, b)));
      if (n == 2) break;  // an edge, not a polygon
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const auto plane = [&](std::int32_t n) {
    const Vec3& p = points[static_cast<std::size_t>(n)];
    if (!axis) return Vec2{p.x, p.y};
    const Cylindrical c = axis->to_cylindrical(p);
    return Vec2{c.r, c.z};
  };
  std::vector<Segment> segments;
  segments.reserve(keys.size());
  for (const std::uint64_t key : keys) {
    const auto na = static_cast<std::int32_t>(key >> 32), nb = static_cast<std::int32_t>(key & 0xffffffffu);
    segments.push_back({plane(na), plane(nb), na, nb});
  }
  return segments;
}

}  // namespace hotmesh::geometry::detail
