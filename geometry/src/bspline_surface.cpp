// hotmesh geometry: tensor-product (rational) B-spline surfaces: validation and evaluation.
#include "hotmesh/geometry/bspline_surface.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bspline_basis.hpp"
#include "hotmesh/geometry/bspline_curve.hpp"

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

}  // namespace hotmesh::geometry
