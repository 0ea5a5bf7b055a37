// hotmesh geometry: the two-sided distance between a discrete wall and its curve (see
// wall_deviation.hpp): the wall's edges taken into the curve's plane, sampled and projected on
// the curve; the curve sampled over the part the wall covers, each sample's nearest edge found
// through a uniform grid (wall_segments.hpp); local maxima of both refined by golden-section
// search, the two directions driven as two_sided_distance.hpp does for walls on faces too.
#include "hotmesh/geometry/wall_deviation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "measure/two_sided_distance.hpp"
#include "measure/wall_segments.hpp"

namespace hotmesh::geometry {

namespace {

using detail::kRoundOff;
using detail::lerp;
using detail::Refinement;
using detail::RunningMaximum;
using detail::Segment;
using detail::SegmentGrid;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Golden-section steps of a refinement: the bracket of two sample spacings shrinks by
/// 0.618^30 ~ 5e-7, so a smooth maximum is found to ~1e-13 of its bracket and a corner's (a
/// kink, slope at most 1) to 5e-7 of it.
constexpr int kGoldenSteps = 30;
/// At most this many curve samples per piece of the curve.
constexpr std::size_t kMaxPieceSamples = std::size_t{1} << 20;

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

class EdgesToCurve;
class CurveToEdges;

/// Everything one measurement needs: the curve, the wall's edges in its plane and their median
/// length; its two directions are EdgesToCurve and CurveToEdges.
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
    median_length_ = detail::median_length(lengths);
  }

  /// mesh_to_shape, and the range of the nodes' parameters.
  EdgesToCurve wall_side(WallDeviation& result) const;
  /// shape_to_mesh over [first_parameter, last_parameter].
  CurveToEdges shape_side(WallDeviation& result) const;

  const CurveProjector& curve() const { return curve_; }
  const WallDeviationOptions& options() const { return options_; }
  std::span<const Segment> segments() const { return segments_; }
  double round_off() const { return round_off_; }
  double median_length() const { return median_length_; }

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

  const CurveProjector& curve_;
  std::span<const Vec3> points_;
  const WallDeviationOptions& options_;
  std::vector<Segment> segments_;
  double round_off_ = 0.0;
  double median_length_ = 0.0;
};

/// mesh_to_shape: every edge sampled at its ends and edge_samples interior points, each
/// projected on the curve (cold); the local maxima along an edge refined in their bracket of two
/// spacings.
class EdgesToCurve {
 public:
  struct Candidate {
    double distance;
    std::size_t segment;
    double lo, hi;  // the bracket, fractions along the segment
  };

  EdgesToCurve(const Measure& measure, WallDeviation& result) : measure_(measure), result_(result) {}

  std::vector<Candidate> sample(RunningMaximum& maximum) {
    const std::span<const Segment> segments = measure_.segments();
    const CurveProjector& curve = measure_.curve();
    std::vector<Candidate> candidates;
    const int n = measure_.options().edge_samples;
    std::vector<double> d(static_cast<std::size_t>(n) + 2);
    double t_lo = kInfinity, t_hi = -kInfinity;
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const Segment& g = segments[i];
      // An edge of zero length in the plane (an edge across theta in 3D): its end point only.
      const int last = distance(g.a, g.b) > measure_.round_off() ? n + 1 : 0;
      for (int j = 0; j <= last; ++j) {
        const double s = last == 0 ? 0.0 : static_cast<double>(j) / (n + 1);
        const CurveProjection q = curve.project(lerp(g.a, g.b, s), measure_.options().lambda);
        d[static_cast<std::size_t>(j)] = q.distance;
        if (std::isnan(q.distance)) maximum.not_finite = true;
        if (j == 0 || j == last) {  // a node
          t_lo = std::min(t_lo, q.parameter);
          t_hi = std::max(t_hi, q.parameter);
        }
        if (maximum.raise(q.distance)) measure_.set_wall_point(result_.mesh_to_shape, i, s, q);
      }
      for (int j = 0; j <= last && last > 0; ++j) {
        const double dj = d[static_cast<std::size_t>(j)];
        const bool peak = (j == 0 || dj >= d[static_cast<std::size_t>(j - 1)]) &&
                          (j == last || dj >= d[static_cast<std::size_t>(j + 1)]);
        if (peak && dj > measure_.round_off()) {
          candidates.push_back({dj, i, std::max(j - 1, 0) / double(n + 1), std::min(j + 1, last) / double(n + 1)});
        }
      }
    }
    result_.first_parameter = t_lo;
    result_.last_parameter = t_hi;
    return candidates;
  }

  static bool higher(const Candidate& a, const Candidate& b) { return a.distance > b.distance; }

  Refinement judge(const Candidate& c, double best) const {
    const Segment& g = measure_.segments()[c.segment];
    const double spacing = distance(g.a, g.b) / (measure_.options().edge_samples + 1);
    // Lipschitz: cannot beat it
    return c.distance + 0.5 * spacing <= best ? Refinement::pass_over : Refinement::refine;
  }

  void refine(const Candidate& c, RunningMaximum& maximum) {
    const Segment& g = measure_.segments()[c.segment];
    const CurveProjector& curve = measure_.curve();
    const double lambda = measure_.options().lambda;
    const auto f = [&](double s) { return curve.project(lerp(g.a, g.b, s), lambda).distance; };
    double value = 0.0;
    const double s = golden_maximum(f, c.lo, c.hi, value);
    if (maximum.raise(value)) {
      measure_.set_wall_point(result_.mesh_to_shape, c.segment, s, curve.project(lerp(g.a, g.b, s), lambda));
    }
  }

 private:
  const Measure& measure_;
  WallDeviation& result_;
};

/// shape_to_mesh: the curve sampled over [first_parameter, last_parameter], each sample's
/// nearest edge found in the grid; the local maxima refined in the curve parameter between
/// their neighbours.
class CurveToEdges {
 public:
  struct Candidate {
    double distance;
    std::size_t sample;
  };

  CurveToEdges(const Measure& measure, WallDeviation& result)
      : measure_(measure), result_(result), grid_(measure.segments(), measure.median_length()) {}

  std::vector<Candidate> sample(RunningMaximum& maximum) {
    const double lambda = measure_.options().lambda;
    t_ = parameters();
    result_.shape_samples = t_.size();
    std::vector<double> d(t_.size());
    c_.resize(t_.size());
    for (std::size_t i = 0; i < t_.size(); ++i) {
      c_[i] = measure_.curve().at(t_[i], lambda).point;
      const SegmentGrid::Nearest w = grid_.nearest(c_[i]);
      d[i] = w.distance;
      if (std::isnan(w.distance) || !is_finite(c_[i])) maximum.not_finite = true;
      if (maximum.raise(w.distance)) measure_.set_curve_point(result_.shape_to_mesh, t_[i], c_[i], w);
    }
    std::vector<Candidate> candidates;
    for (std::size_t i = 0; i < t_.size(); ++i) {
      const bool peak = (i == 0 || d[i] >= d[i - 1]) && (i + 1 == t_.size() || d[i] >= d[i + 1]);
      if (peak && d[i] > measure_.round_off() && t_.size() > 1) candidates.push_back({d[i], i});
    }
    return candidates;
  }

  static bool higher(const Candidate& a, const Candidate& b) { return a.distance > b.distance; }

  Refinement judge(const Candidate& cand, double best) const {
    const std::size_t i = cand.sample, before = i > 0 ? i - 1 : i, after = std::min(i + 1, t_.size() - 1);
    // The chords to the neighbours stand for the arc lengths in the Lipschitz bound.
    const double spread = std::max(distance(c_[before], c_[i]), distance(c_[i], c_[after]));
    return cand.distance + 0.5 * spread <= best ? Refinement::pass_over : Refinement::refine;
  }

  void refine(const Candidate& cand, RunningMaximum& maximum) {
    const CurveProjector& curve = measure_.curve();
    const double lambda = measure_.options().lambda;
    const std::size_t i = cand.sample, before = i > 0 ? i - 1 : i, after = std::min(i + 1, t_.size() - 1);
    const auto f = [&](double u) { return grid_.nearest(curve.at(u, lambda).point).distance; };
    double value = 0.0;
    const double u = golden_maximum(f, t_[before], t_[after], value);
    if (maximum.raise(value)) {
      const Vec2 p = curve.at(u, lambda).point;
      measure_.set_curve_point(result_.shape_to_mesh, u, p, grid_.nearest(p));
    }
  }

 private:
  /// The sample parameters: every piece end inside the range, and between them at most
  /// `spacing` apart along the curve (the length of a piece estimated by 8 chords).
  std::vector<double> parameters() const {
    const double t_lo = result_.first_parameter, t_hi = result_.last_parameter;
    const double lambda = measure_.options().lambda;
    const CurveProjector& curve = measure_.curve();
    const double median_length = measure_.median_length();
    std::vector<double> t{t_lo};
    const double spacing = median_length > 0.0 ? measure_.options().curve_spacing * median_length : kInfinity;
    for (const auto& piece : curve.curve().pieces()) {
      const double a = std::max(piece.begin, t_lo), b = std::min(piece.end, t_hi);
      if (!(b > a)) continue;
      double length = 0.0;
      for (int k = 0; k < 8; ++k) {
        length += distance(curve.at(a + (b - a) * k / 8.0, lambda).point, curve.at(a + (b - a) * (k + 1) / 8.0, lambda).point);
      }
      const double count = std::clamp(std::ceil(length / spacing), 1.0, static_cast<double>(kMaxPieceSamples));
      const auto m = std::isfinite(count) ? static_cast<std::size_t>(count) : std::size_t{1};
      for (std::size_t k = 1; k <= m; ++k) t.push_back(a + (b - a) * static_cast<double>(k) / static_cast<double>(m));
    }
    return t;
  }

  const Measure& measure_;
  WallDeviation& result_;
  const SegmentGrid grid_;
  std::vector<double> t_;  ///< the curve's sample parameters
  std::vector<Vec2> c_;    ///< its points there
};

EdgesToCurve Measure::wall_side(WallDeviation& result) const { return {*this, result}; }
CurveToEdges Measure::shape_side(WallDeviation& result) const { return {*this, result}; }

}  // namespace

WallDeviation wall_deviation(const CurveProjector& curve, std::span<const Vec3> points, const WallFaces& faces,
                             const WallDeviationOptions& options) {
  if (options.edge_samples < 1 || options.edge_samples > 1000000) {
    throw std::invalid_argument("wall_deviation: edge_samples must be 1 to 1e6");
  }
  if (!(options.curve_spacing > 0.0) || !std::isfinite(options.curve_spacing) || !std::isfinite(options.lambda)) {
    throw std::invalid_argument("wall_deviation: curve_spacing must be positive and lambda finite");
  }
  WallDeviation result;
  std::vector<Segment> segments = detail::plane_segments(points, faces, options.axis);
  result.edges = segments.size();
  if (segments.empty()) return result;
  const Measure measure(curve, points, options, std::move(segments));
  detail::measure_both_directions(measure, result);
  return result;
}

}  // namespace hotmesh::geometry
