// Tests of the element stiffness (appendix, eqs. 28-35): symmetry, positive
// semi-definiteness with exactly the rigid-body null space, scaling of the dropped-Jacobian
// integral, and the invariance of the eq. (35) measures.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "element_matrices.hpp"
#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/material.hpp"
#include "test_support.hpp"

namespace hotmesh::deform {
namespace {

using test::rigid_modes;
using test::stiffness;

ElementPoints distorted_quad() {
  ElementPoints e;
  e.count = 4;
  e.p = {{{0, 0, 0}, {2.0, 0.3, 0}, {2.4, 1.7, 0}, {-0.2, 1.1, 0}}};
  return e;
}

ElementPoints distorted_hex() {
  ElementPoints e;
  e.count = 8;
  e.p = {{{0, 0, 0}, {1.3, 0.1, 0.05}, {1.2, 1.1, -0.1}, {0.1, 0.9, 0},
          {0.05, -0.1, 0.8}, {1.4, 0.0, 1.1}, {1.1, 1.2, 0.9}, {-0.1, 1.0, 1.2}}};
  return e;
}



void expect_psd_with_rigid_null_space(ElementType type, const ElementPoints& e, const Lame& lame, bool drop) {
  const int d = type == ElementType::quad4 ? 2 : 3;
  const Eigen::MatrixXd k = stiffness(type, e, lame, drop);
  EXPECT_LT((k - k.transpose()).norm(), 1e-13 * k.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k);
  const auto& values = eigen.eigenvalues();
  const double largest = values.maxCoeff();
  const int rigid = d == 2 ? 3 : 6;
  for (int i = 0; i < rigid; ++i) EXPECT_LT(std::abs(values(i)), 1e-12 * largest) << "eigenvalue " << i;
  EXPECT_GT(values(rigid), 1e-6 * largest) << "a zero-energy mode beyond the rigid-body ones";
  EXPECT_LT((k * rigid_modes(e, d)).norm(), 1e-12 * largest);
}

TEST(ElementStiffness, QuadIsSymmetricPsdWithRigidNullSpace) {
  for (bool drop : {true, false}) {
    expect_psd_with_rigid_null_space(ElementType::quad4, distorted_quad(), {0.5, 1.0}, drop);
    // lambda < 0 as eq. (35) gives with alpha_v << alpha_s: still positive bulk modulus
    expect_psd_with_rigid_null_space(ElementType::quad4, distorted_quad(), {-0.3, 0.5}, drop);
  }
}

TEST(ElementStiffness, HexIsSymmetricPsdWithRigidNullSpace) {
  for (bool drop : {true, false}) {
    expect_psd_with_rigid_null_space(ElementType::hex8, distorted_hex(), {0.5, 1.0}, drop);
    expect_psd_with_rigid_null_space(ElementType::hex8, distorted_hex(), {-0.3, 0.5}, drop);
  }
}

TEST(ElementStiffness, DroppedJacobianMakesSmallElementsStiffer) {
  // Scaling an element by s scales B by 1/s: K ~ 1/s^2 without the Jacobian, s^(d-2) with it.
  for (ElementType type : {ElementType::quad4, ElementType::hex8}) {
    ElementPoints e = type == ElementType::quad4 ? distorted_quad() : distorted_hex();
    const int d = type == ElementType::quad4 ? 2 : 3;
    ElementPoints small = e;
    for (auto& p : small.p) p = 0.1 * p;
    const Lame lame{0.2, 1.0};
    EXPECT_NEAR(stiffness(type, small, lame, true).norm() / stiffness(type, e, lame, true).norm(), 100.0, 1e-9);
    EXPECT_NEAR(stiffness(type, small, lame, false).norm() / stiffness(type, e, lame, false).norm(),
                std::pow(0.1, d - 2), 1e-12);
  }
}

TEST(ElementStiffness, UnitSquareMatchesClosedFormEntry) {
  // Standard plane-strain Q1 stiffness of the unit square (Jacobian kept), G = 1, lambda = 0:
  // K_00 = integral of (lambda + 2G) N,x^2 + G N,y^2 = 2/3 + 1/3 = 1 for the 2x2 rule.
  ElementPoints e;
  e.count = 4;
  e.p = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  const Eigen::MatrixXd k = stiffness(ElementType::quad4, e, {0.0, 1.0}, false);
  EXPECT_NEAR(k(0, 0), 1.0, 1e-14);
  // K_01 (x of node 0, y of node 0) = integral of (lambda + G) N,x N,y = 1/4
  EXPECT_NEAR(k(0, 1), 0.25, 1e-14);
}

TEST(Material, ShapeMeasureIsOneForSquaresAndCubesAndScaleInvariant) {
  const Mesh square = test::unit_square(1, 1);
  EXPECT_NEAR(element_shape(ElementType::quad4, gather(square.cells.nodes(0), square.points)).shape_measure, 1.0, 1e-14);
  const Mesh cube = test::unit_cube(1);
  EXPECT_NEAR(element_shape(ElementType::hex8, gather(cube.cells.nodes(0), cube.points)).shape_measure, 1.0, 1e-14);
  ElementPoints e = distorted_hex(), scaled = e;
  for (auto& p : scaled.p) p = 37.0 * p;
  const double phi = element_shape(ElementType::hex8, e).shape_measure;
  EXPECT_GT(phi, 1.0);
  EXPECT_NEAR(element_shape(ElementType::hex8, scaled).shape_measure, phi, 1e-12);
}

TEST(Material, LameParametersFollowEquation35AndGivePositiveBulkModulus) {
  // Two cells: 0.8 x 1 and 0.2 x 1.
  Mesh mesh = test::unit_square(2, 1);
  mesh.points[1].x = 0.8;  // left cell 0.8 x 1, right cell 0.2 x 1
  mesh.points[4].x = 0.8;
  const MaterialOptions options{StiffnessLaw::shape_volume, 2.0, 0.02, true};
  const auto lame = element_lame(mesh, options);
  for (std::size_t c = 0; c < 2; ++c) {
    const auto shape = element_shape(ElementType::quad4, gather(mesh.cells.nodes(c), mesh.points));
    EXPECT_NEAR(2.0 * lame[c].mu, options.alpha_s * shape.shape_measure, 1e-14);
    EXPECT_GT(lame[c].lambda + 2.0 * lame[c].mu / 3.0, 0.0);
  }
  // median of two volumes is the larger one here: the small cell has |phi_v| = 0.8 / 0.2 = 4
  EXPECT_NEAR(lame[1].lambda + 2.0 * lame[1].mu / 3.0, options.alpha_v * 4.0, 1e-14);
  EXPECT_NEAR(lame[0].lambda + 2.0 * lame[0].mu / 3.0, options.alpha_v * 1.0, 1e-14);
  // |phi_s| of an a x b rectangle: ||J||_F ||J^-1||_F / 2 = (a^2 + b^2) / (2ab)
  EXPECT_NEAR(2.0 * lame[0].mu, options.alpha_s * (0.64 + 1.0) / 1.6, 1e-12);
  EXPECT_NEAR(2.0 * lame[1].mu, options.alpha_s * (0.04 + 1.0) / 0.4, 1e-12);
}

TEST(Material, UniformAndInverseVolumeLaws) {
  Mesh mesh = test::unit_square(2, 1);
  mesh.points[1].x = 0.8;
  mesh.points[4].x = 0.8;
  const auto uniform = element_lame(mesh, {StiffnessLaw::uniform, 1.0, 0.5, false});
  EXPECT_DOUBLE_EQ(uniform[0].mu, 0.5);
  EXPECT_DOUBLE_EQ(uniform[1].mu, 0.5);
  const auto inverse = element_lame(mesh, {StiffnessLaw::inverse_volume, 1.0, 0.5, false});
  EXPECT_NEAR(inverse[1].mu / inverse[0].mu, 4.0, 1e-12);
}

TEST(Material, WallDistanceStiffensCellsByTheirDistanceToTheMovingWallsToThePowerP) {
  // The unit square as a row of 10 cells 0.1 x 1; the moving wall is its left edge x = 0.
  const Mesh mesh = test::unit_square(10, 1);
  std::vector<NodeId> wall;
  for (NodeId n = 0; n < static_cast<NodeId>(mesh.node_count()); ++n) {
    if (mesh.points[static_cast<std::size_t>(n)].x == 0.0) wall.push_back(n);
  }
  ASSERT_EQ(wall.size(), 2u);
  MaterialOptions options{StiffnessLaw::uniform, 1.0, 0.1, false};
  const auto paper = element_lame(mesh, options, wall);  // exponent 0: the wall plays no part
  EXPECT_EQ(paper[0].mu, paper[9].mu);
  for (const double p : {1.0, 1.5, 2.0}) {
    options.wall_distance_exponent = p;
    const auto stiffened = element_lame(mesh, options, wall);
    // Cell c's centre (0.1 c + 0.05, 0.5) lies as far from both wall nodes (0, 0) and (0, 1).
    const auto distance = [](double c) { return std::hypot(0.1 * c + 0.05, 0.5); };
    for (const int c : {1, 4, 9}) {
      const double expected = std::pow(distance(0) / distance(c), p);
      EXPECT_NEAR(stiffened[static_cast<std::size_t>(c)].mu / stiffened[0].mu, expected, 1e-12) << p << " " << c;
      EXPECT_NEAR(stiffened[static_cast<std::size_t>(c)].lambda / stiffened[0].lambda, expected, 1e-12) << p << " " << c;
    }
    const auto without_walls = element_lame(mesh, options);  // not stiffened
    for (std::size_t c = 0; c < paper.size(); ++c) EXPECT_EQ(without_walls[c].mu, paper[c].mu);
  }
}

}  // namespace
}  // namespace hotmesh::deform
