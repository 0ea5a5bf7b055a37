// hotmesh deform: the element stiffness matrix of the paper's appendix, eq. (28) evaluated by
// the Gauss rule (30) with n = 2:
//     K_e = sum_g w_g B_g^T E B_g  [* det J_g, unless the Jacobian is dropped (Stein et al.)]
// for the bilinear quad in plane strain (2x2 points) and the trilinear hex (2x2x2 points),
// with B from the current coordinates. The linear triangle (plane strain), tetrahedron, prism
// and pyramid use the same sum over their own rules, w_g the reference weights
// (deform/src/element/linear_elements.hpp). At a Gauss point, with g_a = grad N_a, the isotropic
// E of eqs. (32)-(33) gives the 2x2 or 3x3 block coupling nodes a and b
//     K_ab,ij = lambda g_a,i g_b,j + G (g_a,j g_b,i + delta_ij g_a . g_b).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform {

/// Degrees of freedom of a cell: d x corners (quad4 8, hex8 24, tri3 6, tet4 12, wedge6 18,
/// pyramid5 15); throws InputError for line2.
int element_dofs(ElementType type);

/// The motion's entry check: throws InputError naming the first cell whose type is not a
/// cell of the mesh's dimension (tri3, quad4 in 2D; tet4, hex8, wedge6, pyramid5 in 3D).
void require_motion_cells(const Mesh& mesh);

/// Writes K_e row-major into k (element_dofs(type)^2 values); dof a*d + i is component i of
/// corner a. The determinant enters as |det J_g| when kept, so the matrix stays positive
/// semi-definite for tangled cells met during a Newton iteration.
void element_stiffness(ElementType type, const ElementPoints& element, const Lame& lame, bool drop_jacobian,
                       std::span<double> k);

/// y_e = K_e x_e for an element matrix of N dofs (row-major, symmetric): the element product
/// of eqs. (9)-(10), which the amg solver's element pass gives the Newton residual K u.
/// Hexes and prisms: a sum of columns scaled by x_j, so that the inner loop runs along
/// contiguous memory and vectorises (column j of the symmetric K_e is its stored row j), 10 %
/// faster than row sums for hexes and 30 % for prisms (bench_operator); for the 8x8 quad
/// matrices row sums win, and for the 12x12 and 15x15 of tetrahedra and pyramids neither does.
template <std::size_t N>
void element_product(const double* ke, const double* xe, double* ye) {
  if constexpr (N >= 18) {
    for (std::size_t r = 0; r < N; ++r) ye[r] = 0.0;
    for (std::size_t j = 0; j < N; ++j) {
      const double xj = xe[j];
      const double* column = ke + j * N;
      for (std::size_t r = 0; r < N; ++r) ye[r] += column[r] * xj;
    }
  } else {
    for (std::size_t r = 0; r < N; ++r) {
      double s = 0.0;
      for (std::size_t j = 0; j < N; ++j) s += ke[r * N + j] * xe[j];
      ye[r] = s;
    }
  }
}

/// y += K_e x_e for the cell with corners `nodes`, x and y dof vectors laid out node after node
/// (D per node): the body of the element loops of eqs. (9)-(10).
template <std::size_t N, std::size_t D>
void add_element_product(std::span<const NodeId> nodes, const double* ke, std::span<const double> x, std::span<double> y) {
  constexpr std::size_t kCorners = N / D;
  std::array<double, N> xe, ye;
  for (std::size_t a = 0; a < kCorners; ++a) {
    const auto base = static_cast<std::size_t>(nodes[a]) * D;
    for (std::size_t i = 0; i < D; ++i) xe[a * D + i] = x[base + i];
  }
  element_product<N>(ke, xe.data(), ye.data());
  for (std::size_t a = 0; a < kCorners; ++a) {
    const auto base = static_cast<std::size_t>(nodes[a]) * D;
    for (std::size_t i = 0; i < D; ++i) y[base + i] += ye[a * D + i];
  }
}

/// Dofs of the largest cell (hex8): the size of scratch storage for any K_e.
inline constexpr std::size_t kMaxElementDofs = 3 * static_cast<std::size_t>(mesh::kMaxElementNodes);

/// Calls f(std::integral_constant<std::size_t, N>{}, std::integral_constant<std::size_t, D>{})
/// with the element dofs N and dofs per node D of a cell of `corners` corners, D = d: the one
/// place where a run-time cell size becomes the compile-time one of add_element_product.
/// Throws std::invalid_argument for a size no cell has.
template <class F>
void with_element_size(std::size_t corners, std::size_t d, F&& f) {
  using std::integral_constant;
  switch (corners * d) {
    case 6: return f(integral_constant<std::size_t, 6>{}, integral_constant<std::size_t, 2>{});    // tri3
    case 8: return f(integral_constant<std::size_t, 8>{}, integral_constant<std::size_t, 2>{});    // quad4
    case 12: return f(integral_constant<std::size_t, 12>{}, integral_constant<std::size_t, 3>{});  // tet4
    case 15: return f(integral_constant<std::size_t, 15>{}, integral_constant<std::size_t, 3>{});  // pyramid5
    case 18: return f(integral_constant<std::size_t, 18>{}, integral_constant<std::size_t, 3>{});  // wedge6
    case 24: return f(integral_constant<std::size_t, 24>{}, integral_constant<std::size_t, 3>{});  // hex8
    default: throw std::invalid_argument("no cell has " + std::to_string(corners) + " corners of " + std::to_string(d) + " dofs");
  }
}

/// y += K_e x_e for a cell of any type: add_element_product<N, D> chosen by the cell's
/// corners and the dofs per node d.
void add_element_product(std::span<const NodeId> nodes, std::span<const double> ke, std::size_t d,
                         std::span<const double> x, std::span<double> y);

/// Adds to each corner of a cell its share of the node's stiffness: the trace of the corner's
/// d x d diagonal block of K_e over d (invariant under the rotations of nodal frames and
/// periodic pairs). `ke` is the element matrix, row-major, of size (d * corners)^2.
void add_node_stiffness(std::span<const NodeId> nodes, std::span<const double> ke, std::size_t d,
                        std::span<double> node_stiffness);

}  // namespace hotmesh::deform
