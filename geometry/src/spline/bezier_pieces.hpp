// hotmesh geometry (internal): exact B-spline algebra through Bezier pieces. A (rational)
// B-spline is split at given breakpoints into Bezier pieces in homogeneous form; pieces can be
// degree-elevated, multiplied by a scalar polynomial piece and joined back into one B-spline
// (C0 at the breakpoints). Used to write the partial shapes c_lambda(t) as exact B-splines.
#pragma once

#include <span>
#include <vector>

#include "hotmesh/geometry/bspline_curve.hpp"

namespace hotmesh::geometry::detail {

/// One Bezier piece: homogeneous poles w_i P_i and weights w_i (all 1 for polynomial pieces).
struct BezierPiece {
  std::vector<Vec2> weighted_poles;
  std::vector<double> weights;

  int degree() const { return static_cast<int>(weights.size()) - 1; }
};

/// The Bezier pieces of `curve` between consecutive `breaks` (strictly increasing, more than
/// `snap` apart). Every knot of the curve between the first and last break, and each end of
/// the curve, is a break or lies within `snap` of one (knots of two curves, or a curve end and
/// an FEM node, that differ by rounding): the piece is then the curve's polynomial piece that
/// holds most of the interval, to be read on [breaks[i], breaks[i + 1]].
std::vector<BezierPiece> bezier_pieces(const BSplineCurve2d& curve, std::span<const double> breaks, double snap);

/// The same piece written with degree `degree` (>= its own).
BezierPiece elevated(const BezierPiece& piece, int degree);

/// The polynomial product of the piece's weight function w(t) (degree p) with the polynomial
/// piece b (degree q): the homogeneous piece of w(t) b(t), of degree p + q, with weights w.
BezierPiece weight_times(const BezierPiece& piece, const BezierPiece& b);

/// One B-spline made of `pieces` (any degrees, elevated to the highest) joined at `breaks`
/// (pieces.size() + 1 values). Rational if any weight differs from 1.
BSplineCurve2d join_pieces(std::span<const BezierPiece> pieces, std::span<const double> breaks);

}  // namespace hotmesh::geometry::detail
