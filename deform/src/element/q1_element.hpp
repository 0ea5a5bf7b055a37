// hotmesh deform (internal): the bilinear quad (quad4, d = 2) and trilinear hex (hex8, d = 3)
// of the paper's eq. (29): N_a = 2^-d prod_k (1 + xi_k xi_k^a), corners in Gmsh order, and
// 2-point Gauss-Legendre rules (all weights 1) as in eq. (30) with n = 2.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform::detail {

template <std::size_t D>
struct Q1 {
  static constexpr std::size_t kNodes = std::size_t{1} << D;
  static constexpr std::size_t kDofs = kNodes * D;
  using Point = std::array<double, D>;
  using Matrix = std::array<std::array<double, D>, D>;

  /// Reference coordinates xi^a of the corners.
  static constexpr std::array<Point, kNodes> corners() {
    if constexpr (D == 2) {
      return {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
    } else {
      return {{{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}};
    }
  }

  /// dN_a / dxi_k at xi.
  static std::array<Point, kNodes> reference_gradients(const Point& xi) {
    std::array<Point, kNodes> g{};
    const auto c = corners();
    for (std::size_t a = 0; a < kNodes; ++a) {
      for (std::size_t k = 0; k < D; ++k) {
        double v = c[a][k] / static_cast<double>(kNodes);
        for (std::size_t m = 0; m < D; ++m) {
          if (m != k) v *= 1.0 + xi[m] * c[a][m];
        }
        g[a][k] = v;
      }
    }
    return g;
  }

  /// Gauss points of the 2^d rule.
  static std::array<Point, kNodes> gauss_points() {
    const double s = 1.0 / std::sqrt(3.0);
    auto c = corners();
    for (auto& p : c) {
      for (auto& v : p) v *= s;
    }
    return c;
  }

  /// J_ik = sum_a x^a_i dN_a/dxi_k.
  static Matrix jacobian(const ElementPoints& e, const std::array<Point, kNodes>& dn) {
    Matrix j{};
    for (std::size_t a = 0; a < kNodes; ++a) {
      for (std::size_t i = 0; i < D; ++i) {
        for (std::size_t k = 0; k < D; ++k) j[i][k] += e.p[a][i] * dn[a][k];
      }
    }
    return j;
  }

  static double determinant(const Matrix& j) {
    if constexpr (D == 2) {
      return j[0][0] * j[1][1] - j[0][1] * j[1][0];
    } else {
      return j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1]) - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0]) +
             j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
    }
  }

  static Matrix inverse(const Matrix& j, double det) {
    Matrix r{};
    if constexpr (D == 2) {
      r = {{{j[1][1] / det, -j[0][1] / det}, {-j[1][0] / det, j[0][0] / det}}};
    } else {
      r[0][0] = (j[1][1] * j[2][2] - j[1][2] * j[2][1]) / det;
      r[0][1] = (j[0][2] * j[2][1] - j[0][1] * j[2][2]) / det;
      r[0][2] = (j[0][1] * j[1][2] - j[0][2] * j[1][1]) / det;
      r[1][0] = (j[1][2] * j[2][0] - j[1][0] * j[2][2]) / det;
      r[1][1] = (j[0][0] * j[2][2] - j[0][2] * j[2][0]) / det;
      r[1][2] = (j[0][2] * j[1][0] - j[0][0] * j[1][2]) / det;
      r[2][0] = (j[1][0] * j[2][1] - j[1][1] * j[2][0]) / det;
      r[2][1] = (j[0][1] * j[2][0] - j[0][0] * j[2][1]) / det;
      r[2][2] = (j[0][0] * j[1][1] - j[0][1] * j[1][0]) / det;
    }
    return r;
  }

  static double frobenius(const Matrix& m) {
    double s = 0.0;
    for (const auto& row : m) {
      for (double v : row) s += v * v;
    }
    return std::sqrt(s);
  }
};

}  // namespace hotmesh::deform::detail
