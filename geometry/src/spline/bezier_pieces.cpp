// hotmesh geometry (internal): Bezier extraction by knot insertion (Boehm), degree elevation
// and products of Bezier polynomials (The NURBS Book, sections 5.2, 5.5 and 5.6), all in
// homogeneous coordinates so rational curves stay exact.
// Why not OpenCASCADE (BSplCLib::InsertKnots, Geom2dConvert_BSplineCurveToBezierCurve,
// Geom2d_BezierCurve::Increase): it would replace the split and the elevation only. The snapping
// of knots that lie within rounding of an FEM node, the product of a weight function with a
// polynomial piece and the C0 join have no counterpart there. What it could replace runs once
// per wall at set-up: building every deflected wall from its table takes 2 ms of the 4.5 s
// sliding ramp and 15 ms of the 170 s small stator well (report.json seconds.shapes), and the
// swap would move every deflected curve, and so every mesh, in its last bits.
#include "spline/bezier_pieces.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hotmesh::geometry::detail {

namespace {

struct Homogeneous {
  double x, y, w;
};

Homogeneous lerp(const Homogeneous& a, const Homogeneous& b, double alpha) {
  return {alpha * b.x + (1 - alpha) * a.x, alpha * b.y + (1 - alpha) * a.y, alpha * b.w + (1 - alpha) * a.w};
}

/// Inserts knot u once (Boehm's algorithm) into a flat knot vector of degree p.
void insert_knot(std::vector<double>& knots, std::vector<Homogeneous>& poles, std::size_t p, double u) {
  // Span k with knots[k] <= u < knots[k+1] (u is strictly inside the parameter range).
  const auto it = std::upper_bound(knots.begin(), knots.end(), u);
  const auto k = static_cast<std::size_t>(it - knots.begin()) - 1;
  std::vector<Homogeneous> result(poles.size() + 1);
  for (std::size_t i = 0; i < result.size(); ++i) {
    if (i + p <= k) {
      result[i] = poles[i];
    } else if (i > k) {
      result[i] = poles[i - 1];
    } else {
      const double alpha = (u - knots[i]) / (knots[i + p] - knots[i]);
      result[i] = lerp(poles[i - 1], poles[i], alpha);
    }
  }
  knots.insert(knots.begin() + static_cast<std::ptrdiff_t>(k + 1), u);
  poles = std::move(result);
}

double binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

}  // namespace

std::vector<BezierPiece> bezier_pieces(const BSplineCurve2d& curve, std::span<const double> breaks, double snap) {
  const auto p = static_cast<std::size_t>(curve.degree());
  std::vector<double> knots = curve.knots();
  std::vector<Homogeneous> poles(curve.poles().size());
  for (std::size_t i = 0; i < poles.size(); ++i) {
    const double w = curve.is_rational() ? curve.weights()[i] : 1.0;
    poles[i] = {w * curve.poles()[i].x, w * curve.poles()[i].y, w};
  }
  // Raise every break to multiplicity p (the ends of the curve already have p + 1).
  for (const double b : breaks) {
    if (b <= curve.first_parameter() || b >= curve.last_parameter()) continue;
    const auto mult = static_cast<std::size_t>(std::count(knots.begin(), knots.end(), b));
    for (std::size_t m = mult; m < p; ++m) insert_knot(knots, poles, p, b);
  }
  // Now the pole groups between consecutive distinct knots are the Bezier pieces. A knot that
  // is not a break lies within `snap` of one (a curve end or a knot of another curve that
  // differs by rounding): the piece holding the interval's middle stands for the interval.
  std::vector<BezierPiece> pieces;
  pieces.reserve(breaks.size() - 1);
  for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
    const double mid = 0.5 * (breaks[b] + breaks[b + 1]);
    const auto it = std::upper_bound(knots.begin(), knots.end(), mid);
    const auto span = std::clamp<std::size_t>(static_cast<std::size_t>(it - knots.begin()), p + 1, poles.size()) - 1;
    if (std::abs(knots[span] - breaks[b]) > snap || std::abs(knots[span + 1] - breaks[b + 1]) > snap) {
      throw std::logic_error("bezier_pieces: a knot of the curve lies between two breaks");
    }
    BezierPiece piece;
    for (std::size_t i = span - p; i <= span; ++i) {
      piece.weighted_poles.push_back({poles[i].x, poles[i].y});
      piece.weights.push_back(poles[i].w);
    }
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

BezierPiece elevated(const BezierPiece& piece, int degree) {
  BezierPiece result = piece;
  for (int n = piece.degree(); n < degree; ++n) {
    BezierPiece next;
    const auto un = static_cast<std::size_t>(n);
    next.weighted_poles.resize(un + 2);
    next.weights.resize(un + 2);
    next.weighted_poles[0] = result.weighted_poles[0];
    next.weights[0] = result.weights[0];
    for (std::size_t i = 1; i <= un; ++i) {
      const double a = static_cast<double>(i) / (n + 1);
      next.weighted_poles[i] = a * result.weighted_poles[i - 1] + (1 - a) * result.weighted_poles[i];
      next.weights[i] = a * result.weights[i - 1] + (1 - a) * result.weights[i];
    }
    next.weighted_poles[un + 1] = result.weighted_poles[un];
    next.weights[un + 1] = result.weights[un];
    result = std::move(next);
  }
  return result;
}

BezierPiece weight_times(const BezierPiece& piece, const BezierPiece& b) {
  const int p = piece.degree();
  const int q = b.degree();
  BezierPiece result;
  result.weighted_poles.assign(static_cast<std::size_t>(p + q + 1), Vec2{});
  result.weights = elevated(piece, p + q).weights;
  for (int i = 0; i <= p; ++i) {
    for (int j = 0; j <= q; ++j) {
      const double c = binomial(p, i) * binomial(q, j) / binomial(p + q, i + j);
      // b is polynomial: its homogeneous poles are its poles.
      result.weighted_poles[static_cast<std::size_t>(i + j)] +=
          c * piece.weights[static_cast<std::size_t>(i)] * b.weighted_poles[static_cast<std::size_t>(j)];
    }
  }
  return result;
}

BSplineCurve2d join_pieces(std::span<const BezierPiece> pieces, std::span<const double> breaks) {
  if (pieces.empty() || breaks.size() != pieces.size() + 1) {
    throw std::logic_error("join_pieces: one break more than pieces needed");
  }
  int degree = 1;
  bool rational = false;
  for (const BezierPiece& piece : pieces) {
    degree = std::max(degree, piece.degree());
    for (const double w : piece.weights) rational = rational || w != 1.0;
  }
  const auto p = static_cast<std::size_t>(degree);
  std::vector<double> knots(p + 1, breaks.front());
  std::vector<Vec2> poles;
  std::vector<double> weights;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const BezierPiece piece = elevated(pieces[k], degree);
    for (std::size_t i = 0; i <= p; ++i) {
      const Vec2 pole = piece.weighted_poles[i] / piece.weights[i];
      if (k > 0 && i == 0) {
        // Shared end pole of two pieces: equal up to rounding; keep the mean.
        poles.back() = 0.5 * (poles.back() + pole);
        weights.back() = 0.5 * (weights.back() + piece.weights[i]);
        continue;
      }
      poles.push_back(pole);
      weights.push_back(piece.weights[i]);
    }
    const std::size_t multiplicity = k + 1 < pieces.size() ? p : p + 1;
    knots.insert(knots.end(), multiplicity, breaks[k + 1]);
  }
  if (!rational) weights.clear();
  return BSplineCurve2d(degree, std::move(knots), std::move(poles), std::move(weights));
}

}  // namespace hotmesh::geometry::detail
