// hotmesh geometry: the stages of a deflected boundary curve (sections 4.2 and 4.3).
//
// r(t) is the undeformed curve (from CAD, or the polyline through the FEM nodes). The FEM
// nodes cover the parameter range [t_1, t_k]; on it the reconstruction gives an interpolant:
//   form curve:        c(t) interpolates Q_j + delta_j              (eq. 21, the paper's form)
//   form displacement: d(t) interpolates delta_j, and c(t) = r(t) + d(t)
// The deflection D(t) = c(t) - r(t) is held constant beyond the FEM range: for t < t_1,
// D(t) = D(t_1); for t > t_k, D(t) = D(t_k) (the part of the curve that no node covers moves
// rigidly with its nearest node). The stage lambda in [0, 1] of an increment is
//   c_lambda(t) = r(t) + lambda D(t)        (section 4.3, partial shapes)
// so c_0 = r and c_1 = c. A curve without deflection has c_lambda = r for every lambda.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/geometry/bspline_curve.hpp"
#include "hotmesh/core/enum_names.hpp"

namespace hotmesh::geometry {

enum class DeflectionForm {
  curve,         ///< c(t) interpolates Q_j + delta_j (eq. 21)
  displacement,  ///< d(t) interpolates delta_j; c(t) = r(t) + d(t) keeps the CAD curvature
};

/// The names the case file, the service and restart files use.
inline constexpr EnumNames<DeflectionForm, 2> kDeflectionFormNames{
    {{{DeflectionForm::curve, "curve"}, {DeflectionForm::displacement, "displacement"}}}};
const char* to_string(DeflectionForm form);

class DeflectedCurve {
 public:
  enum class Region : unsigned char { before, inside, after };

  /// A parameter interval on which every stage is a single polynomial (or rational) piece:
  /// between consecutive knots of r and of the interpolant and the ends of the FEM range.
  /// The spans let the hot path evaluate without searching.
  struct Piece {
    double begin = 0.0;
    double end = 0.0;
    std::size_t undeformed_span = 0;
    std::size_t interpolant_span = 0;  ///< meaningful for Region::inside only
    Region region = Region::before;
  };

  /// A curve that does not deflect: every stage is `undeformed`.
  explicit DeflectedCurve(BSplineCurve2d undeformed);
  /// `interpolant` is c(t) (form curve) or d(t) (form displacement); its parameter range is
  /// the FEM range and must lie inside the range of `undeformed`, else std::invalid_argument.
  DeflectedCurve(BSplineCurve2d undeformed, BSplineCurve2d interpolant, DeflectionForm form);

  const BSplineCurve2d& undeformed() const { return undeformed_; }
  /// c(t) or d(t) on the FEM range; empty for a curve without deflection.
  const std::optional<BSplineCurve2d>& interpolant() const { return interpolant_; }
  DeflectionForm form() const { return form_; }

  double first_parameter() const { return undeformed_.first_parameter(); }
  double last_parameter() const { return undeformed_.last_parameter(); }

  const std::vector<Piece>& pieces() const { return pieces_; }
  /// Index of the piece that holds t (t clamped to the parameter range).
  std::size_t piece_at(double t) const;

  /// D(t) = c_1(t) - r(t).
  Vec2 deflection(double t) const;
  Vec2 point(double t, double lambda) const { return derivatives(t, lambda).point; }
  /// c_lambda and its first two derivatives at t (clamped to the parameter range).
  CurveDerivatives2d derivatives(double t, double lambda) const;
  /// Same, on a given piece (one-sided at its ends); for the hot path. No clamping.
  CurveDerivatives2d derivatives(double t, double lambda, const Piece& piece) const;

  /// The corners: the piece ends where c_0 or c_1 turns by at least `min_angle` (radians)
  /// between its one-sided tangents. Every C0 point of any stage is a piece end (a knot of r
  /// or of the interpolant, or an end of the FEM range), and c_lambda is affine in lambda, so
  /// these are the kinks of the FEM table, the CAD vertices and the full-multiplicity knots.
  std::vector<ShapeFeature> corners(double min_angle) const;

  /// c_lambda as one exact B-spline over the whole parameter range, C0 at the piece ends.
  /// Rational if r is; its degree is max(p, q) for a polynomial r of degree p and p + q for
  /// a rational one (the weight function multiplies the deflection).
  BSplineCurve2d stage(double lambda) const;

 private:
  void build_pieces();
  /// Parameter distance below which two knots are the same knot up to rounding.
  double sliver() const;

  BSplineCurve2d undeformed_;
  std::optional<BSplineCurve2d> interpolant_;
  DeflectionForm form_ = DeflectionForm::curve;
  Vec2 deflection_before_;  // D(t_1)
  Vec2 deflection_after_;   // D(t_k)
  std::vector<Piece> pieces_;
};

}  // namespace hotmesh::geometry
