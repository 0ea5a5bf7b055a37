// hotmesh deform: element stiffness matrices, eq. (28)-(30) (pointwise physics layer), for
// Q1 cells and (issue 24, first step) the linear tri3, tet4, wedge6 and pyramid5.
#include "hotmesh/deform/element_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "element/linear_elements.hpp"
#include "element/q1_element.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::deform {
namespace {

/// The quadrature sum of K_e = sum_g w_g B^T E B over the points g, for the gradients
/// g_a = grad N_a of the N corners and constant Lame parameters. Entry by entry
///     K_ab,ij = sum_g w_g (lambda g_a,i g_b,j + mu (g_a,j g_b,i + delta_ij g_a . g_b)),
/// which is, with the d x d sums M_ab = sum_g w_g g_a g_b^T,
///     K_ab = lambda M_ab + mu (M_ab^T + tr(M_ab) I).
/// So each point adds d^2 products per pair of corners (not 3 d^2), and only the pairs a <= b:
/// M_ba = M_ab^T, and K_ba = K_ab^T.
template <std::size_t D, std::size_t N>
class PointSums {
 public:
  void add(const std::array<std::array<double, D>, N>& g, double w) {
    std::size_t p = 0;
    for (std::size_t a = 0; a < N; ++a) {
      std::array<double, D> wg{};
      for (std::size_t i = 0; i < D; ++i) wg[i] = w * g[a][i];
      for (std::size_t b = a; b < N; ++b, ++p) {
        double* m = m_.data() + p * D * D;
        for (std::size_t i = 0; i < D; ++i) {
          for (std::size_t j = 0; j < D; ++j) m[i * D + j] += wg[i] * g[b][j];
        }
      }
    }
  }

  /// K_e, row-major, every entry written.
  void write(const Lame& lame, std::span<double> k) const {
    constexpr std::size_t n = N * D;
    std::size_t p = 0;
    for (std::size_t a = 0; a < N; ++a) {
      for (std::size_t b = a; b < N; ++b, ++p) {
        const double* m = m_.data() + p * D * D;
        double trace = 0.0;
        for (std::size_t i = 0; i < D; ++i) trace += m[i * D + i];
        for (std::size_t i = 0; i < D; ++i) {
          for (std::size_t j = 0; j < D; ++j) {
            double v = lame.lambda * m[i * D + j] + lame.mu * m[j * D + i];
            if (i == j) v += lame.mu * trace;
            k[(a * D + i) * n + b * D + j] = v;
            k[(b * D + j) * n + a * D + i] = v;
          }
        }
      }
    }
  }

 private:
  std::array<double, N*(N + 1) / 2 * D * D> m_{};
};

template <std::size_t D>
void q1_stiffness(const ElementPoints& e, const Lame& lame, bool drop_jacobian, std::span<double> k) {
  using Q = detail::Q1<D>;
  PointSums<D, Q::kNodes> sums;
  for (const auto& xi : Q::gauss_points()) {
    const auto dn = Q::reference_gradients(xi);
    const auto j = Q::jacobian(e, dn);
    const double det = Q::determinant(j);
    if (det == 0.0 || !std::isfinite(det)) continue;  // a collapsed point carries no stiffness
    const auto inv = Q::inverse(j, det);
    // g_a = J^-T dN_a/dxi: g_a,i = sum_k dN_a/dxi_k (J^-1)_ki
    std::array<std::array<double, D>, Q::kNodes> g{};
    for (std::size_t a = 0; a < Q::kNodes; ++a) {
      for (std::size_t i = 0; i < D; ++i) {
        for (std::size_t m = 0; m < D; ++m) g[a][i] += dn[a][m] * inv[m][i];
      }
    }
    const double w = drop_jacobian ? 1.0 : std::abs(det);  // Gauss weights are all 1
    sums.add(g, w);
  }
  sums.write(lame, k);
}

/// The element matrix of a linear element E of linear_elements.hpp, the same sum as
/// q1_stiffness over E's rule: w_g B^T E B with w_g the reference weight when the Jacobian is
/// dropped, w_g |det J_g| when kept.
template <class E>
void linear_stiffness(const ElementPoints& e, const Lame& lame, bool drop_jacobian, std::span<double> k) {
  constexpr std::size_t D = E::kDim;
  constexpr std::size_t nodes = E::kNodes;
  using Q = detail::Q1<D>;  // the d x d matrix helpers
  PointSums<D, nodes> sums;
  const auto x = detail::corner_coordinates<D, nodes>(e);
  for (const auto& q : E::quadrature()) {
    const auto dn = E::reference_gradients(q.xi);
    const auto j = detail::jacobian<D, nodes>(x, dn);
    const double det = Q::determinant(j);
    if (det == 0.0 || !std::isfinite(det)) continue;  // a collapsed point carries no stiffness
    const auto inv = Q::inverse(j, det);
    std::array<std::array<double, D>, nodes> g{};
    for (std::size_t a = 0; a < nodes; ++a) {
      for (std::size_t i = 0; i < D; ++i) {
        for (std::size_t m = 0; m < D; ++m) g[a][i] += dn[a][m] * inv[m][i];
      }
    }
    const double w = drop_jacobian ? q.weight : q.weight * std::abs(det);
    sums.add(g, w);
  }
  sums.write(lame, k);
}

}  // namespace

int element_dofs(ElementType type) {
  switch (type) {
    case ElementType::quad4: return 8;
    case ElementType::hex8: return 24;
    case ElementType::tri3: return 6;
    case ElementType::tet4: return 12;
    case ElementType::wedge6: return 18;
    case ElementType::pyramid5: return 15;
    default: throw InputError("element_dofs: " + std::string(name(type)) + " is not a cell type");
  }
}

void require_motion_cells(const Mesh& mesh) {
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const ElementType t = mesh.cells.type(c);
    if (dimension(t) != mesh.dimension) {
      throw InputError("cell " + std::to_string(mesh.cell_id(static_cast<CellId>(c))) + " is a " + std::string(name(t)) +
                       ": the mesh-motion solver moves " +
                       (mesh.dimension == 2 ? "2D meshes of tri3 and quad4 cells"
                                            : "3D meshes of tet4, hex8, wedge6 and pyramid5 cells"));
    }
  }
}

void add_element_product(std::span<const NodeId> nodes, std::span<const double> ke, std::size_t d,
                         std::span<const double> x, std::span<double> y) {
  with_element_size(nodes.size(), d, [&](auto n, auto dofs) { add_element_product<n, dofs>(nodes, ke.data(), x, y); });
}

void element_stiffness(ElementType type, const ElementPoints& element, const Lame& lame, bool drop_jacobian,
                       std::span<double> k) {
  if (type == ElementType::quad4) {
    q1_stiffness<2>(element, lame, drop_jacobian, k);
  } else if (type == ElementType::hex8) {
    q1_stiffness<3>(element, lame, drop_jacobian, k);
  } else if (type == ElementType::tri3) {
    linear_stiffness<detail::Tri3>(element, lame, drop_jacobian, k);
  } else if (type == ElementType::tet4) {
    linear_stiffness<detail::Tet4>(element, lame, drop_jacobian, k);
  } else if (type == ElementType::wedge6) {
    linear_stiffness<detail::Wedge6>(element, lame, drop_jacobian, k);
  } else if (type == ElementType::pyramid5) {
    linear_stiffness<detail::Pyramid5>(element, lame, drop_jacobian, k);
  } else {
    element_dofs(type);  // throws: line2 is no cell
  }
}

void add_node_stiffness(std::span<const NodeId> nodes, std::span<const double> ke, std::size_t d,
                        std::span<double> node_stiffness) {
  const std::size_t n = nodes.size() * d;
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    double trace = 0.0;
    for (std::size_t i = 0; i < d; ++i) trace += ke[(a * d + i) * n + a * d + i];
    node_stiffness[static_cast<std::size_t>(nodes[a])] += trace / static_cast<double>(d);
  }
}

}  // namespace hotmesh::deform
