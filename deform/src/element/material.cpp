// hotmesh deform: eq. (35), per-element Lamé parameters from the original mesh.
#include "hotmesh/deform/material.hpp"

#include <algorithm>
#include <cmath>

#include "element/linear_elements.hpp"
#include "element/q1_element.hpp"
#include "hotmesh/core/input_error.hpp"
#include "support/nearest_point.hpp"

namespace hotmesh::deform {
namespace {

constexpr double kNearestWallShare = 1e-6;  // of the bounding diagonal: the least distance a cell is stiffened for

template <std::size_t D>
ElementShape q1_shape(const ElementPoints& e) {
  using Q = detail::Q1<D>;
  const auto dn = Q::reference_gradients({});
  const auto j = Q::jacobian(e, dn);
  const double det = Q::determinant(j);
  ElementShape s;
  s.volume = det * static_cast<double>(std::size_t{1} << D);
  if (!(det > 0.0)) {
    s.shape_measure = 1e12;  // a centre Jacobian <= 0 is as distorted as it gets
    return s;
  }
  // ||Jh||_F ||Jh^-1||_F = ||J||_F ||J^-1||_F: the det(J)^(1/d) scaling cancels.
  s.shape_measure = Q::frobenius(j) * Q::frobenius(Q::inverse(j, det)) / static_cast<double>(D);
  return s;
}

/// Eq. (35)'s measures for a linear element E of linear_elements.hpp, measured against E's
/// regular cell: with J and W the Jacobians of the cell and of E::ideal() at E::centre(),
/// T = J W^-1 maps the regular cell onto this one (exactly, for tri3 and tet4), and
///     |phi_s| = ||T||_F ||T^-1||_F / d,   V_e = det J * (reference volume).
/// A cell similar to the regular one (rotated, scaled, shifted) has T = s R: |phi_s| = 1.
/// For quad4/hex8 W is a multiple of I, which is q1_shape.
template <class E>
ElementShape linear_shape(const ElementPoints& e) {
  constexpr std::size_t D = E::kDim;
  using Q = detail::Q1<D>;
  const auto dn = E::reference_gradients(E::centre());
  const auto j = detail::jacobian<D, E::kNodes>(detail::corner_coordinates<D, E::kNodes>(e), dn);
  const double det = Q::determinant(j);
  ElementShape s;
  s.volume = det * E::kReferenceVolume;
  if (!(det > 0.0)) {
    s.shape_measure = 1e12;  // as q1_shape
    return s;
  }
  const auto w = detail::jacobian<D, E::kNodes>(E::ideal(), dn);
  const auto w_inverse = Q::inverse(w, Q::determinant(w));
  const auto j_inverse = Q::inverse(j, det);
  typename Q::Matrix t{}, t_inverse{};
  for (std::size_t i = 0; i < D; ++i) {
    for (std::size_t k = 0; k < D; ++k) {
      for (std::size_t m = 0; m < D; ++m) {
        t[i][k] += j[i][m] * w_inverse[m][k];
        t_inverse[i][k] += w[i][m] * j_inverse[m][k];
      }
    }
  }
  s.shape_measure = Q::frobenius(t) * Q::frobenius(t_inverse) / static_cast<double>(D);
  return s;
}

}  // namespace

ElementShape element_shape(ElementType type, const ElementPoints& element) {
  switch (type) {
    case ElementType::quad4: return q1_shape<2>(element);
    case ElementType::hex8: return q1_shape<3>(element);
    case ElementType::tri3: return linear_shape<detail::Tri3>(element);
    case ElementType::tet4: return linear_shape<detail::Tet4>(element);
    case ElementType::wedge6: return linear_shape<detail::Wedge6>(element);
    case ElementType::pyramid5: return linear_shape<detail::Pyramid5>(element);
    default: throw InputError("element_shape: " + std::string(name(type)) + " is not a cell type");
  }
}

std::vector<Lame> element_lame(const Mesh& mesh, const MaterialOptions& options,
                               std::span<const NodeId> moving_wall_nodes) {
  return element_lame(mesh, mesh.points, options, moving_wall_nodes);
}

namespace {

/// (D / d)^p per cell: d the distance from the cell's centre (the mean of its nodes) to the
/// nearest of `walls`, D the bounding diagonal of `points`, d at least 1e-6 D.
std::vector<double> wall_distance_factors(const Mesh& mesh, std::span<const Vec3> points, double exponent,
                                          std::span<const NodeId> walls) {
  std::vector<Vec3> wall_points, centres(mesh.cell_count());
  for (NodeId n : walls) wall_points.push_back(points[static_cast<std::size_t>(n)]);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const auto nodes = mesh.cells.nodes(c);
    for (NodeId n : nodes) centres[c] += points[static_cast<std::size_t>(n)];
    centres[c] = centres[c] / static_cast<double>(nodes.size());
  }
  const double diagonal = mesh::bounding_diagonal(points);
  std::vector<double> factors = detail::nearest_distances(centres, wall_points);
  for (double& f : factors) f = std::pow(diagonal / std::max(f, kNearestWallShare * diagonal), exponent);
  return factors;
}

}  // namespace

std::vector<Lame> element_lame(const Mesh& mesh, std::span<const Vec3> points, const MaterialOptions& options,
                               std::span<const NodeId> moving_wall_nodes) {
  const std::size_t n = mesh.cell_count();
  std::vector<ElementShape> shapes(n);
  for (std::size_t c = 0; c < n; ++c) shapes[c] = element_shape(mesh.cells.type(c), gather(mesh.cells.nodes(c), points));

  std::vector<double> volumes(n);
  std::transform(shapes.begin(), shapes.end(), volumes.begin(), [](const ElementShape& s) { return s.volume; });
  const auto middle = volumes.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(volumes.begin(), middle, volumes.end());
  const double median = n > 0 ? *middle : 1.0;

  std::vector<Lame> lame(n);
  for (std::size_t c = 0; c < n; ++c) {
    const double volume_ratio = shapes[c].volume > 0.0 ? median / shapes[c].volume : 1e12;  // |phi_v|
    double two_g = options.alpha_s;  // 2G
    double bulk = options.alpha_v;   // lambda + 2G/3
    switch (options.law) {
      case StiffnessLaw::shape_volume:
        two_g *= shapes[c].shape_measure;
        bulk *= volume_ratio;
        break;
      case StiffnessLaw::uniform: break;
      case StiffnessLaw::inverse_volume:
        two_g *= volume_ratio;
        bulk *= volume_ratio;
        break;
    }
    lame[c] = {bulk - two_g / 3.0, 0.5 * two_g};
  }
  if (options.wall_distance_exponent > 0.0 && !moving_wall_nodes.empty()) {
    const std::vector<double> factors =
        wall_distance_factors(mesh, points, options.wall_distance_exponent, moving_wall_nodes);
    for (std::size_t c = 0; c < n; ++c) {
      lame[c].lambda *= factors[c];
      lame[c].mu *= factors[c];
    }
  }
  return lame;
}

}  // namespace hotmesh::deform
