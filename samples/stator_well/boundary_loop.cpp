// hotmesh sample stator_well: the boundary loop in arc length (see boundary_loop.hpp).
#include "boundary_loop.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace hotmesh::samples {

namespace {

constexpr int kArcSamplesPerSpan = 128;  // chord sums over these give arc lengths to ~1e-6

/// The parameter at arc length `s` of a (parameter, arc length) table, or the reverse.
double interpolate(const std::vector<std::array<double, 2>>& table, std::size_t from, double value) {
  const std::size_t to = 1 - from;
  const auto it = std::lower_bound(table.begin(), table.end(), value, [&](const auto& e, double x) { return e[from] < x; });
  if (it == table.begin()) return table.front()[to];
  if (it == table.end()) return table.back()[to];
  const auto& a = *(it - 1);
  const auto& b = *it;
  return a[to] + (b[to] - a[to]) * (value - a[from]) / (b[from] - a[from]);
}

}  // namespace

BoundaryLoop::BoundaryLoop(const std::vector<LoopCurve>& curves) {
  const std::size_t n = curves.size();
  if (n == 0) throw std::invalid_argument("boundary loop: no curves");
  start_.assign(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const BSplineCurve2d& c = curves[i].curve;
    curves_.push_back(c);
    const auto breaks = c.breakpoints();
    auto& table = arc_.emplace_back();
    table.push_back({breaks.front(), 0.0});
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      for (int j = 1; j <= kArcSamplesPerSpan; ++j) {
        const double t = j == kArcSamplesPerSpan ? breaks[k + 1] : breaks[k] + (breaks[k + 1] - breaks[k]) * j / kArcSamplesPerSpan;
        table.push_back({t, table.back()[1] + distance(c.point(t), c.point(table.back()[0]))});
      }
    }
    start_[i + 1] = start_[i] + table.back()[1];
    const auto& next = curves[(i + 1) % n].curve;
    const Vec2 next_start = next.point(next.first_parameter());
    if (distance(c.point(c.last_parameter()), next_start) > 1e-12 * (1.0 + norm(next_start))) {
      throw std::invalid_argument(fmt::format("boundary loop: curve {} does not end where the next starts", i));
    }
  }
  eps_ = 1e-12 * length();
  // Walls: consecutive wall curves with a continuous tangent form one wall (union-find).
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const Vec2 ta = curves_[i].derivatives(curves_[i].last_parameter()).first;
    const Vec2 tb = curves_[j].derivatives(curves_[j].first_parameter()).first;
    const double sine = (ta.x * tb.y - ta.y * tb.x) / (norm(ta) * norm(tb));
    if (curves[i].wall && curves[j].wall && std::abs(sine) < 1e-6 && dot(ta, tb) > 0.0) parent[root(i)] = root(j);
  }
  for (std::size_t i = 0; i < n; ++i) wall_.push_back(curves[i].wall ? static_cast<int>(root(i)) : -1);
}

Vec2 BoundaryLoop::point(double s) const {
  s = std::fmod(s, length());
  const std::size_t i = curve_after(s);
  return curves_[i].point(interpolate(arc_[i], 1, s - start_[i]));
}

std::optional<double> BoundaryLoop::locate(Vec2 p, double tolerance) const {
  for (std::size_t i = 0; i < curves_.size(); ++i) {
    const BSplineCurve2d& c = curves_[i];
    // The nearest sample, then Newton on the squared distance.
    double t = arc_[i].front()[0], nearest = distance(c.point(t), p);
    for (const auto& e : arc_[i]) {
      const double d = distance(c.point(e[0]), p);
      if (d < nearest) {
        nearest = d;
        t = e[0];
      }
    }
    for (int it = 0; it < 30; ++it) {
      const auto d = c.derivatives(t);
      const double g = dot(d.point - p, d.first);
      const double h = dot(d.first, d.first) + dot(d.point - p, d.second);
      if (h <= 0.0) break;
      const double next = std::clamp(t - g / h, c.first_parameter(), c.last_parameter());
      if (std::abs(next - t) < 1e-15) break;
      t = next;
    }
    if (distance(c.point(t), p) > tolerance) continue;
    const double s = start_[i] + interpolate(arc_[i], 0, t);
    return s > length() - eps_ ? 0.0 : s;
  }
  return std::nullopt;
}

std::size_t BoundaryLoop::curve_after(double s) const {
  s = std::fmod(s, length());
  const auto it = std::upper_bound(start_.begin(), start_.end(), s + eps_);
  return std::min(static_cast<std::size_t>(it - start_.begin()) - 1, curves_.size() - 1);
}

std::size_t BoundaryLoop::curve_before(double s) const {
  if (s <= eps_) s += length();
  const auto it = std::lower_bound(start_.begin(), start_.end(), s - eps_);
  return std::min(static_cast<std::size_t>(it - start_.begin()) - 1, curves_.size() - 1);
}

std::vector<int> BoundaryLoop::walls_at(double s) const {
  std::vector<int> walls;
  for (const std::size_t i : {curve_after(s), curve_before(s)}) {
    if (wall_[i] >= 0 && std::find(walls.begin(), walls.end(), wall_[i]) == walls.end()) walls.push_back(wall_[i]);
  }
  return walls;
}

}  // namespace hotmesh::samples
