// hotmesh geometry (internal): tensor-grid global interpolation (see grid_interpolation.hpp).
#include "reconstruct/grid_interpolation.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <stdexcept>

#include "spline/bspline_basis.hpp"

namespace hotmesh::geometry::detail {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// The square collocation matrix (B)_ja = N_a(t_j) of interpolation at t on `knots`.
SparseMatrix collocation(std::span<const double> knots, int degree, std::span<const double> t) {
  const auto p = static_cast<std::size_t>(degree);
  const std::size_t count = knots.size() - p - 1;
  if (t.size() != count) throw std::logic_error("grid interpolation: one parameter per pole expected");
  std::vector<Eigen::Triplet<double>> entries;
  BasisDerivatives basis;
  for (std::size_t j = 0; j < t.size(); ++j) {
    const std::size_t span = find_span(knots, degree, count, t[j]);
    basis_derivatives(knots, degree, span, t[j], 0, basis);
    for (std::size_t a = 0; a <= p; ++a) {
      entries.emplace_back(static_cast<int>(j), static_cast<int>(span - p + a), basis[0][a]);
    }
  }
  const auto size = static_cast<Eigen::Index>(count);
  SparseMatrix matrix(size, size);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

}  // namespace

// With grid values D_ij at (u_i, v_j) and collocation matrices (B_u)_ia = N_a(u_i),
// (B_v)_jb = N_b(v_j), the poles solve
//     B_u P B_v^T = D,   so   P B_v^T = B_u^{-1} D   and   P^T = B_v^{-1} (B_u^{-1} D)^T:
// the curves through every line of constant v, then through their poles along v. One sparse
// LU per direction; every line and component is a right-hand side.
std::vector<Vec3> interpolate_on_grid(std::span<const double> u_knots, int p, std::span<const double> u,
                                      std::span<const double> v_knots, int q, std::span<const double> v,
                                      std::span<const Vec3> values) {
  const std::size_t m = u.size();
  const std::size_t n = v.size();
  if (values.size() != m * n) throw std::logic_error("grid interpolation: one value per grid point expected");
  const Eigen::SparseLU<SparseMatrix> lu_u(collocation(u_knots, p, u));
  const Eigen::SparseLU<SparseMatrix> lu_v(collocation(v_knots, q, v));
  if (lu_u.info() != Eigen::Success || lu_v.info() != Eigen::Success) {
    throw std::logic_error("grid interpolation: singular collocation matrix");
  }
  std::vector<Vec3> poles(m * n);
  Eigen::MatrixXd grid(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n));
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t j = 0; j < n; ++j) grid(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = values[i * n + j][c];
    }
    const Eigen::MatrixXd along_u = lu_u.solve(grid);                    // P B_v^T
    const Eigen::MatrixXd transposed = lu_v.solve(along_u.transpose());  // P^T
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t k = 0; k < n; ++k) {
        poles[i * n + k][c] = transposed(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i));
      }
    }
  }
  return poles;
}

}  // namespace hotmesh::geometry::detail
