// Tests of the element level for tri3, tet4, wedge6 and pyramid5 (issue 24, first step;
// deform/src/element/linear_elements.hpp): the patch test on distorted patches of each type (Jacobian
// kept), the rigid-body modes in the null space of K_e, symmetry, positive semi-definiteness
// with exactly the rigid-body null space, eq. (35)'s |phi_s| = 1 for the regular cells and
// their volumes, and the motion's refusal of these cells (the solver handles Q1 only).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "element_matrices.hpp"
#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/core/input_error.hpp"
#include "element/linear_elements.hpp"
#include "test_support.hpp"

namespace hotmesh::deform {
namespace {

using test::rigid_modes;
using test::stiffness;

constexpr std::array kTypes{ElementType::tri3, ElementType::tet4, ElementType::wedge6, ElementType::pyramid5};



ElementPoints points(std::initializer_list<Vec3> corners) {
  ElementPoints e;
  for (const Vec3& p : corners) e.p[static_cast<std::size_t>(e.count++)] = p;
  return e;
}

/// A visibly distorted but valid cell of each type, in Gmsh order.
ElementPoints distorted(ElementType type) {
  switch (type) {
    case ElementType::tri3: return points({{0.1, -0.2, 0}, {2.3, 0.4, 0}, {0.6, 1.1, 0}});
    case ElementType::tet4: return points({{0, 0, 0}, {1.7, 0.2, 0.1}, {0.4, 0.9, -0.2}, {0.3, 0.5, 1.4}});
    case ElementType::wedge6:
      return points({{0, 0, 0}, {1.4, 0.1, 0.1}, {0.2, 1.1, -0.1}, {0.1, -0.1, 0.9}, {1.2, 0.2, 1.3}, {0.3, 1.3, 0.8}});
    case ElementType::pyramid5:
      return points({{0, 0, 0}, {1.5, 0.1, 0.1}, {1.3, 1.2, -0.1}, {-0.1, 0.9, 0}, {0.7, 0.3, 1.1}});
    default: return {};
  }
}

/// The regular cell of each type (all edges 1), in Gmsh order.
ElementPoints regular(ElementType type) {
  const double y = std::sqrt(3.0) / 2.0;
  switch (type) {
    case ElementType::tri3: return points({{0, 0, 0}, {1, 0, 0}, {0.5, y, 0}});
    case ElementType::tet4: return points({{0, 0, 0}, {1, 0, 0}, {0.5, y, 0}, {0.5, y / 3.0, std::sqrt(2.0 / 3.0)}});
    case ElementType::wedge6: return points({{0, 0, 0}, {1, 0, 0}, {0.5, y, 0}, {0, 0, 1}, {1, 0, 1}, {0.5, y, 1}});
    case ElementType::pyramid5:
      return points({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1.0 / std::sqrt(2.0)}});
    default: return {};
  }
}


/// A rigid rotation about a skew axis, a scaling and a shift: the similarity a regular cell may
/// be given without changing its shape.
ElementPoints rotated_scaled(ElementPoints e, double scale) {
  const double c = std::cos(0.7), s = std::sin(0.7), c2 = std::cos(0.4), s2 = std::sin(0.4);
  for (int a = 0; a < e.count; ++a) {
    Vec3& p = e.p[static_cast<std::size_t>(a)];
    const Vec3 r1{c * p.x - s * p.y, s * p.x + c * p.y, p.z};  // about z
    const Vec3 r2{r1.x, c2 * r1.y - s2 * r1.z, s2 * r1.y + c2 * r1.z};  // about x
    p = scale * r2 + Vec3{3.0, -1.0, 2.0};
  }
  return e;
}

// ---- the reference elements (deform/src/element/linear_elements.hpp) ---------------------------------

/// A few points inside the reference element: the centre and points towards its corners.
template <class E>
std::vector<typename E::Point> inner_points() {
  std::vector<typename E::Point> p{E::centre()};
  for (const auto& c : detail::reference_corners<E>()) {
    typename E::Point q{};
    for (std::size_t k = 0; k < E::kDim; ++k) q[k] = 0.6 * c[k] + 0.4 * E::centre()[k] + 0.03 * double(k + 1);
    p.push_back(q);
  }
  return p;
}

template <class E>
void expect_interpolating_and_linear_complete() {
  const auto corners = detail::reference_corners<E>();
  for (std::size_t b = 0; b < E::kNodes; ++b) {
    const auto n = E::values(corners[b]);
    for (std::size_t a = 0; a < E::kNodes; ++a) EXPECT_NEAR(n[a], a == b ? 1.0 : 0.0, 1e-15) << name(E::kType);
  }
  for (const auto& xi : inner_points<E>()) {
    const auto n = E::values(xi);
    double sum = 0.0;
    typename E::Point x{};
    for (std::size_t a = 0; a < E::kNodes; ++a) {
      sum += n[a];
      for (std::size_t k = 0; k < E::kDim; ++k) x[k] += n[a] * corners[a][k];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << name(E::kType);
    for (std::size_t k = 0; k < E::kDim; ++k) EXPECT_NEAR(x[k], xi[k], 1e-14) << name(E::kType);
  }
}

TEST(LinearElements, ShapeFunctionsInterpolateCornersAndReproduceLinearFields) {
  expect_interpolating_and_linear_complete<detail::Tri3>();
  expect_interpolating_and_linear_complete<detail::Tet4>();
  expect_interpolating_and_linear_complete<detail::Wedge6>();
  expect_interpolating_and_linear_complete<detail::Pyramid5>();
}

template <class E>
void expect_gradients_are_derivatives() {
  const double h = 1e-6;
  for (const auto& xi : inner_points<E>()) {
    const auto g = E::reference_gradients(xi);
    for (std::size_t k = 0; k < E::kDim; ++k) {
      auto plus = xi, minus = xi;
      plus[k] += h;
      minus[k] -= h;
      const auto np = E::values(plus), nm = E::values(minus);
      for (std::size_t a = 0; a < E::kNodes; ++a) {
        EXPECT_NEAR(g[a][k], (np[a] - nm[a]) / (2.0 * h), 1e-8) << name(E::kType) << " N_" << a << " d/dxi_" << k;
      }
    }
  }
}

TEST(LinearElements, GradientsAreTheShapeFunctionsDerivatives) {
  expect_gradients_are_derivatives<detail::Tri3>();
  expect_gradients_are_derivatives<detail::Tet4>();
  expect_gradients_are_derivatives<detail::Wedge6>();
  expect_gradients_are_derivatives<detail::Pyramid5>();
}

template <class E, class F>
double integrate(F f) {
  double s = 0.0;
  for (const auto& q : E::quadrature()) s += q.weight * f(q.xi);
  return s;
}

TEST(LinearElements, QuadratureIntegratesWhatTheElementsNeedExactly) {
  // volumes and first moments (centroids)
  EXPECT_NEAR(integrate<detail::Tri3>([](auto) { return 1.0; }), 0.5, 1e-15);
  EXPECT_NEAR(integrate<detail::Tet4>([](auto) { return 1.0; }), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(integrate<detail::Tet4>([](auto x) { return x[2]; }), 1.0 / 24.0, 1e-15);
  // wedge: degree 2 in (xi, eta), 3 in zeta
  EXPECT_NEAR(integrate<detail::Wedge6>([](auto) { return 1.0; }), 1.0, 1e-15);
  EXPECT_NEAR(integrate<detail::Wedge6>([](auto x) { return x[0] * x[0]; }), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(integrate<detail::Wedge6>([](auto x) { return x[0] * x[1] * x[2] * x[2]; }), 1.0 / 24.0 * 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(integrate<detail::Wedge6>([](auto x) { return x[2] * x[2] * x[2] + x[2] * x[2]; }), 1.0 / 3.0, 1e-15);
  // pyramid: functions of u = xi / (1 - zeta), v = eta / (1 - zeta) of degree <= 3 in each,
  // against the measure (1 - zeta)^2 du dv dzeta
  auto u = [](auto x) { return x[0] / (1.0 - x[2]); };
  auto v = [](auto x) { return x[1] / (1.0 - x[2]); };
  EXPECT_NEAR(integrate<detail::Pyramid5>([](auto) { return 1.0; }), 4.0 / 3.0, 1e-15);
  EXPECT_NEAR(integrate<detail::Pyramid5>([](auto x) { return x[2]; }), 1.0 / 3.0, 1e-15);  // centroid at 1/4
  EXPECT_NEAR(integrate<detail::Pyramid5>([&](auto x) { return u(x) * u(x) * v(x) * v(x); }), 4.0 / 27.0, 1e-15);
  EXPECT_NEAR(integrate<detail::Pyramid5>([&](auto x) { return u(x) * u(x) * u(x) * v(x); }), 0.0, 1e-15);
}

const Lame kLames[] = {{0.5, 1.0}, {-0.3, 0.5}};  // lambda < 0 as eq. (35) gives for alpha_v << alpha_s

TEST(LinearElements, DofsAreDimensionTimesCorners) {
  EXPECT_EQ(element_dofs(ElementType::tri3), 6);
  EXPECT_EQ(element_dofs(ElementType::tet4), 12);
  EXPECT_EQ(element_dofs(ElementType::wedge6), 18);
  EXPECT_EQ(element_dofs(ElementType::pyramid5), 15);
  EXPECT_THROW(element_dofs(ElementType::line2), InputError);
}

TEST(LinearElements, StiffnessIsSymmetric) {
  for (ElementType type : kTypes) {
    for (bool drop : {true, false}) {
      const Eigen::MatrixXd k = stiffness(type, distorted(type), kLames[0], drop);
      EXPECT_GT(k.norm(), 0.0);
      EXPECT_LT((k - k.transpose()).norm(), 1e-14 * k.norm()) << name(type) << " drop " << drop;
    }
  }
}

TEST(LinearElements, RigidBodyModesAreInTheNullSpace) {
  for (ElementType type : kTypes) {
    const int d = dimension(type);
    const ElementPoints e = distorted(type);
    const Eigen::MatrixXd modes = rigid_modes(e, d);
    for (bool drop : {true, false}) {
      for (const Lame& lame : kLames) {
        const Eigen::MatrixXd k = stiffness(type, e, lame, drop);
        const Eigen::MatrixXd r = k * modes;
        EXPECT_LT(r.leftCols(d).norm(), 1e-13 * k.norm()) << name(type) << ": translations";
        EXPECT_LT(r.rightCols(modes.cols() - d).norm(), 1e-13 * k.norm() * modes.norm()) << name(type) << ": rotations";
      }
    }
  }
}

TEST(LinearElements, StiffnessIsPsdWithExactlyTheRigidNullSpace) {
  for (ElementType type : kTypes) {
    const int rigid = dimension(type) == 2 ? 3 : 6;
    for (const ElementPoints& e : {distorted(type), regular(type)}) {
      for (bool drop : {true, false}) {
        for (const Lame& lame : kLames) {
          const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(stiffness(type, e, lame, drop));
          const auto& values = eigen.eigenvalues();
          const double largest = values.maxCoeff();
          for (int i = 0; i < rigid; ++i) {
            EXPECT_LT(std::abs(values(i)), 1e-12 * largest) << name(type) << " eigenvalue " << i;
          }
          EXPECT_GT(values(rigid), 1e-6 * largest) << name(type) << ": a zero-energy mode beyond the rigid-body ones";
        }
      }
    }
  }
}

// ---- patch test: K u = 0 at the interior nodes for u linear, on distorted patches ----------

struct Patch {
  int dimension = 3;
  std::vector<Vec3> nodes;
  std::vector<std::vector<int>> cells;
  std::vector<ElementType> types;  ///< one per cell
  std::vector<bool> interior;
};

/// Moves every node by a deterministic offset of up to `amplitude` in each direction used.
void distort(Patch& patch, int d, double amplitude) {
  for (std::size_t i = 0; i < patch.nodes.size(); ++i) {
    const auto t = static_cast<double>(i);
    patch.nodes[i].x += amplitude * std::sin(1.7 * t + 0.3);
    patch.nodes[i].y += amplitude * std::sin(2.9 * t + 1.1);
    if (d == 3) patch.nodes[i].z += amplitude * std::sin(4.3 * t + 2.3);
  }
}

/// n x n squares of a grid, each cut into two triangles along a diagonal.
Patch triangle_patch(int n) {
  Patch p;
  p.dimension = 2;
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      p.nodes.push_back({double(i), double(j), 0});
      p.interior.push_back(i > 0 && i < n && j > 0 && j < n);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      p.cells.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      p.cells.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      p.types.insert(p.types.end(), 2, ElementType::tri3);
    }
  }
  return p;
}

/// The triangle patch extruded through `layers` layers into prisms.
Patch wedge_patch(int n, int layers) {
  const Patch base = triangle_patch(n);
  Patch p;
  const int m = static_cast<int>(base.nodes.size());
  for (int k = 0; k <= layers; ++k) {
    for (int a = 0; a < m; ++a) {
      p.nodes.push_back({base.nodes[static_cast<std::size_t>(a)].x, base.nodes[static_cast<std::size_t>(a)].y, double(k)});
      p.interior.push_back(base.interior[static_cast<std::size_t>(a)] && k > 0 && k < layers);
    }
  }
  for (int k = 0; k < layers; ++k) {
    for (const auto& t : base.cells) {
      p.cells.push_back({t[0] + k * m, t[1] + k * m, t[2] + k * m, t[0] + (k + 1) * m, t[1] + (k + 1) * m, t[2] + (k + 1) * m});
      p.types.push_back(ElementType::wedge6);
    }
  }
  return p;
}

/// An n^3 grid of cubes: node ids and the cubes' Gmsh hex corners.
Patch cube_grid(int n) {
  Patch p;
  auto id = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        p.nodes.push_back({double(i), double(j), double(k)});
        p.interior.push_back(i > 0 && i < n && j > 0 && j < n && k > 0 && k < n);
      }
    }
  }
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        p.cells.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                           id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
        p.types.push_back(ElementType::hex8);
      }
    }
  }
  return p;
}

double signed_volume(const std::vector<Vec3>& x, const std::vector<int>& tet) {
  auto at = [&](int a) { return x[static_cast<std::size_t>(tet[static_cast<std::size_t>(a)])]; };
  return dot(cross(at(1) - at(0), at(2) - at(0)), at(3) - at(0)) / 6.0;
}

/// Every cube cut into the six tetrahedra of the Kuhn triangulation (conforming across cubes),
/// numbered with positive volume.
Patch tet_patch(int n) {
  Patch p = cube_grid(n);
  const std::vector<std::vector<int>> hexes = std::move(p.cells);
  p.cells.clear();
  p.types.assign(hexes.size() * 6, ElementType::tet4);
  // Hex corner of the offsets (dx, dy, dz) in Gmsh order.
  auto corner = [](int dx, int dy, int dz) { return dz * 4 + (dy == 0 ? dx : 3 - dx); };
  const int permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& h : hexes) {
    for (const auto& perm : permutations) {
      std::array<int, 3> o{0, 0, 0};
      std::vector<int> tet{h[static_cast<std::size_t>(corner(0, 0, 0))]};
      for (int axis : perm) {
        o[static_cast<std::size_t>(axis)] = 1;
        tet.push_back(h[static_cast<std::size_t>(corner(o[0], o[1], o[2]))]);
      }
      if (signed_volume(p.nodes, tet) < 0) std::swap(tet[1], tet[2]);
      p.cells.push_back(tet);
    }
  }
  return p;
}

/// A grid of cubes in which every other cube (checkerboard) is cut into six pyramids, one on
/// each face, their apex at a new node in the cube's centre and each base numbered so that its
/// right-hand normal points at the apex; the other cubes stay hexes. Between two pyramids a
/// base's quadrature error would cancel (it depends on the base alone and the two see it in
/// opposite orientations); against a hex it does not, so this patch tests the pyramid's rule.
Patch pyramid_patch(int n) {
  Patch p = cube_grid(n);
  const std::vector<std::vector<int>> hexes = std::move(p.cells);
  p.cells.clear();
  p.types.clear();
  for (std::size_t c = 0; c < hexes.size(); ++c) {
    const auto& h = hexes[c];
    const auto i = static_cast<int>(c) % n, j = static_cast<int>(c) / n % n, k = static_cast<int>(c) / (n * n);
    if ((i + j + k) % 2 == 1) {
      p.cells.push_back(h);
      p.types.push_back(ElementType::hex8);
      continue;
    }
    Vec3 centre{0, 0, 0};
    for (int a : h) centre = centre + 0.125 * p.nodes[static_cast<std::size_t>(a)];
    const int apex = static_cast<int>(p.nodes.size());
    p.nodes.push_back(centre);
    p.interior.push_back(true);
    for (const mesh::LocalFace& f : mesh::faces(ElementType::hex8)) {  // outward: reversed
      p.cells.push_back({h[f.nodes[0]], h[f.nodes[3]], h[f.nodes[2]], h[f.nodes[1]], apex});
      p.types.push_back(ElementType::pyramid5);
    }
  }
  return p;
}

Patch patch_of(ElementType type) {
  switch (type) {
    case ElementType::tri3: return triangle_patch(3);
    case ElementType::tet4: return tet_patch(2);
    case ElementType::wedge6: return wedge_patch(3, 2);
    default: return pyramid_patch(2);
  }
}

/// max |(K u)_i| over the interior dofs, relative to max |K_e| max |u|, for u = A x + b.
double interior_residual(const Patch& patch, bool drop_jacobian) {
  const int d = patch.dimension;
  const auto nodes = static_cast<int>(patch.nodes.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(nodes * d, nodes * d);
  const Lame lame{0.7, 1.3};
  for (std::size_t cell = 0; cell < patch.cells.size(); ++cell) {
    const auto& c = patch.cells[cell];
    const ElementType type = patch.types[cell];
    ElementPoints e;
    for (int a : c) e.p[static_cast<std::size_t>(e.count++)] = patch.nodes[static_cast<std::size_t>(a)];
    const auto shape = element_shape(type, e);
    EXPECT_GT(shape.volume, 0.0) << "the distorted patch has a folded cell";
    const Eigen::MatrixXd ke = stiffness(type, e, lame, drop_jacobian);
    for (std::size_t a = 0; a < c.size(); ++a) {
      for (std::size_t b = 0; b < c.size(); ++b) {
        k.block(c[a] * d, c[b] * d, d, d) += ke.block(static_cast<int>(a) * d, static_cast<int>(b) * d, d, d);
      }
    }
  }
  const double a[3][3] = {{0.3, -0.7, 0.2}, {0.5, 0.1, -0.4}, {-0.6, 0.8, 0.25}};  // not symmetric: strain and spin
  Eigen::VectorXd u(nodes * d);
  for (int n = 0; n < nodes; ++n) {
    for (int i = 0; i < d; ++i) {
      double v = 0.1 * (i + 1);
      for (int j = 0; j < d; ++j) v += a[i][j] * patch.nodes[static_cast<std::size_t>(n)][j];
      u(n * d + i) = v;
    }
  }
  const Eigen::VectorXd f = k * u;
  double worst = 0.0;
  int interior = 0;
  for (int n = 0; n < nodes; ++n) {
    if (!patch.interior[static_cast<std::size_t>(n)]) continue;
    ++interior;
    for (int i = 0; i < d; ++i) worst = std::max(worst, std::abs(f(n * d + i)));
  }
  EXPECT_GT(interior, 0);
  return worst / (k.cwiseAbs().maxCoeff() * u.cwiseAbs().maxCoeff());
}

void expect_patch_test(ElementType type) {
  Patch patch = patch_of(type);
  distort(patch, dimension(type), 0.18);
  ASSERT_EQ(patch.types.size(), patch.cells.size());
  EXPECT_LT(interior_residual(patch, false), 1e-13) << name(type);
  // The test can fail: with the Jacobian dropped the cells' different sizes weigh the fluxes
  // differently, and the linear field is no longer in equilibrium.
  EXPECT_GT(interior_residual(patch, true), 1e-3) << name(type);
}

TEST(LinearElements, PatchTestOnDistortedTriangles) { expect_patch_test(ElementType::tri3); }
TEST(LinearElements, PatchTestOnDistortedTetrahedra) { expect_patch_test(ElementType::tet4); }
TEST(LinearElements, PatchTestOnDistortedPrisms) { expect_patch_test(ElementType::wedge6); }
TEST(LinearElements, PatchTestOnDistortedPyramidsAmongHexes) { expect_patch_test(ElementType::pyramid5); }

// ---- eq. (35) ---------------------------------------------------------------------------------

TEST(LinearElements, RegularCellOfEveryTypeHasUnitShapeMeasure) {
  for (ElementType type : kTypes) {
    EXPECT_NEAR(element_shape(type, regular(type)).shape_measure, 1.0, 1e-14) << name(type);
    if (dimension(type) == 3) {  // rotated, scaled and shifted: still 1
      EXPECT_NEAR(element_shape(type, rotated_scaled(regular(type), 0.01)).shape_measure, 1.0, 1e-12) << name(type);
    }
    EXPECT_GT(element_shape(type, distorted(type)).shape_measure, 1.05) << name(type);
  }
}

TEST(LinearElements, ShapeMeasureGrowsWithStretching) {
  // A regular cell stretched by 2 along x: |phi_s| = (2^2 + d - 1)^(1/2) (1/4 + d - 1)^(1/2) / d
  // (T = diag(2, 1, ...) in the frame where the stretch acts).
  for (ElementType type : kTypes) {
    ElementPoints e = regular(type);
    for (int a = 0; a < e.count; ++a) e.p[static_cast<std::size_t>(a)].x *= 2.0;
    const double d = dimension(type);
    EXPECT_NEAR(element_shape(type, e).shape_measure, std::sqrt((4.0 + d - 1.0) * (0.25 + d - 1.0)) / d, 1e-13)
        << name(type);
  }
}

TEST(LinearElements, VolumeOfTheRegularCellsIsTheirVolume) {
  const double s = 0.3;  // edge
  const double expected[] = {std::sqrt(3.0) / 4.0 * s * s, s * s * s / (6.0 * std::sqrt(2.0)),
                             std::sqrt(3.0) / 4.0 * s * s * s, s * s * s / (3.0 * std::sqrt(2.0))};
  for (std::size_t t = 0; t < kTypes.size(); ++t) {
    const ElementType type = kTypes[t];
    ElementPoints e = regular(type);
    if (dimension(type) == 3) {
      e = rotated_scaled(e, s);
    } else {
      for (auto& p : e.p) p = s * p;
    }
    EXPECT_NEAR(element_shape(type, e).volume, expected[t], 1e-14) << name(type);
  }
}

TEST(LinearElements, MotionRefusesCellsOfAnotherDimensionNamingTheCell) {
  Mesh mesh = test::unit_cube(1);
  mesh.cells.add(ElementType::tri3, {0, 1, 2});
  try {
    move_mesh(mesh, {}, {}, {});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "cell 2 is a tri3: the mesh-motion solver moves 3D meshes of tet4, hex8, wedge6 and pyramid5 cells");
  }
}

}  // namespace
}  // namespace hotmesh::deform
