// hotmesh geometry: closest points on the stages of a deflected curve (section 4.2): a sampled
// box tree for a global start, safeguarded Newton on the squared distance with de Boor
// evaluation for the local solve.
// Why not CGAL's AABB tree: its primitives are fixed segments, one geometry per tree. Here one
// tree serves every stage lambda of the motion, its boxes holding the sample segments of r and
// c_1 and so of every c_lambda between them (affine in lambda); with CGAL each increment would
// build a tree of its own. And a query here wants every run of segments within twice the
// sampling deviation of the nearest, to start Newton from each, not the one closest point.
#include "hotmesh/geometry/curve_projector.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace hotmesh::geometry {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Chord deviation the sampling aims at, relative to the length scale.
constexpr double kSamplingTarget = 2e-4;
/// Newton stops when the step moves the point by less than this, relative to the scale.
constexpr double kNewtonTolerance = 1e-13;
constexpr int kMaxNewtonIterations = 60;
/// Newton steps shorter than this (relative to the scale) skip the descent check.
constexpr double kLocalStep = 1e-7;
/// After an accepted step shorter than this (relative to the scale) Newton stops.
constexpr double kFinalStep = 1e-9;
constexpr int kMaxSplitDepth = 24;

double squared(const Vec2& v) { return dot(v, v); }

double box_squared_distance(const Vec2& lo, const Vec2& hi, const Vec2& p) {
  const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
  const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
  return dx * dx + dy * dy;
}

/// Unit normal (tangent turned by +90 degrees) from a point with derivatives; where the first
/// derivative vanishes (a cusp of the parametrisation), the second gives the direction.
bool unit_normal(const CurveDerivatives2d& d, Vec2& normal) {
  for (const Vec2& v : {d.first, d.second}) {
    const double length = norm(v);
    if (length > 0.0 && std::isfinite(length)) {
      normal = perpendicular(v / length);
      return true;
    }
  }
  return false;
}

}  // namespace

CurveProjector::CurveProjector(DeflectedCurve curve) : curve_(std::move(curve)) {
  sample_pieces();
  build_tree();
}

void CurveProjector::sample_pieces() {
  const auto& pieces = curve_.pieces();
  int degree = curve_.undeformed().degree();
  if (curve_.interpolant()) degree = std::max(degree, curve_.interpolant()->degree());
  const int base = std::max(4, 2 * degree);

  // A coarse pass for the length scale.
  Vec2 lo{kInfinity, kInfinity};
  Vec2 hi{-kInfinity, -kInfinity};
  for (const auto& piece : pieces) {
    for (int i = 0; i <= base; ++i) {
      const double t = piece.begin + (piece.end - piece.begin) * i / base;
      for (const double lambda : {0.0, 1.0}) {
        const Vec2 q = curve_.derivatives(t, lambda, piece).point;
        lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
      }
    }
  }
  scale_ = norm(hi - lo);
  if (!(scale_ > 0.0)) scale_ = std::max({1.0, std::abs(lo.x), std::abs(lo.y)});
  const double target = kSamplingTarget * scale_;

  double worst = 0.0;
  samples_.clear();
  segment_piece_.clear();
  piece_segment_.clear();
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto& piece = pieces[k];
    piece_segment_.push_back(samples_.size());
    const auto sample = [&](double t) {
      return Sample{t, curve_.derivatives(t, 0.0, piece).point, curve_.derivatives(t, 1.0, piece).point};
    };
    // Deviation of both r and c_1 from the chord of [a, b], at three interior points.
    const auto deviation = [&](const Sample& a, const Sample& b) {
      double d = 0.0;
      for (const double s : {0.25, 0.5, 0.75}) {
        const Sample m = sample(a.t + s * (b.t - a.t));
        d = std::max({d, norm(m.r - (a.r + s * (b.r - a.r))), norm(m.c - (a.c + s * (b.c - a.c)))});
      }
      return d;
    };
    // Splits [a, b] until the chords are within the target; appends a and the inner samples.
    const auto refine = [&](auto&& self, const Sample& a, const Sample& b, int depth) -> void {
      const double d = deviation(a, b);
      if (d > target && depth < kMaxSplitDepth) {
        const Sample m = sample(0.5 * (a.t + b.t));
        self(self, a, m, depth + 1);
        self(self, m, b, depth + 1);
        return;
      }
      worst = std::max(worst, d);
      samples_.push_back(a);
      segment_piece_.push_back(static_cast<std::uint32_t>(k));
    };
    Sample a = sample(piece.begin);
    for (int i = 1; i <= base; ++i) {
      const Sample b = sample(i == base ? piece.end : piece.begin + (piece.end - piece.begin) * i / base);
      refine(refine, a, b, 0);
      a = b;
    }
  }
  const auto& last = pieces.back();
  samples_.push_back({last.end, curve_.derivatives(last.end, 0.0, last).point,
                      curve_.derivatives(last.end, 1.0, last).point});
  piece_segment_.push_back(samples_.size() - 1);

  lo = {kInfinity, kInfinity};
  hi = {-kInfinity, -kInfinity};
  for (const Sample& s : samples_) {
    for (const Vec2& q : {s.r, s.c}) {
      lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
      hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
    }
  }
  scale_ = std::max(scale_, norm(hi - lo));
  deviation_ = 1.5 * worst + 1e-12 * scale_;
  newton_tolerance_ = kNewtonTolerance * scale_;
}

void CurveProjector::build_tree() {
  const std::size_t segments = samples_.size() - 1;
  leaves_ = std::bit_ceil(segments);
  tree_.assign(2 * leaves_, Box{{kInfinity, kInfinity}, {-kInfinity, -kInfinity}});
  for (std::size_t i = 0; i < segments; ++i) {
    Box& box = tree_[leaves_ + i];
    for (const Vec2& q : {samples_[i].r, samples_[i].c, samples_[i + 1].r, samples_[i + 1].c}) {
      box.lo = {std::min(box.lo.x, q.x), std::min(box.lo.y, q.y)};
      box.hi = {std::max(box.hi.x, q.x), std::max(box.hi.y, q.y)};
    }
  }
  for (std::size_t i = leaves_ - 1; i >= 1; --i) {
    const Box& a = tree_[2 * i];
    const Box& b = tree_[2 * i + 1];
    tree_[i] = {{std::min(a.lo.x, b.lo.x), std::min(a.lo.y, b.lo.y)},
                {std::max(a.hi.x, b.hi.x), std::max(a.hi.y, b.hi.y)}};
  }
}

// Minimises f(t) = |c_lambda(t) - p|^2 / 2 piece by piece: Newton steps t -= f'/f'' with
// f' = (c - p).c', f'' = c'.c' + (c - p).c'' (Gauss-Newton c'.c' where f'' is not clearly
// positive), halved until f decreases. A step that leaves the piece stops at its end; from
// there the search continues in the neighbouring piece unless f grows on both sides, which is
// a minimum at a corner of the curve (C0 knots: degree-1 curves, joined faces). The search
// stays on the pieces `searched`: their outer ends are ends of the curve for it.
CurveProjector::Local CurveProjector::newton(const Vec2& p, double lambda, double t, std::size_t k,
                                             const Pieces& searched) const {
  const auto& pieces = curve_.pieces();
  CurveDerivatives2d e = curve_.derivatives(t, lambda, pieces[k]);
  double f = squared(e.point - p);
  int iteration = 0;
  bool converged = false;
  while (iteration < kMaxNewtonIterations) {
    ++iteration;
    const Vec2 diff = e.point - p;
    const double g = dot(diff, e.first);
    const double gg = dot(e.first, e.first);
    if (!(gg > 0.0)) {
      converged = true;  // the parametrisation stalls here; nothing better along t
      break;
    }
    double h = gg + dot(diff, e.second);
    if (!(h > 0.1 * gg)) h = gg;
    double step = -g / h;
    if (std::abs(step) * std::sqrt(gg) <= newton_tolerance_) {
      converged = true;
      break;
    }
    const auto& piece = pieces[k];
    bool clipped = false;
    if (t + step <= piece.begin || t + step >= piece.end) {
      const bool left = t + step <= piece.begin;
      const double edge = left ? piece.begin : piece.end;
      if (t != edge) {
        step = edge - t;  // go to the end of the piece first
        clipped = true;
      } else {
        const bool last = left ? k == searched.first : k == searched.last;
        if (last) {
          converged = true;  // minimum at an end of the curve
          break;
        }
        const std::size_t next = left ? k - 1 : k + 1;
        const CurveDerivatives2d other = curve_.derivatives(t, lambda, pieces[next]);
        const double g_other = dot(other.point - p, other.first);
        if (left ? g_other <= 0.0 : g_other >= 0.0) {
          converged = true;  // f grows on both sides of this corner
          break;
        }
        k = next;
        e = other;
        continue;
      }
    }
    double t_new = t + step;
    CurveDerivatives2d e_new = curve_.derivatives(t_new, lambda, pieces[k]);
    double f_new = squared(e_new.point - p);
    // Near the solution the quadratic model is good and f is flat to rounding: take the step.
    if (std::abs(step) * std::sqrt(gg) <= kLocalStep * scale_) f_new = std::min(f_new, f);
    for (int halving = 0; f_new > f && halving < 40; ++halving) {
      step *= 0.5;
      t_new = t + step;
      e_new = curve_.derivatives(t_new, lambda, pieces[k]);
      f_new = squared(e_new.point - p);
    }
    if (f_new > f) {
      converged = true;  // no decrease left at rounding level
      break;
    }
    t = t_new;
    e = e_new;
    f = f_new;
    // Quadratic convergence: after a step this short the next one would be below rounding.
    if (!clipped && std::abs(step) * std::sqrt(gg) <= kFinalStep * scale_) {
      converged = true;
      break;
    }
  }
  return {t, k, e, f, iteration, converged};
}

CurveProjection CurveProjector::finish(const Vec2& p, double lambda, const Local& local) const {
  const auto& pieces = curve_.pieces();
  const auto& piece = pieces[local.piece];
  CurveProjection result;
  result.point = local.value.point;
  result.parameter = local.t;
  result.distance = std::sqrt(local.squared_distance);
  result.iterations = local.iterations;
  Vec2 normal{0.0, 0.0};
  const bool has_normal = unit_normal(local.value, normal);
  // At a corner the two one-sided normals differ: use their bisector.
  std::size_t other = pieces.size();
  if (local.t == piece.begin && local.piece > 0) other = local.piece - 1;
  if (local.t == piece.end && local.piece + 1 < pieces.size()) other = local.piece + 1;
  Vec2 other_normal;
  if (other < pieces.size() && unit_normal(curve_.derivatives(local.t, lambda, pieces[other]), other_normal)) {
    if (!has_normal) {
      normal = other_normal;
    } else if (dot(normal, other_normal) < 1.0 - 1e-14) {
      const Vec2 sum = normal + other_normal;
      const double length = norm(sum);
      if (length > 1e-8) {
        normal = sum / length;
      } else if (result.distance > 0.0) {
        normal = (p - result.point) / result.distance;  // a cusp: the direction to the point
      }
    }
  } else if (!has_normal) {
    normal = result.distance > 0.0 ? (p - result.point) / result.distance : Vec2{0.0, 1.0};
  }
  result.normal = normal;
  result.tangent = {normal.y, -normal.x};
  return result;
}

double CurveProjector::segment_squared_distance(std::size_t i, const Vec2& p, double lambda, double& t) const {
  const Vec2 a = samples_[i].r + lambda * (samples_[i].c - samples_[i].r);
  const Vec2 b = samples_[i + 1].r + lambda * (samples_[i + 1].c - samples_[i + 1].r);
  const Vec2 ab = b - a;
  const double length2 = squared(ab);
  const double u = length2 > 0.0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  t = samples_[i].t + u * (samples_[i + 1].t - samples_[i].t);
  return squared(a + u * ab - p);
}

bool CurveProjector::overlaps(std::size_t node, std::size_t first, std::size_t end) const {
  const auto depth = static_cast<std::size_t>(std::bit_width(node)) - 1;
  const std::size_t span = leaves_ >> depth;
  const std::size_t begin = node * span - leaves_;
  return begin < end && first < begin + span;
}

// 1. Distance to the nearest segment of the sample polyline (branch and bound).
double CurveProjector::nearest_segment_squared_distance(const Vec2& p, double lambda, const Pieces& searched) const {
  const std::size_t segments = searched.end_segment;
  const auto box_distance = [&](std::size_t node) { return box_squared_distance(tree_[node].lo, tree_[node].hi, p); };
  std::size_t stack[128];
  std::size_t top = 0;
  double best = kInfinity;
  stack[top++] = 1;
  while (top > 0) {
    const std::size_t node = stack[--top];
    if (box_distance(node) >= best || !overlaps(node, searched.first_segment, searched.end_segment)) continue;
    if (node >= leaves_) {
      double t = 0.0;
      if (node - leaves_ < segments) best = std::min(best, segment_squared_distance(node - leaves_, p, lambda, t));
      continue;
    }
    const std::size_t near = box_distance(2 * node) <= box_distance(2 * node + 1) ? 2 * node : 2 * node + 1;
    stack[top++] = near ^ 1u;  // the sibling: visited after the nearer child
    stack[top++] = near;
  }
  return best;
}

// 2. Runs of consecutive segments within the threshold, in increasing order of segments.
int CurveProjector::runs_within(const Vec2& p, double lambda, double threshold, const Pieces& searched,
                                Run (&runs)[kMaxRuns]) const {
  const std::size_t segments = searched.end_segment;
  int run_count = 0;
  int current = -1;
  std::size_t stack[128];
  std::size_t top = 0;
  stack[top++] = 1;
  while (top > 0) {
    const std::size_t node = stack[--top];
    if (box_squared_distance(tree_[node].lo, tree_[node].hi, p) > threshold ||
        !overlaps(node, searched.first_segment, searched.end_segment)) {
      continue;
    }
    if (node < leaves_) {
      stack[top++] = 2 * node + 1;  // left child first: segments in increasing order
      stack[top++] = 2 * node;
      continue;
    }
    const std::size_t segment = node - leaves_;
    double t = 0.0;
    if (segment >= segments) continue;
    const double d = segment_squared_distance(segment, p, lambda, t);
    if (d > threshold) continue;
    if (current >= 0 && runs[current].last + 1 == segment) {
      Run& run = runs[current];
      run.last = segment;
      if (d < run.squared_distance) run = {segment, d, t, segment};
      continue;
    }
    if (run_count < kMaxRuns) {
      current = run_count++;
    } else {  // full: the new run replaces the farthest, if it is nearer
      current = static_cast<int>(std::max_element(runs, runs + kMaxRuns,
                                                  [](const Run& a, const Run& b) {
                                                    return a.squared_distance < b.squared_distance;
                                                  }) -
                                 runs);
      if (runs[current].squared_distance <= d) {
        current = -1;
        continue;
      }
    }
    runs[current] = {segment, d, t, segment};
  }
  return run_count;
}

CurveProjection CurveProjector::global_search(const Vec2& p, double lambda, const Pieces& searched) const {
  const double best = nearest_segment_squared_distance(p, lambda, searched);
  // The curve's closest point lies next to a run of segments within twice the sampling
  // deviation of the nearest segment's distance.
  const double reach = std::sqrt(best) + 2.0 * deviation_;
  Run runs[kMaxRuns];
  const int run_count = runs_within(p, lambda, reach * reach, searched, runs);
  // 3. Newton from the best point of each run; the closest result wins.
  Local winner{};
  winner.squared_distance = kInfinity;
  for (int i = 0; i < run_count; ++i) {
    const Local local = newton(p, lambda, runs[i].t, segment_piece_[runs[i].segment], searched);
    if (local.squared_distance < winner.squared_distance) winner = local;
  }
  return finish(p, lambda, winner);
}

CurveProjector::Pieces CurveProjector::pieces_in(const ParameterRange& range) const {
  const auto& pieces = curve_.pieces();
  std::size_t first = 0;
  std::size_t last = pieces.size() - 1;
  if (range.first > pieces.front().begin) first = std::min(curve_.piece_at(range.first), last);  // at a piece end: the next
  if (range.last < pieces.back().end) {
    last = curve_.piece_at(range.last);
    if (last > first && !(pieces[last].begin < range.last)) --last;  // at a piece end: the one before
  }
  last = std::max(last, first);
  return {first, last, piece_segment_[first], piece_segment_[last + 1]};
}

CurveProjection CurveProjector::project(const Vec2& p, double lambda, double hint, const ParameterRange& range) const {
  const double l = std::clamp(lambda, 0.0, 1.0);
  const Pieces searched = pieces_in(range);
  if (std::isfinite(hint)) {
    const auto& pieces = curve_.pieces();
    const double t = std::clamp(hint, pieces[searched.first].begin, pieces[searched.last].end);
    const std::size_t k = std::clamp(curve_.piece_at(t), searched.first, searched.last);
    const Local local = newton(p, l, t, k, searched);
    if (local.converged) return finish(p, l, local);
  }
  return global_search(p, l, searched);
}

CurveProjection CurveProjector::at(double t, double lambda) const {
  const double u = std::clamp(t, curve_.first_parameter(), curve_.last_parameter());
  const double l = std::clamp(lambda, 0.0, 1.0);
  const std::size_t k = curve_.piece_at(u);
  const CurveDerivatives2d value = curve_.derivatives(u, l, curve_.pieces()[k]);
  return finish(value.point, l, {u, k, value, 0.0, 0, true});
}

}  // namespace hotmesh::geometry
