// hotmesh geometry: the two-sided distance between a discrete wall and its curve (see
// wall_deviation.hpp): the wall's edges taken into the curve's plane, sampled and projected on
// the curve; the curve sampled over the part the wall covers, each sample's nearest edge found
// through a uniform grid; local maxima of both refined by golden-section search.
#include "hotmesh/geometry/wall_deviation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hotmesh::geometry {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Distances below this, relative to the curve's length scale, are round-off: a local maximum
/// of samples this close to the other side is not refined.
constexpr double kRoundOff = 1e-9;
/// Golden-section steps of a refinement: the bracket of two sample spacings shrinks by
/// 0.618^30 ~ 5e-7, so a smooth maximum is found to ~1e-13 of its bracket and a corner's (a
/// kink, slope at most 1) to 5e-7 of it.
constexpr int kGoldenSteps = 30;
/// At most this many curve samples per piece of the curve.
constexpr std::size_t kMaxPieceSamples = std::size_t{1} << 20;

/// A wall edge in the curve's plane, with the indices of its end points.
struct Segment {
  Vec2 a;
  Vec2 b;
  std::int32_t na = 0;
  std::int32_t nb = 0;
};

Vec2 lerp(const Vec2& a, const Vec2& b, double s) { return a + s * (b - a); }
Vec3 lerp(const Vec3& a, const Vec3& b, double s) { return a + s * (b - a); }

/// Distance from p to the segment ab, and the fraction s of its nearest point.
double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b, double& s) {
  const Vec2 d = b - a;
  const double length2 = dot(d, d);
  s = length2 > 0.0 ? std::clamp(dot(p - a, d) / length2, 0.0, 1.0) : 0.0;
  return distance(p, lerp(a, b, s));
}

/// The maximum of f on [lo, hi] by golden-section search, for a function with one maximum
/// there (a bump); returns its argument and sets `value`.
template <class F>
double golden_maximum(F&& f, double lo, double hi, double& value) {
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < kGoldenSteps; ++k) {
    if (f1 > f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - phi * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + phi * (hi - lo);
      f2 = f(x2);
    }
  }
  value = std::max(f1, f2);
  return f1 > f2 ? x1 : x2;
}

/// Uniform grid over the wall's edges: each cell lists the edges passing through it, so that
/// the nearest edge to a point is found by searching rings of cells around the point's cell
/// until the ring is farther than the nearest edge found.
class SegmentGrid {
 public:
  struct Nearest {
    double distance = kInfinity;
    std::size_t segment = 0;
    double s = 0.0;  ///< fraction along the segment of the nearest point
  };

  /// `cell`: the cell size wanted (the median edge length); enlarged so that there are at most
  /// about three cells per edge.
  SegmentGrid(std::span<const Segment> segments, double cell) : segments_(segments) {
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

  Nearest nearest(const Vec2& p) const {
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

 private:
  std::pair<std::size_t, std::size_t> index(const Vec2& p) const {
    const auto clamp = [](double u, std::size_t n) {
      if (!(u > 0.0)) return std::size_t{0};  // NaN too
      return std::min(static_cast<std::size_t>(std::min(u, 1e18)), n - 1);
    };
    return {clamp((p.x - lo_.x) / cell_, nx_), clamp((p.y - lo_.y) / cell_, ny_)};
  }

  void visit(std::size_t cell, const Vec2& p, Nearest& best) const {
    for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
      const Segment& g = segments_[items_[k]];
      double s = 0.0;
      const double d = segment_distance(p, g.a, g.b, s);
      if (d < best.distance) best = {d, items_[k], s};
    }
  }

  std::span<const Segment> segments_;
  Vec2 lo_;
  double cell_ = 1.0;
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> items_;
};

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

/// Everything one measurement needs.
class Measure {
 public:
  Measure(const CurveProjector& curve, std::span<const Vec3> points, const WallDeviationOptions& options,
          std::vector<Segment> segments)
      : curve_(curve), points_(points), options_(options), segments_(std::move(segments)) {
    round_off_ = kRoundOff * curve.length_scale();
    std::vector<double> lengths;
    for (const Segment& g : segments_) {
      const double length = distance(g.a, g.b);
      if (length > round_off_) lengths.push_back(length);
    }
    if (!lengths.empty()) {
      std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
      median_length_ = lengths[lengths.size() / 2];
    }
  }

  /// mesh_to_shape, and the range of the nodes' parameters.
  void wall_to_curve(WallDeviation& result) {
    struct Candidate {
      double distance;
      std::size_t segment;
      double lo, hi;  // the bracket, fractions along the segment
    };
    std::vector<Candidate> candidates;
    const int n = options_.edge_samples;
    std::vector<double> d(static_cast<std::size_t>(n) + 2);
    double t_lo = kInfinity, t_hi = -kInfinity, best = -1.0;
    WallDeviationPoint& worst = result.mesh_to_shape;
    bool not_finite = false;
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      const Segment& g = segments_[i];
      // An edge of zero length in the plane (an edge across theta in 3D): its end point only.
      const int last = distance(g.a, g.b) > round_off_ ? n + 1 : 0;
      for (int j = 0; j <= last; ++j) {
        const double s = last == 0 ? 0.0 : static_cast<double>(j) / (n + 1);
        const CurveProjection q = curve_.project(lerp(g.a, g.b, s), options_.lambda);
        d[static_cast<std::size_t>(j)] = q.distance;
        if (std::isnan(q.distance)) not_finite = true;
        if (j == 0 || j == last) {  // a node
          t_lo = std::min(t_lo, q.parameter);
          t_hi = std::max(t_hi, q.parameter);
        }
        if (q.distance > best) {
          best = q.distance;
          set_wall_point(worst, i, s, q);
        }
      }
      for (int j = 0; j <= last && last > 0; ++j) {
        const double dj = d[static_cast<std::size_t>(j)];
        const bool peak = (j == 0 || dj >= d[static_cast<std::size_t>(j - 1)]) &&
                          (j == last || dj >= d[static_cast<std::size_t>(j + 1)]);
        if (peak && dj > round_off_) {
          candidates.push_back({dj, i, std::max(j - 1, 0) / double(n + 1), std::min(j + 1, last) / double(n + 1)});
        }
      }
    }
    // The highest first, so that the bound prunes the most.
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.distance > b.distance; });
    for (const Candidate& c : candidates) {
      const Segment& g = segments_[c.segment];
      const double spacing = distance(g.a, g.b) / (n + 1);
      if (c.distance + 0.5 * spacing <= best) continue;  // Lipschitz: cannot beat it
      const auto f = [&](double s) { return curve_.project(lerp(g.a, g.b, s), options_.lambda).distance; };
      double value = 0.0;
      const double s = golden_maximum(f, c.lo, c.hi, value);
      if (value > best) {
        best = value;
        set_wall_point(worst, c.segment, s, curve_.project(lerp(g.a, g.b, s), options_.lambda));
      }
    }
    worst.distance = not_finite ? std::numeric_limits<double>::quiet_NaN() : std::max(best, 0.0);
    result.first_parameter = t_lo;
    result.last_parameter = t_hi;
  }

  /// shape_to_mesh over [first_parameter, last_parameter].
  void curve_to_wall(WallDeviation& result) {
    const double t_lo = result.first_parameter, t_hi = result.last_parameter;
    const double lambda = options_.lambda;
    const SegmentGrid grid(segments_, median_length_);
    // The sample parameters: every piece end inside the range, and between them at most
    // `spacing` apart along the curve (the length of a piece estimated by 8 chords).
    std::vector<double> t{t_lo};
    const double spacing = median_length_ > 0.0 ? options_.curve_spacing * median_length_ : kInfinity;
    for (const auto& piece : curve_.curve().pieces()) {
      const double a = std::max(piece.begin, t_lo), b = std::min(piece.end, t_hi);
      if (!(b > a)) continue;
      double length = 0.0;
      for (int k = 0; k < 8; ++k) {
        length += distance(curve_.at(a + (b - a) * k / 8.0, lambda).point, curve_.at(a + (b - a) * (k + 1) / 8.0, lambda).point);
      }
      const double count = std::clamp(std::ceil(length / spacing), 1.0, static_cast<double>(kMaxPieceSamples));
      const auto m = std::isfinite(count) ? static_cast<std::size_t>(count) : std::size_t{1};
      for (std::size_t k = 1; k <= m; ++k) t.push_back(a + (b - a) * static_cast<double>(k) / static_cast<double>(m));
    }
    result.shape_samples = t.size();

    WallDeviationPoint& worst = result.shape_to_mesh;
    double best = -1.0;
    bool not_finite = false;
    std::vector<double> d(t.size());
    std::vector<Vec2> c(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
      c[i] = curve_.at(t[i], lambda).point;
      const SegmentGrid::Nearest w = grid.nearest(c[i]);
      d[i] = w.distance;
      if (std::isnan(w.distance) || !is_finite(c[i])) not_finite = true;
      if (w.distance > best) {
        best = w.distance;
        set_curve_point(worst, t[i], c[i], w);
      }
    }
    struct Candidate {
      double distance;
      std::size_t sample;
    };
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const bool peak = (i == 0 || d[i] >= d[i - 1]) && (i + 1 == t.size() || d[i] >= d[i + 1]);
      if (peak && d[i] > round_off_ && t.size() > 1) candidates.push_back({d[i], i});
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.distance > b.distance; });
    for (const Candidate& cand : candidates) {
      const std::size_t i = cand.sample, before = i > 0 ? i - 1 : i, after = std::min(i + 1, t.size() - 1);
      // The chords to the neighbours stand for the arc lengths in the Lipschitz bound.
      const double spread = std::max(distance(c[before], c[i]), distance(c[i], c[after]));
      if (cand.distance + 0.5 * spread <= best) continue;
      const auto f = [&](double u) { return grid.nearest(curve_.at(u, lambda).point).distance; };
      double value = 0.0;
      const double u = golden_maximum(f, t[before], t[after], value);
      if (value > best) {
        best = value;
        const Vec2 p = curve_.at(u, lambda).point;
        set_curve_point(worst, u, p, grid.nearest(p));
      }
    }
    worst.distance = not_finite ? std::numeric_limits<double>::quiet_NaN() : std::max(best, 0.0);
  }

 private:
  /// A point of the plane put back in space: in 2D at the z of `near`, in 3D in the meridional
  /// plane through `near`.
  Vec3 in_space(const Vec2& q, const Vec3& near) const {
    if (!options_.axis) return {q.x, q.y, near.z};
    const Cylindrical c = options_.axis->to_cylindrical(near);
    return options_.axis->to_cartesian({q.x, c.theta, q.y});
  }
  Vec3 on_edge(const Segment& g, double s) const {
    return lerp(points_[static_cast<std::size_t>(g.na)], points_[static_cast<std::size_t>(g.nb)], s);
  }

  void set_wall_point(WallDeviationPoint& w, std::size_t segment, double s, const CurveProjection& q) const {
    const Segment& g = segments_[segment];
    const Vec3 near = on_edge(g, s);
    w.distance = q.distance;
    w.point = in_space(lerp(g.a, g.b, s), near);
    w.nearest = in_space(q.point, near);
    w.parameter = q.parameter;
    w.edge = {g.na, g.nb};
  }

  void set_curve_point(WallDeviationPoint& w, double t, const Vec2& p, const SegmentGrid::Nearest& n) const {
    const Segment& g = segments_[n.segment];
    const Vec3 near = on_edge(g, n.s);
    w.distance = n.distance;
    w.point = in_space(p, near);
    w.nearest = in_space(lerp(g.a, g.b, n.s), near);
    w.parameter = t;
    w.edge = {g.na, g.nb};
  }

  const CurveProjector& curve_;
  std::span<const Vec3> points_;
  const WallDeviationOptions& options_;
  std::vector<Segment> segments_;
  double round_off_ = 0.0;
  double median_length_ = 0.0;
};

}  // namespace

void WallFaces::add(std::span<const std::int32_t> corners) {
  if (corners.size() < 2) throw std::invalid_argument("WallFaces::add: a face needs at least 2 corners");
  corners_.insert(corners_.end(), corners.begin(), corners.end());
  offsets_.push_back(corners_.size());
}

void WallDeviation::take_worst_direction() {
  const double a = mesh_to_shape.distance, b = shape_to_mesh.distance;
  worst = b > a ? WallDirection::shape_to_mesh : WallDirection::mesh_to_shape;
  hausdorff = std::isnan(a) || std::isnan(b) ? std::numeric_limits<double>::quiet_NaN() : std::max(a, b);
}

const char* to_string(WallDirection direction) {
  return direction == WallDirection::mesh_to_shape ? "mesh_to_shape" : "shape_to_mesh";
}

WallDeviation wall_deviation(const CurveProjector& curve, std::span<const Vec3> points, const WallFaces& faces,
                             const WallDeviationOptions& options) {
  if (options.edge_samples < 1 || options.edge_samples > 1000000) {
    throw std::invalid_argument("wall_deviation: edge_samples must be 1 to 1e6");
  }
  if (!(options.curve_spacing > 0.0) || !std::isfinite(options.curve_spacing) || !std::isfinite(options.lambda)) {
    throw std::invalid_argument("wall_deviation: curve_spacing must be positive and lambda finite");
  }
  WallDeviation result;
  std::vector<Segment> segments = plane_segments(points, faces, options.axis);
  result.edges = segments.size();
  if (segments.empty()) return result;
  Measure measure(curve, points, options, std::move(segments));
  measure.wall_to_curve(result);
  measure.curve_to_wall(result);
  result.take_worst_direction();
  return result;
}

}  // namespace hotmesh::geometry
