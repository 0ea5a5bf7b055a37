// hotmesh geometry: stages c_lambda(t) = r(t) + lambda D(t) of a deflected curve (sections
// 4.2-4.3): evaluation on pieces for the projection's hot path, and the exact B-spline of a
// stage for export.
#include "hotmesh/geometry/deflected_curve.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "spline/bezier_pieces.hpp"

namespace hotmesh::geometry {

const char* to_string(DeflectionForm form) { return kDeflectionFormNames.name(form).data(); }

DeflectedCurve::DeflectedCurve(BSplineCurve2d undeformed) : undeformed_(std::move(undeformed)) { build_pieces(); }

DeflectedCurve::DeflectedCurve(BSplineCurve2d undeformed, BSplineCurve2d interpolant, DeflectionForm form)
    : undeformed_(std::move(undeformed)), interpolant_(std::move(interpolant)), form_(form) {
  const double a = interpolant_->first_parameter();
  const double b = interpolant_->last_parameter();
  if (a < undeformed_.first_parameter() || b > undeformed_.last_parameter()) {
    throw std::invalid_argument("deflected curve: the interpolant's range must lie inside the curve's");
  }
  const auto end_deflection = [&](double t) {
    const Vec2 value = interpolant_->point(t);
    return form_ == DeflectionForm::curve ? value - undeformed_.point(t) : value;
  };
  deflection_before_ = end_deflection(a);
  deflection_after_ = end_deflection(b);
  build_pieces();
}

double DeflectedCurve::sliver() const { return 1e-12 * (last_parameter() - first_parameter()); }

void DeflectedCurve::build_pieces() {
  std::vector<double> breaks = undeformed_.breakpoints();
  if (interpolant_) {
    const std::vector<double> more = interpolant_->breakpoints();
    breaks.insert(breaks.end(), more.begin(), more.end());
    std::sort(breaks.begin(), breaks.end());
    // Knots of the two curves that differ by rounding only (an FEM node on a CAD knot: a face
    // end, the junction of two faces) would make slivers of pieces that Newton cannot cross:
    // keep one of them (a polynomial piece evaluated that far beyond its span is the same to
    // rounding).
    const double sliver = this->sliver();
    std::vector<double> kept{breaks.front()};
    for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
      if (breaks[i] - kept.back() > sliver && breaks.back() - breaks[i] > sliver) kept.push_back(breaks[i]);
    }
    kept.push_back(breaks.back());
    breaks = std::move(kept);
  }
  pieces_.clear();
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    Piece piece;
    piece.begin = breaks[i];
    piece.end = breaks[i + 1];
    const double mid = 0.5 * (piece.begin + piece.end);
    piece.undeformed_span = undeformed_.span_at(mid);
    if (interpolant_ && mid > interpolant_->first_parameter() && mid < interpolant_->last_parameter()) {
      piece.region = Region::inside;
      piece.interpolant_span = interpolant_->span_at(mid);
    } else if (interpolant_ && mid >= interpolant_->last_parameter()) {
      piece.region = Region::after;
    }
    pieces_.push_back(piece);
  }
}

std::size_t DeflectedCurve::piece_at(double t) const {
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), t,
                                   [](double value, const Piece& piece) { return value < piece.end; });
  return it == pieces_.end() ? pieces_.size() - 1 : static_cast<std::size_t>(it - pieces_.begin());
}

Vec2 DeflectedCurve::deflection(double t) const { return point(t, 1.0) - point(t, 0.0); }

CurveDerivatives2d DeflectedCurve::derivatives(double t, double lambda) const {
  const double u = std::clamp(t, first_parameter(), last_parameter());
  return derivatives(u, lambda, pieces_[piece_at(u)]);
}

// Section 4.3: c_lambda(t) = r(t) + lambda D(t); on the FEM range D = c - r (form curve,
// c from eq. 21) or D = d (form displacement); outside it D is the end value.
CurveDerivatives2d DeflectedCurve::derivatives(double t, double lambda, const Piece& piece) const {
  CurveDerivatives2d r = undeformed_.derivatives(t, piece.undeformed_span);
  switch (piece.region) {
    case Region::before: r.point += lambda * deflection_before_; return r;
    case Region::after: r.point += lambda * deflection_after_; return r;
    case Region::inside: break;
  }
  const CurveDerivatives2d i = interpolant_->derivatives(t, piece.interpolant_span);
  if (form_ == DeflectionForm::displacement) {
    return {r.point + lambda * i.point, r.first + lambda * i.first, r.second + lambda * i.second};
  }
  const double mu = 1.0 - lambda;
  return {mu * r.point + lambda * i.point, mu * r.first + lambda * i.first, mu * r.second + lambda * i.second};
}

namespace {

/// The direction of a curve at a point: its first derivative, or where that vanishes (a cusp
/// of the parametrisation) its second. Zero if both vanish.
Vec2 direction(const CurveDerivatives2d& d) {
  for (const Vec2& v : {d.first, d.second}) {
    const double length = norm(v);
    if (length > 0.0 && std::isfinite(length)) return v / length;
  }
  return {0.0, 0.0};
}

}  // namespace

std::vector<ShapeFeature> DeflectedCurve::corners(double min_angle) const {
  std::vector<ShapeFeature> found;
  for (std::size_t k = 0; k + 1 < pieces_.size(); ++k) {
    const double t = pieces_[k].end;
    const auto turn = [&](double lambda) {
      const Vec2 before = direction(derivatives(t, lambda, pieces_[k]));
      const Vec2 after = direction(derivatives(t, lambda, pieces_[k + 1]));
      return std::atan2(std::abs(cross(before, after)), dot(before, after));
    };
    const double undeformed = turn(0.0);
    const double angle = std::max(undeformed, turn(1.0));
    if (angle >= min_angle) found.push_back({t, angle, undeformed});
  }
  return found;
}

BSplineCurve2d DeflectedCurve::stage(double lambda) const {
  if (!interpolant_ || lambda == 0.0) return undeformed_;
  std::vector<double> breaks;
  breaks.reserve(pieces_.size() + 1);
  breaks.push_back(pieces_.front().begin);
  for (const Piece& piece : pieces_) breaks.push_back(piece.end);

  // Breaks are more than a sliver apart and each knot build_pieces dropped lies within a
  // sliver of a kept one, so a piece's own ends lie within two slivers of its breaks.
  const double snap = 2 * sliver();
  const std::vector<detail::BezierPiece> r = detail::bezier_pieces(undeformed_, breaks, snap);
  const auto inside_begin = static_cast<std::ptrdiff_t>(
      std::find_if(pieces_.begin(), pieces_.end(), [](const Piece& p) { return p.region == Region::inside; }) -
      pieces_.begin());
  const auto inside_end = static_cast<std::ptrdiff_t>(
      std::find_if(pieces_.begin(), pieces_.end(), [](const Piece& p) { return p.region == Region::after; }) -
      pieces_.begin());
  const std::vector<double> inner_breaks(breaks.begin() + inside_begin, breaks.begin() + inside_end + 1);
  const std::vector<detail::BezierPiece> c = detail::bezier_pieces(*interpolant_, inner_breaks, snap);

  std::vector<detail::BezierPiece> result;
  result.reserve(pieces_.size());
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    const detail::BezierPiece& rk = r[k];
    if (pieces_[k].region != Region::inside) {
      // Rigid translation by lambda D_end: homogeneous poles move by w_i lambda D_end.
      const Vec2 shift = lambda * (pieces_[k].region == Region::before ? deflection_before_ : deflection_after_);
      detail::BezierPiece moved = rk;
      for (std::size_t i = 0; i < moved.weights.size(); ++i) moved.weighted_poles[i] += moved.weights[i] * shift;
      result.push_back(std::move(moved));
      continue;
    }
    const detail::BezierPiece& ck = c[k - static_cast<std::size_t>(inside_begin)];
    // Numerator of c_lambda = (A + lambda w d) / w (displacement form) or
    // ((1 - lambda) A + lambda w c) / w (curve form), with A, w the homogeneous form of r.
    const detail::BezierPiece wc = undeformed_.is_rational() ? detail::weight_times(rk, ck) : ck;
    const int degree = std::max(rk.degree(), wc.degree());
    detail::BezierPiece a = detail::elevated(rk, degree);
    const detail::BezierPiece b = detail::elevated(wc, degree);
    const double mu = form_ == DeflectionForm::curve ? 1.0 - lambda : 1.0;
    for (std::size_t i = 0; i < a.weights.size(); ++i) {
      a.weighted_poles[i] = mu * a.weighted_poles[i] + lambda * b.weighted_poles[i];
    }
    result.push_back(std::move(a));
  }
  return detail::join_pieces(result, breaks);
}

}  // namespace hotmesh::geometry
