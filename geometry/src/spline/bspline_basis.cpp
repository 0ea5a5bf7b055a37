// hotmesh geometry (internal): B-spline basis functions and derivatives (The NURBS Book,
// algorithms A2.1 and A2.3, restated for at most second derivatives).
#include "spline/bspline_basis.hpp"

#include <algorithm>

namespace hotmesh::geometry::detail {

std::size_t find_span(std::span<const double> knots, int degree, std::size_t pole_count, double t) {
  const auto p = static_cast<std::size_t>(degree);
  // First knot strictly greater than t among knots[p+1 .. n]; the span starts one before it.
  const auto first = knots.begin() + static_cast<std::ptrdiff_t>(p + 1);
  const auto last = knots.begin() + static_cast<std::ptrdiff_t>(pole_count);
  const auto it = std::upper_bound(first, last, t);
  return static_cast<std::size_t>(it - knots.begin()) - 1;
}

void basis_derivatives(std::span<const double> knots, int degree, std::size_t span, double t, int order,
                       BasisDerivatives& ders) {
  const auto p = static_cast<std::size_t>(degree);
  // ndu[j][r], r <= j: knot differences (lower triangle); ndu[r][j], r <= j: basis functions
  // of degree j (upper triangle, including the diagonal).
  double ndu[kMaxOrder][kMaxOrder];
  double left[kMaxOrder];
  double right[kMaxOrder];
  ndu[0][0] = 1.0;
  for (std::size_t j = 1; j <= p; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (std::size_t r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (std::size_t j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];

  const int top = std::min(order, degree);
  for (int k = top + 1; k <= order; ++k) {
    for (std::size_t j = 0; j <= p; ++j) ders[static_cast<std::size_t>(k)][j] = 0.0;
  }
  if (top == 0) return;

  // Derivatives: coefficients a[s][j] of the k-th derivative as a combination of degree p-k
  // basis functions, built row by row from the (k-1)-th (two alternating rows).
  double a[2][kMaxOrder];
  const int ip = degree;
  for (int r = 0; r <= ip; ++r) {
    int s1 = 0;
    int s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= top; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = ip - k;
      const auto upk1 = static_cast<std::size_t>(pk + 1);
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[upk1][static_cast<std::size_t>(rk)];
        d = a[s2][0] * ndu[static_cast<std::size_t>(rk)][static_cast<std::size_t>(pk)];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : ip - r;
      for (int j = j1; j <= j2; ++j) {
        const auto uj = static_cast<std::size_t>(j);
        const auto urkj = static_cast<std::size_t>(rk + j);
        a[s2][uj] = (a[s1][uj] - a[s1][uj - 1]) / ndu[upk1][urkj];
        d += a[s2][uj] * ndu[urkj][static_cast<std::size_t>(pk)];
      }
      if (r <= pk) {
        const auto uk = static_cast<std::size_t>(k);
        a[s2][uk] = -a[s1][uk - 1] / ndu[upk1][static_cast<std::size_t>(r)];
        d += a[s2][uk] * ndu[static_cast<std::size_t>(r)][static_cast<std::size_t>(pk)];
      }
      ders[static_cast<std::size_t>(k)][static_cast<std::size_t>(r)] = d;
      std::swap(s1, s2);
    }
  }
  double factor = ip;
  for (int k = 1; k <= top; ++k) {
    for (std::size_t j = 0; j <= p; ++j) ders[static_cast<std::size_t>(k)][j] *= factor;
    factor *= ip - k;
  }
}

}  // namespace hotmesh::geometry::detail
