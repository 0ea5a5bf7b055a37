// hotmesh tests (deform): an element's stiffness as a dense matrix and its rigid-body modes,
// for the tests of the Q1 element and of the linear elements beside it.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "hotmesh/deform/element_stiffness.hpp"

namespace hotmesh::test {

using deform::ElementPoints;
using deform::ElementType;
using deform::Lame;
using geometry::Vec3;

/// K_e of `type` on the corners `e` (`drop`: the Jacobian dropped, as the motion uses it).
inline Eigen::MatrixXd stiffness(ElementType type, const ElementPoints& e, const Lame& lame, bool drop) {
  const int n = deform::element_dofs(type);
  std::vector<double> k(static_cast<std::size_t>(n * n));
  deform::element_stiffness(type, e, lame, drop, k);
  return Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(k.data(), n, n);
}

/// Translations and infinitesimal rotations of the corners, one column each (3 in 2D, 6 in 3D).
inline Eigen::MatrixXd rigid_modes(const ElementPoints& e, int d) {
  const int modes = d == 2 ? 3 : 6;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(e.count * d, modes);
  for (int a = 0; a < e.count; ++a) {
    const Vec3& p = e.p[static_cast<std::size_t>(a)];
    for (int i = 0; i < d; ++i) m(a * d + i, i) = 1.0;
    if (d == 2) {
      m(a * 2, 2) = -p.y;
      m(a * 2 + 1, 2) = p.x;
    } else {
      const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      for (int r = 0; r < 3; ++r) {
        const Vec3 v = cross(axes[r], p);
        for (int i = 0; i < 3; ++i) m(a * 3 + i, 3 + r) = v[i];
      }
    }
  }
  return m;
}

}  // namespace hotmesh::test
