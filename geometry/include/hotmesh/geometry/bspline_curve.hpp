// hotmesh geometry: a clamped B-spline (optionally rational, NURBS) curve in a plane, the
// paper's eq. (20) r(t) = sum_i N_i^p(t) P_i, with de Boor evaluation of the point and its
// first two derivatives. Meridional curves (r, z), 2D boundary curves (x, y), deflected curves
// and displacement curves are all of this type. Evaluation is const, allocation-free and
// thread-safe: it is the inner loop of every projection.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "hotmesh/core/vec2.hpp"

namespace hotmesh::geometry {

/// OpenCASCADE's limit, so every curve read from a CAD file fits.
inline constexpr int kMaxBSplineDegree = 25;

/// A point of a curve with its first and second derivatives with respect to the parameter.
struct CurveDerivatives2d {
  Vec2 point;
  Vec2 first;
  Vec2 second;
};

class BSplineCurve2d {
 public:
  /// `knots` is the flat (full) knot vector, clamped: its first and last degree + 1 values
  /// are equal, it is non-decreasing, interior multiplicities are at most `degree`, and
  /// knots.size() == poles.size() + degree + 1. `weights` is empty (polynomial curve) or one
  /// positive weight per pole (rational curve). Throws std::invalid_argument otherwise.
  BSplineCurve2d(int degree, std::vector<double> knots, std::vector<Vec2> poles,
                 std::vector<double> weights = {});

  /// The degree-1 curve through `points` with parameter `parameters[i]` at points[i]
  /// (strictly increasing parameters, at least two points).
  static BSplineCurve2d polyline(std::span<const double> parameters, std::span<const Vec2> points);

  int degree() const { return degree_; }
  const std::vector<double>& knots() const { return knots_; }
  const std::vector<Vec2>& poles() const { return poles_; }
  const std::vector<double>& weights() const { return weights_; }  ///< empty if polynomial
  bool is_rational() const { return !weights_.empty(); }
  double first_parameter() const { return knots_[static_cast<std::size_t>(degree_)]; }
  double last_parameter() const { return knots_[poles_.size()]; }

  /// Index i of the knot span [knots[i], knots[i+1]) that holds t (the last non-empty span
  /// for t >= last_parameter(), the first for t <= first_parameter()).
  std::size_t span_at(double t) const;
  /// The distinct knot values from first_parameter() to last_parameter(): the parameters
  /// where the curve may be less smooth than its degree allows.
  std::vector<double> breakpoints() const;

  Vec2 point(double t) const;
  /// Point and derivatives at t, clamped to the parameter range.
  CurveDerivatives2d derivatives(double t) const;
  /// Same, with the knot span given: the polynomial piece of that span is evaluated, so at a
  /// knot the one-sided derivatives of either neighbouring span are available. No clamping.
  CurveDerivatives2d derivatives(double t, std::size_t span) const;

  /// The same curve traversed the other way: parameter t maps to first + last - t.
  BSplineCurve2d reversed() const;
  /// The same curve with its parameter mapped affinely onto [first, last] (first < last).
  BSplineCurve2d reparametrized(double first, double last) const;
  /// The curve moved by `offset`.
  BSplineCurve2d translated(const Vec2& offset) const;
  /// The curve with its two coordinates exchanged, (a, b) -> (b, a): a meridional curve (r, z)
  /// in the plane of a 2D axisymmetric mesh, whose (x, y) are (z, r).
  BSplineCurve2d swapped_coordinates() const;

 private:
  int degree_;
  std::vector<double> knots_;
  std::vector<Vec2> poles_;
  std::vector<double> weights_;
};

}  // namespace hotmesh::geometry
