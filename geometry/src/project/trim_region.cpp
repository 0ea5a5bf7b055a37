// hotmesh geometry: the part of a face's parameter rectangle inside its trimming loops
// (trim_region.hpp).
#include "hotmesh/geometry/trim_region.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace hotmesh::geometry {

namespace {

/// Trims within this fraction of the rectangle's extent of a side lie along it.
constexpr double kOnSide = 1e-9;

/// Twice the signed area of (a, b, c): positive when c lies to the left of a -> b.
double orientation(const Vec2& a, const Vec2& b, const Vec2& c) { return cross(b - a, c - a); }

}  // namespace

TrimRegion::TrimRegion(std::vector<Curve> curves, const ParameterRectangle& rectangle)
    : curves_(std::move(curves)), rectangle_(rectangle) {
  if (!(rectangle.u_first < rectangle.u_last && rectangle.v_first < rectangle.v_last)) {
    throw std::invalid_argument("trim region: empty parameter rectangle");
  }
  for (const Curve& c : curves_) {
    for (const Vec2& q : c.points) {
      if (!is_finite(q)) throw std::invalid_argument("trim region: a point that is not finite");
    }
  }
  // The ends of curves that meet (a loop's vertices, a curve closing on itself) made one point,
  // so no ray slips through a gap of rounding between them.
  const double snap = kOnSide * std::max(rectangle.u_last - rectangle.u_first, rectangle.v_last - rectangle.v_first);
  std::vector<Vec2*> ends;
  for (Curve& c : curves_) {
    if (c.points.size() < 2) continue;
    for (Vec2* end : {&c.points.front(), &c.points.back()}) {
      for (const Vec2* other : ends) {
        if (distance(*end, *other) <= snap) {
          *end = *other;
          break;
        }
      }
      ends.push_back(end);
    }
  }
  for (const Curve& c : curves_) {
    for (std::size_t k = 1; k < c.points.size(); ++k) {
      segments_.push_back({c.points[k - 1], c.points[k]});
      binding_.push_back(c.binding ? 1 : 0);
    }
  }
  if (segments_.empty()) throw std::invalid_argument("trim region: no curve with two points");
  // About one segment per cell on the loops: sqrt(segments) cells a side, 4 to 256.
  cells_ = std::clamp<std::size_t>(static_cast<std::size_t>(std::sqrt(static_cast<double>(segments_.size()))), 4, 256);
  in_cell_.assign(cells_ * cells_, {});
  const double hu = (rectangle_.u_last - rectangle_.u_first) / static_cast<double>(cells_);
  const double hv = (rectangle_.v_last - rectangle_.v_first) / static_cast<double>(cells_);
  const auto cell_of = [&](double x, double first, double h) {
    return static_cast<std::size_t>(std::clamp(std::floor((x - first) / h), 0.0, static_cast<double>(cells_ - 1)));
  };
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const Segment& s = segments_[k];
    const std::size_t i0 = cell_of(std::min(s.a.x, s.b.x), rectangle_.u_first, hu);
    const std::size_t i1 = cell_of(std::max(s.a.x, s.b.x), rectangle_.u_first, hu);
    const std::size_t j0 = cell_of(std::min(s.a.y, s.b.y), rectangle_.v_first, hv);
    const std::size_t j1 = cell_of(std::max(s.a.y, s.b.y), rectangle_.v_first, hv);
    for (std::size_t i = i0; i <= i1; ++i) {
      for (std::size_t j = j0; j <= j1; ++j) in_cell_[i * cells_ + j].push_back(k);
    }
  }
  // A cell centre's side by the even-odd rule along a ray towards +t (crossings of segments
  // that straddle its s: one endpoint below, the other at or above).
  centre_inside_.assign(cells_ * cells_, 0);
  for (std::size_t i = 0; i < cells_; ++i) {
    for (std::size_t j = 0; j < cells_; ++j) {
      const Vec2 c = centre(i, j);
      bool inside = false;
      for (const Segment& s : segments_) {
        if ((s.a.y < c.y) == (s.b.y < c.y)) continue;
        const double x = s.a.x + (c.y - s.a.y) * (s.b.x - s.a.x) / (s.b.y - s.a.y);
        if (x > c.x) inside = !inside;
      }
      centre_inside_[i * cells_ + j] = inside ? 1 : 0;
    }
  }
}

// Not quite the middle of the cell: the middles of a grid over a symmetric part fall on the
// vertices of its loops (a ray through a vertex counts once only when the loop is closed
// exactly there).
Vec2 TrimRegion::centre(std::size_t i, std::size_t j) const {
  const double fu = (static_cast<double>(i) + 0.4873) / static_cast<double>(cells_);
  const double fv = (static_cast<double>(j) + 0.5129) / static_cast<double>(cells_);
  return {rectangle_.u_first + fu * (rectangle_.u_last - rectangle_.u_first),
          rectangle_.v_first + fv * (rectangle_.v_last - rectangle_.v_first)};
}

// The path from -> to crosses s where the two lie on opposite sides of each other's lines. A
// segment's end counts on one side only (b's side taken as "left or on"), so where the path
// runs through the vertex between two segments exactly one of them crosses it.
bool TrimRegion::crosses(const Vec2& from, const Vec2& to, const Segment& s) {
  const double oa = orientation(from, to, s.a);
  const double ob = orientation(from, to, s.b);
  if ((oa < 0.0) == (ob < 0.0)) return false;
  const double of = orientation(s.a, s.b, from);
  const double ot = orientation(s.a, s.b, to);
  return (of < 0.0) != (ot < 0.0);
}

bool TrimRegion::contains(double t, double s) const {
  const ParameterRectangle& r = rectangle_;
  if (!(t >= r.u_first && t <= r.u_last && s >= r.v_first && s <= r.v_last)) return false;
  const double hu = (r.u_last - r.u_first) / static_cast<double>(cells_);
  const double hv = (r.v_last - r.v_first) / static_cast<double>(cells_);
  const auto i = std::min(cells_ - 1, static_cast<std::size_t>((t - r.u_first) / hu));
  const auto j = std::min(cells_ - 1, static_cast<std::size_t>((s - r.v_first) / hv));
  const std::size_t cell = i * cells_ + j;
  const Vec2 from = centre(i, j);
  const Vec2 to{t, s};
  bool inside = centre_inside_[cell] != 0;
  for (const std::size_t k : in_cell_[cell]) {
    if (crosses(from, to, segments_[k])) inside = !inside;
  }
  return inside;
}

// Wholly outside: within the rectangle, its middle outside, and no segment's box meeting it
// (the segments of the grid cells it overlaps); then the nearest segment to its middle decides.
bool TrimRegion::excludes(const ParameterRectangle& part) const {
  const ParameterRectangle& r = rectangle_;
  if (part.u_first < r.u_first || part.u_last > r.u_last || part.v_first < r.v_first || part.v_last > r.v_last) {
    return false;
  }
  const Vec2 middle{0.5 * (part.u_first + part.u_last), 0.5 * (part.v_first + part.v_last)};
  if (contains(middle.x, middle.y)) return false;
  const double hu = (r.u_last - r.u_first) / static_cast<double>(cells_);
  const double hv = (r.v_last - r.v_first) / static_cast<double>(cells_);
  const auto cell_of = [&](double x, double first, double h) {
    return static_cast<std::size_t>(std::clamp(std::floor((x - first) / h), 0.0, static_cast<double>(cells_ - 1)));
  };
  for (std::size_t i = cell_of(part.u_first, r.u_first, hu); i <= cell_of(part.u_last, r.u_first, hu); ++i) {
    for (std::size_t j = cell_of(part.v_first, r.v_first, hv); j <= cell_of(part.v_last, r.v_first, hv); ++j) {
      for (const std::size_t k : in_cell_[i * cells_ + j]) {
        const Segment& s = segments_[k];
        if (std::max(s.a.x, s.b.x) >= part.u_first && std::min(s.a.x, s.b.x) <= part.u_last &&
            std::max(s.a.y, s.b.y) >= part.v_first && std::min(s.a.y, s.b.y) <= part.v_last) {
          return false;
        }
      }
    }
  }
  std::size_t nearest = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const Vec2 d = segments_[k].b - segments_[k].a;
    const double length2 = dot(d, d);
    const double f = length2 > 0.0 ? std::clamp(dot(middle - segments_[k].a, d) / length2, 0.0, 1.0) : 0.0;
    const double gap = distance(segments_[k].a + f * d, middle);
    if (gap < best) best = gap, nearest = k;
  }
  return binding_[nearest] != 0;
}

Vec2 curve_point(std::span<const Vec2> q, double x) {
  const std::size_t n = q.size();
  const auto i = std::min(static_cast<std::size_t>(std::max(x, 0.0)), n - 2);
  const double f = x - static_cast<double>(i);
  const Vec2 before = i > 0 ? q[i - 1] : n > 2 ? 3.0 * (q[0] - q[1]) + q[2] : 2.0 * q[0] - q[1];
  const Vec2 after = i + 2 < n ? q[i + 2] : n > 2 ? 3.0 * (q[n - 1] - q[n - 2]) + q[n - 3] : 2.0 * q[n - 1] - q[n - 2];
  const Vec2 m0 = 0.5 * (q[i + 1] - before), m1 = 0.5 * (after - q[i]);
  const double f2 = f * f, f3 = f2 * f;
  return (2.0 * f3 - 3.0 * f2 + 1.0) * q[i] + (f3 - 2.0 * f2 + f) * m0 + (-2.0 * f3 + 3.0 * f2) * q[i + 1] +
         (f3 - f2) * m1;
}

// Golden-section search on |S - p|^2 down to 1e-3 of a span (where it still tells the nearer of
// two points well above rounding), then the secant method on its derivative
// (S - p).(S_t t' + S_s s') within that bracket: the squared distance is flat to rounding over
// sqrt(rounding) of the curve, its derivative is not.
double nearest_on_curve(std::span<const Vec2> q, double a, double b, const Vec3& p,
                        const std::function<SurfaceDerivatives(const Vec2&)>& surface) {
  const auto miss = [&](double x) {
    const Vec3 off = surface(curve_point(q, x)).point - p;
    return dot(off, off);
  };
  constexpr double kGolden = 0.6180339887498949;
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
  double f1 = miss(x1), f2 = miss(x2);
  for (int iteration = 0; b - a > 1e-3 && iteration < 40; ++iteration) {
    if (f1 <= f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - kGolden * (b - a), f1 = miss(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + kGolden * (b - a), f2 = miss(x2);
    }
  }
  const auto slope = [&](double x) {
    constexpr double h = 1e-7;
    const Vec2 tangent = (curve_point(q, x + h) - curve_point(q, x - h)) / (2.0 * h);
    const SurfaceDerivatives d = surface(curve_point(q, x));
    return dot(d.point - p, tangent.x * d.du + tangent.y * d.dv);
  };
  double xa = a, ga = slope(a), xb = b, gb = slope(b);
  if (ga >= 0.0) return a;  // the nearest point is an end of the search
  if (gb <= 0.0) return b;
  double x = f1 <= f2 ? x1 : x2;
  for (int iteration = 0; iteration < 20; ++iteration) {
    x = xa - ga * (xb - xa) / (gb - ga);  // regula falsi, the bracket kept
    const double g = slope(x);
    if (g == 0.0 || xb - xa <= 1e-15 * std::max(1.0, std::abs(x))) break;
    if (g < 0.0) {
      xa = x, ga = g, gb *= 0.5;  // Illinois: the stale end's value halved
    } else {
      xb = x, gb = g, ga *= 0.5;
    }
  }
  return x;
}

bool along_rectangle_side(std::span<const Vec2> points, const ParameterRectangle& r) {
  const double du = kOnSide * (r.u_last - r.u_first), dv = kOnSide * (r.v_last - r.v_first);
  const auto all = [&](auto on) { return std::all_of(points.begin(), points.end(), on); };
  return all([&](const Vec2& p) { return std::abs(p.x - r.u_first) <= du; }) ||
         all([&](const Vec2& p) { return std::abs(p.x - r.u_last) <= du; }) ||
         all([&](const Vec2& p) { return std::abs(p.y - r.v_first) <= dv; }) ||
         all([&](const Vec2& p) { return std::abs(p.y - r.v_last) <= dv; });
}

std::shared_ptr<const TrimRegion> trim_region(const CadFace& face, const std::function<bool(int edge)>& shared) {
  const ParameterRectangle r = face.surface.domain();
  bool trimmed = false;
  std::vector<TrimRegion::Curve> curves;
  for (const TrimCurve& c : face.trims) {
    if (c.points.size() < 2) continue;
    trimmed = trimmed || !along_rectangle_side(c.points, r);
    curves.push_back({c.points, c.edge > 0 && shared(c.edge)});
  }
  if (!trimmed) return nullptr;
  return std::make_shared<const TrimRegion>(std::move(curves), r);
}

}  // namespace hotmesh::geometry
