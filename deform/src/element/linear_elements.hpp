// hotmesh deform (internal): the linear elements beyond Q1 (issue 24, first step) - the
// triangle tri3 (d = 2), the tetrahedron tet4, the prism wedge6 and the pyramid pyramid5
// (d = 3) - as the paper's eq. (29)-(30) does for quad4/hex8 in q1_element.hpp: reference
// corners in Gmsh order, dN_a/dxi, a quadrature rule {xi_g, w_g} whose weights sum to the
// reference volume, the centre where eq. (35) measures the cell, and the regular ("ideal")
// cell that eq. (35)'s |phi_s| compares against. docs/method.md, "Hybrid meshes: triangles,
// tetrahedra, prisms and pyramids", states the same definitions.
//
//   tri3   xi, eta >= 0, xi + eta <= 1      N = 1 - xi - eta, xi, eta
//          1 point (centroid, w = 1/2): the gradients are constant.
//   tet4   xi, eta, zeta >= 0, sum <= 1     N = 1 - xi - eta - zeta, xi, eta, zeta
//          1 point (centroid, w = 1/6).
//   wedge6 triangle x [-1, 1]               N = L_a(xi, eta) (1 -+ zeta) / 2, corners 0-1-2 at
//          zeta = -1, 3-4-5 above them. 3-point triangle rule (1/6, 1/6), (2/3, 1/6),
//          (1/6, 2/3), w = 1/6, times 2-point Gauss-Legendre in zeta: 6 points, exact for
//          degree 2 in (xi, eta) and 3 in zeta: K_e of a prism with constant J exactly, and on
//          any prism the patch-test integrals int grad N_a dV = int adj(J)^T grad_xi N_a dxi
//          (degree 1 in (xi, eta), 2 in zeta).
//   pyramid5 base [-1, 1]^2 at zeta = 0, apex (0, 0, 1); the rational basis of Bedrosian
//          (1992), also Nigam & Phillips (2012) and Gmsh's:
//              N_a = (1 - zeta + xi_a xi)(1 - zeta + eta_a eta) / (4 (1 - zeta)),  a = 0..3
//              N_4 = zeta
//          Quadrature by the conical (collapsed) product rule, Stroud (1971):
//          xi = u (1 - zeta), eta = v (1 - zeta), dxi deta dzeta = (1 - zeta)^2 du dv dzeta.
//          In (u, v, zeta) every dN_a/dxi_k, and so J and det J, depends on (u, v) alone
//          (dN_a/dxi = xi_a (1 + eta_a v) / 4, ...), so the rule is 2x2 Gauss-Legendre in
//          (u, v) times the 1-point Gauss-Jacobi rule of weight (1 - zeta)^2 on [0, 1]
//          (zeta = 1/4, w = 1/3): 4 points, exact for the patch-test integrals of any pyramid
//          (multilinear in (u, v)) and for K_e of a pyramid with a parallelogram base
//          (constant J, B^T B of degree 2 in u and in v). The rule never evaluates the apex,
//          where the rational gradients are undefined.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform::detail {

template <std::size_t D>
struct QuadraturePoint {
  std::array<double, D> xi{};
  double weight = 0.0;
};

struct Tri3 {
  static constexpr std::size_t kDim = 2;
  static constexpr ElementType kType = ElementType::tri3;
  static constexpr std::size_t kNodes = 3;
  using Point = std::array<double, kDim>;
  static constexpr double kReferenceVolume = 0.5;

  static std::array<double, kNodes> values(const Point& xi) { return {1.0 - xi[0] - xi[1], xi[0], xi[1]}; }
  static std::array<Point, kNodes> reference_gradients(const Point& /*xi*/) { return {{{-1, -1}, {1, 0}, {0, 1}}}; }
  static std::array<QuadraturePoint<kDim>, 1> quadrature() { return {{{{1.0 / 3.0, 1.0 / 3.0}, 0.5}}}; }
  static Point centre() { return {1.0 / 3.0, 1.0 / 3.0}; }
  /// The equilateral triangle.
  static std::array<Point, kNodes> ideal() { return {{{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2.0}}}; }
};

struct Tet4 {
  static constexpr std::size_t kDim = 3;
  static constexpr ElementType kType = ElementType::tet4;
  static constexpr std::size_t kNodes = 4;
  using Point = std::array<double, kDim>;
  static constexpr double kReferenceVolume = 1.0 / 6.0;

  static std::array<double, kNodes> values(const Point& xi) {
    return {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  }
  static std::array<Point, kNodes> reference_gradients(const Point& /*xi*/) {
    return {{{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  }
  static std::array<QuadraturePoint<kDim>, 1> quadrature() { return {{{{0.25, 0.25, 0.25}, 1.0 / 6.0}}}; }
  static Point centre() { return {0.25, 0.25, 0.25}; }
  /// The regular tetrahedron of unit edges.
  static std::array<Point, kNodes> ideal() {
    const double r3 = std::sqrt(3.0);
    return {{{0, 0, 0}, {1, 0, 0}, {0.5, r3 / 2.0, 0}, {0.5, r3 / 6.0, std::sqrt(2.0 / 3.0)}}};
  }
};

struct Wedge6 {
  static constexpr std::size_t kDim = 3;
  static constexpr ElementType kType = ElementType::wedge6;
  static constexpr std::size_t kNodes = 6;
  using Point = std::array<double, kDim>;
  static constexpr double kReferenceVolume = 1.0;

  static std::array<double, kNodes> values(const Point& xi) {
    const double l[3] = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
    std::array<double, kNodes> n{};
    for (std::size_t a = 0; a < 3; ++a) {
      n[a] = l[a] * 0.5 * (1.0 - xi[2]);
      n[a + 3] = l[a] * 0.5 * (1.0 + xi[2]);
    }
    return n;
  }
  static std::array<Point, kNodes> reference_gradients(const Point& xi) {
    const double l[3] = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
    const double dl[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
    std::array<Point, kNodes> g{};
    for (std::size_t a = 0; a < 3; ++a) {
      for (std::size_t s = 0; s < 2; ++s) {  // s = 0: bottom (zeta = -1), s = 1: top
        const double sign = s == 0 ? -1.0 : 1.0;
        const double h = 0.5 * (1.0 + sign * xi[2]);
        g[a + 3 * s] = {dl[a][0] * h, dl[a][1] * h, 0.5 * sign * l[a]};
      }
    }
    return g;
  }
  static std::array<QuadraturePoint<kDim>, 6> quadrature() {
    const double z = 1.0 / std::sqrt(3.0);
    const double t[3][2] = {{1.0 / 6.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 6.0}, {1.0 / 6.0, 2.0 / 3.0}};
    std::array<QuadraturePoint<kDim>, 6> q{};
    for (std::size_t i = 0; i < 3; ++i) {
      q[i] = {{t[i][0], t[i][1], -z}, 1.0 / 6.0};
      q[i + 3] = {{t[i][0], t[i][1], z}, 1.0 / 6.0};
    }
    return q;
  }
  static Point centre() { return {1.0 / 3.0, 1.0 / 3.0, 0.0}; }
  /// The prism of unit edges: an equilateral triangle extruded by its side.
  static std::array<Point, kNodes> ideal() {
    const double y = std::sqrt(3.0) / 2.0;
    return {{{0, 0, 0}, {1, 0, 0}, {0.5, y, 0}, {0, 0, 1}, {1, 0, 1}, {0.5, y, 1}}};
  }
};

struct Pyramid5 {
  static constexpr std::size_t kDim = 3;
  static constexpr ElementType kType = ElementType::pyramid5;
  static constexpr std::size_t kNodes = 5;
  using Point = std::array<double, kDim>;
  static constexpr double kReferenceVolume = 4.0 / 3.0;

  /// The rational basis (N_4 = zeta at the apex, where the base functions' limit is 0).
  static std::array<double, kNodes> values(const Point& xi) {
    constexpr double base[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    std::array<double, kNodes> n{};
    const double t = 1.0 - xi[2];
    for (std::size_t a = 0; a < 4; ++a) {
      n[a] = t > 0.0 ? (t + base[a][0] * xi[0]) * (t + base[a][1] * xi[1]) / (4.0 * t) : 0.0;
    }
    n[4] = xi[2];
    return n;
  }
  /// The rational basis's gradients; not defined at the apex (zeta = 1), where no point of
  /// the rule lies.
  static std::array<Point, kNodes> reference_gradients(const Point& xi) {
    constexpr double base[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const double u = xi[0] / (1.0 - xi[2]);
    const double v = xi[1] / (1.0 - xi[2]);
    std::array<Point, kNodes> g{};
    for (std::size_t a = 0; a < 4; ++a) {
      const double xa = base[a][0], ya = base[a][1];
      g[a] = {0.25 * xa * (1.0 + ya * v), 0.25 * ya * (1.0 + xa * u), 0.25 * (-1.0 + xa * ya * u * v)};
    }
    g[4] = {0.0, 0.0, 1.0};
    return g;
  }
  static std::array<QuadraturePoint<kDim>, 4> quadrature() {
    const double s = 1.0 / std::sqrt(3.0);
    const double zeta = 0.25;  // Gauss-Jacobi, weight (1 - zeta)^2 on [0, 1], 1 point
    const double w = 1.0 / 3.0;  // int_0^1 (1 - zeta)^2 dzeta, times the Gauss-Legendre weights 1 x 1
    std::array<QuadraturePoint<kDim>, 4> q{};
    constexpr double uv[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (std::size_t i = 0; i < 4; ++i) q[i] = {{uv[i][0] * s * (1.0 - zeta), uv[i][1] * s * (1.0 - zeta), zeta}, w};
    return q;
  }
  /// The reference pyramid's centroid.
  static Point centre() { return {0.0, 0.0, 0.25}; }
  /// The pyramid of unit edges: a unit square base, the apex 1/sqrt(2) above its centre.
  static std::array<Point, kNodes> ideal() {
    return {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1.0 / std::sqrt(2.0)}}};
  }
};

/// Reference coordinates of the corners, in Gmsh order.
template <class E>
std::array<typename E::Point, E::kNodes> reference_corners() {
  if constexpr (E::kType == ElementType::tri3) {
    return {{{0, 0}, {1, 0}, {0, 1}}};
  } else if constexpr (E::kType == ElementType::tet4) {
    return {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  } else if constexpr (E::kType == ElementType::wedge6) {
    return {{{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}};
  } else {
    return {{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}}};
  }
}

/// The corners of `e` as D-vectors (the first D coordinates).
template <std::size_t D, std::size_t N>
std::array<std::array<double, D>, N> corner_coordinates(const ElementPoints& e) {
  std::array<std::array<double, D>, N> x{};
  for (std::size_t a = 0; a < N; ++a) {
    for (std::size_t i = 0; i < D; ++i) x[a][i] = e.p[a][i];
  }
  return x;
}

/// J_ik = sum_a x^a_i dN_a/dxi_k.
template <std::size_t D, std::size_t N>
std::array<std::array<double, D>, D> jacobian(const std::array<std::array<double, D>, N>& x,
                                              const std::array<std::array<double, D>, N>& dn) {
  std::array<std::array<double, D>, D> j{};
  for (std::size_t a = 0; a < N; ++a) {
    for (std::size_t i = 0; i < D; ++i) {
      for (std::size_t k = 0; k < D; ++k) j[i][k] += x[a][i] * dn[a][k];
    }
  }
  return j;
}

}  // namespace hotmesh::deform::detail
