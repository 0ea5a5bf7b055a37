// hotmesh geometry: clamped (rational) B-spline curves in a plane: validation, de Boor
// evaluation of point and derivatives (eq. 20), and parameter transformations.
// Why not OpenCASCADE's Geom2d_BSplineCurve / BSplCLib: measured by bench_bspline
// (docs/performance.md, "B-spline evaluation"), this evaluation is as fast on short curves and
// 1.3-1.6 times faster on long ones, and OpenCASCADE's differs in the last digits (3e-13),
// which would change every moved mesh in its last bits for no gain.
#include "hotmesh/geometry/bspline_curve.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "spline/bspline_basis.hpp"

namespace hotmesh::geometry {

namespace {

[[noreturn]] void invalid(const std::string& what) {
  throw std::invalid_argument("B-spline curve: " + what);
}

}  // namespace

BSplineCurve2d::BSplineCurve2d(int degree, std::vector<double> knots, std::vector<Vec2> poles,
                               std::vector<double> weights)
    : degree_(degree), knots_(std::move(knots)), poles_(std::move(poles)), weights_(std::move(weights)) {
  if (degree_ < 1 || degree_ > kMaxBSplineDegree) {
    invalid("degree " + std::to_string(degree_) + " is outside 1.." + std::to_string(kMaxBSplineDegree));
  }
  const auto p = static_cast<std::size_t>(degree_);
  if (poles_.size() < p + 1) invalid("needs at least degree + 1 poles");
  if (knots_.size() != poles_.size() + p + 1) invalid("needs poles + degree + 1 knots");
  if (!weights_.empty() && weights_.size() != poles_.size()) invalid("needs one weight per pole");
  for (const double k : knots_) {
    if (!std::isfinite(k)) invalid("knots must be finite");
  }
  for (const Vec2& q : poles_) {
    if (!is_finite(q)) invalid("poles must be finite");
  }
  for (const double w : weights_) {
    if (!(w > 0.0) || !std::isfinite(w)) invalid("weights must be positive and finite");
  }
  if (!std::is_sorted(knots_.begin(), knots_.end())) invalid("knots must be non-decreasing");
  if (knots_[p] != knots_.front() || knots_[poles_.size()] != knots_.back()) invalid("knots must be clamped");
  if (!(first_parameter() < last_parameter())) invalid("parameter range is empty");
  if (!(knots_[p] < knots_[p + 1]) || !(knots_[poles_.size() - 1] < knots_[poles_.size()])) {
    invalid("an end knot has multiplicity above degree + 1");
  }
  for (std::size_t i = p + 1; i < poles_.size(); ++i) {
    if (knots_[i] == knots_[i - p]) invalid("an interior knot has multiplicity above the degree");
  }
}

BSplineCurve2d BSplineCurve2d::polyline(std::span<const double> parameters, std::span<const Vec2> points) {
  if (parameters.size() != points.size() || points.size() < 2) {
    invalid("a polyline needs at least two points, one parameter each");
  }
  for (std::size_t i = 1; i < parameters.size(); ++i) {
    if (!(parameters[i] > parameters[i - 1])) invalid("polyline parameters must increase strictly");
  }
  std::vector<double> knots;
  knots.reserve(points.size() + 2);
  knots.push_back(parameters.front());
  knots.insert(knots.end(), parameters.begin(), parameters.end());
  knots.push_back(parameters.back());
  return BSplineCurve2d(1, std::move(knots), std::vector<Vec2>(points.begin(), points.end()));
}

std::size_t BSplineCurve2d::span_at(double t) const {
  return detail::find_span(knots_, degree_, poles_.size(), t);
}

std::vector<double> BSplineCurve2d::breakpoints() const {
  std::vector<double> result;
  for (std::size_t i = static_cast<std::size_t>(degree_); i <= poles_.size(); ++i) {
    if (result.empty() || knots_[i] != result.back()) result.push_back(knots_[i]);
  }
  return result;
}

Vec2 BSplineCurve2d::point(double t) const { return derivatives(t).point; }

CurveDerivatives2d BSplineCurve2d::derivatives(double t) const {
  const double u = std::clamp(t, first_parameter(), last_parameter());
  return derivatives(u, span_at(u));
}

// Eq. (20) and its derivatives. For a rational curve the homogeneous numerator A(t) =
// sum N_i w_i P_i and denominator w(t) = sum N_i w_i are differentiated, then
// C = A / w, C' = (A' - w' C) / w, C'' = (A'' - 2 w' C' - w'' C) / w.
CurveDerivatives2d BSplineCurve2d::derivatives(double t, std::size_t span) const {
  detail::BasisDerivatives n;
  detail::basis_derivatives(knots_, degree_, span, t, 2, n);
  const auto p = static_cast<std::size_t>(degree_);
  const std::size_t first = span - p;
  Vec2 a[3];
  if (weights_.empty()) {
    for (std::size_t j = 0; j <= p; ++j) {
      const Vec2& q = poles_[first + j];
      for (std::size_t k = 0; k < 3; ++k) a[k] += n[k][j] * q;
    }
    return {a[0], a[1], a[2]};
  }
  double w[3] = {0.0, 0.0, 0.0};
  for (std::size_t j = 0; j <= p; ++j) {
    const double wj = weights_[first + j];
    const Vec2 q = wj * poles_[first + j];
    for (std::size_t k = 0; k < 3; ++k) {
      a[k] += n[k][j] * q;
      w[k] += n[k][j] * wj;
    }
  }
  CurveDerivatives2d d;
  d.point = a[0] / w[0];
  d.first = (a[1] - w[1] * d.point) / w[0];
  d.second = (a[2] - 2.0 * w[1] * d.first - w[2] * d.point) / w[0];
  return d;
}

BSplineCurve2d BSplineCurve2d::reversed() const {
  const double sum = knots_.front() + knots_.back();
  std::vector<double> knots(knots_.size());
  std::transform(knots_.rbegin(), knots_.rend(), knots.begin(), [sum](double k) { return sum - k; });
  std::vector<Vec2> poles(poles_.rbegin(), poles_.rend());
  std::vector<double> weights(weights_.rbegin(), weights_.rend());
  return BSplineCurve2d(degree_, std::move(knots), std::move(poles), std::move(weights));
}

BSplineCurve2d BSplineCurve2d::reparametrized(double first, double last) const {
  if (!(first < last)) invalid("reparametrization needs first < last");
  const double a = knots_.front();
  const double scale = (last - first) / (knots_.back() - a);
  std::vector<double> knots(knots_.size());
  std::transform(knots_.begin(), knots_.end(), knots.begin(),
                 [&](double k) { return first + (k - a) * scale; });
  for (std::size_t i = 0; i <= static_cast<std::size_t>(degree_); ++i) {
    knots[i] = first;
    knots[knots.size() - 1 - i] = last;
  }
  return BSplineCurve2d(degree_, std::move(knots), poles_, weights_);
}

BSplineCurve2d BSplineCurve2d::translated(const Vec2& offset) const {
  std::vector<Vec2> poles(poles_);
  for (Vec2& q : poles) q += offset;
  return BSplineCurve2d(degree_, knots_, std::move(poles), weights_);
}

BSplineCurve2d BSplineCurve2d::swapped_coordinates() const {
  std::vector<Vec2> poles(poles_);
  for (Vec2& q : poles) q = {q.y, q.x};
  return BSplineCurve2d(degree_, knots_, std::move(poles), weights_);
}

}  // namespace hotmesh::geometry
