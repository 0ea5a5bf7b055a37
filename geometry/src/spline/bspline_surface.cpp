// hotmesh geometry: tensor-product (rational) B-spline surfaces: validation, evaluation of the
// point and of its derivatives up to second order.
#include "hotmesh/geometry/bspline_surface.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "hotmesh/geometry/bspline_curve.hpp"
#include "spline/bspline_basis.hpp"

namespace hotmesh::geometry {

namespace {

/// Knot vectors are checked by building a curve on them: the same rules apply.
void check_knots(int degree, const std::vector<double>& knots) {
  if (degree < 1 || knots.size() < 2 * static_cast<std::size_t>(degree) + 2) {
    throw std::invalid_argument("B-spline surface: degree or knot count out of range");
  }
  const std::size_t count = knots.size() - static_cast<std::size_t>(degree) - 1;
  BSplineCurve2d(degree, knots, std::vector<Vec2>(count));
}

/// A homogeneous point (w x, w y, w z, w), or a derivative of one.
struct Weighted {
  Vec3 xyz;
  double w = 0.0;
};

std::vector<double> distinct_knots(const std::vector<double>& knots, double first, double last) {
  std::vector<double> out;
  for (const double t : knots) {
    if (t >= first && t <= last && (out.empty() || t > out.back())) out.push_back(t);
  }
  return out;
}

}  // namespace

BSplineSurface::BSplineSurface(int u_degree, int v_degree, std::vector<double> u_knots, std::vector<double> v_knots,
                               std::vector<Vec3> poles, std::vector<double> weights)
    : u_degree_(u_degree), v_degree_(v_degree), u_knots_(std::move(u_knots)), v_knots_(std::move(v_knots)),
      poles_(std::move(poles)), weights_(std::move(weights)) {
  check_knots(u_degree_, u_knots_);
  check_knots(v_degree_, v_knots_);
  if (poles_.size() != u_count() * v_count()) throw std::invalid_argument("B-spline surface: wrong pole count");
  if (!weights_.empty() && weights_.size() != poles_.size()) {
    throw std::invalid_argument("B-spline surface: needs one weight per pole");
  }
  for (const double w : weights_) {
    if (!(w > 0.0) || !std::isfinite(w)) throw std::invalid_argument("B-spline surface: weights must be positive");
  }
  for (const Vec3& p : poles_) {
    if (!is_finite(p)) throw std::invalid_argument("B-spline surface: poles must be finite");
  }
}

Vec3 BSplineSurface::point(double u, double v) const {
  const double uu = std::clamp(u, u_first(), u_last());
  const double vv = std::clamp(v, v_first(), v_last());
  const std::size_t us = detail::find_span(u_knots_, u_degree_, u_count(), uu);
  const std::size_t vs = detail::find_span(v_knots_, v_degree_, v_count(), vv);
  detail::BasisDerivatives nu;
  detail::BasisDerivatives nv;
  detail::basis_derivatives(u_knots_, u_degree_, us, uu, 0, nu);
  detail::basis_derivatives(v_knots_, v_degree_, vs, vv, 0, nv);
  Vec3 sum;
  double weight = 0.0;
  for (std::size_t i = 0; i <= static_cast<std::size_t>(u_degree_); ++i) {
    for (std::size_t j = 0; j <= static_cast<std::size_t>(v_degree_); ++j) {
      const std::size_t k = (us - static_cast<std::size_t>(u_degree_) + i) * v_count() +
                            (vs - static_cast<std::size_t>(v_degree_) + j);
      const double w = (weights_.empty() ? 1.0 : weights_[k]) * nu[0][i] * nv[0][j];
      sum += w * poles_[k];
      weight += w;
    }
  }
  return sum / weight;
}

// Derivatives of a rational surface (The NURBS Book, eq. 4.20 and algorithm A4.4, restated for
// derivatives up to second order). With N_i(u), M_j(v) the basis functions and w_ij the weights,
//   A(u, v) = sum_ij N_i M_j w_ij P_ij,   w(u, v) = sum_ij N_i M_j w_ij,   S = A / w.
// Differentiating A = w S and solving for the derivatives of S:
//   S_u  = (A_u - w_u S) / w,                  S_v  = (A_v - w_v S) / w,
//   S_uu = (A_uu - 2 w_u S_u - w_uu S) / w,    S_vv = (A_vv - 2 w_v S_v - w_vv S) / w,
//   S_uv = (A_uv - w_u S_v - w_v S_u - w_uv S) / w.
// A polynomial surface has w = 1 and S = A. The tensor sums run one direction at a time: for
// each row i the sums over j with M, M', M'', then those over i with N, N', N''.
SurfaceDerivatives BSplineSurface::derivatives(double u, double v) const {
  return continued_derivatives(std::clamp(u, u_first(), u_last()), std::clamp(v, v_first(), v_last()));
}

// Beyond the rectangle the spans at its edges are the nearest (find_span), and the basis
// functions of a span are the polynomials of that span at any parameter: the end pieces go on.
SurfaceDerivatives BSplineSurface::continued_derivatives(double uu, double vv) const {
  const std::size_t us = detail::find_span(u_knots_, u_degree_, u_count(), uu);
  const std::size_t vs = detail::find_span(v_knots_, v_degree_, v_count(), vv);
  detail::BasisDerivatives nu;
  detail::BasisDerivatives nv;
  detail::basis_derivatives(u_knots_, u_degree_, us, uu, 2, nu);
  detail::basis_derivatives(v_knots_, v_degree_, vs, vv, 2, nv);
  const auto p = static_cast<std::size_t>(u_degree_);
  const auto q = static_cast<std::size_t>(v_degree_);
  Weighted a[3][3] = {};  // a[k][l]: derivative k times in u and l times in v
  for (std::size_t i = 0; i <= p; ++i) {
    Weighted row[3] = {};
    for (std::size_t j = 0; j <= q; ++j) {
      const std::size_t k = (us - p + i) * v_count() + (vs - q + j);
      const double w = weights_.empty() ? 1.0 : weights_[k];
      for (std::size_t l = 0; l < 3; ++l) {
        row[l].xyz += (nv[l][j] * w) * poles_[k];
        row[l].w += nv[l][j] * w;
      }
    }
    for (std::size_t l = 0; l < 3; ++l) {
      for (std::size_t k = 0; k + l < 3; ++k) {
        a[k][l].xyz += nu[k][i] * row[l].xyz;
        a[k][l].w += nu[k][i] * row[l].w;
      }
    }
  }
  if (weights_.empty()) return {a[0][0].xyz, a[1][0].xyz, a[0][1].xyz, a[2][0].xyz, a[1][1].xyz, a[0][2].xyz};
  const double w = a[0][0].w;
  SurfaceDerivatives d;
  d.point = a[0][0].xyz / w;
  d.du = (a[1][0].xyz - a[1][0].w * d.point) / w;
  d.dv = (a[0][1].xyz - a[0][1].w * d.point) / w;
  d.duu = (a[2][0].xyz - 2.0 * a[1][0].w * d.du - a[2][0].w * d.point) / w;
  d.duv = (a[1][1].xyz - a[1][0].w * d.dv - a[0][1].w * d.du - a[1][1].w * d.point) / w;
  d.dvv = (a[0][2].xyz - 2.0 * a[0][1].w * d.dv - a[0][2].w * d.point) / w;
  return d;
}

std::vector<double> BSplineSurface::u_breakpoints() const { return distinct_knots(u_knots_, u_first(), u_last()); }
std::vector<double> BSplineSurface::v_breakpoints() const { return distinct_knots(v_knots_, v_first(), v_last()); }

}  // namespace hotmesh::geometry
