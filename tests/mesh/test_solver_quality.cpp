// Tests of the flow solver's measures (mesh/solver_quality.hpp) on cells whose figures are
// known: sheared quads (non-orthogonality the shear angle, inside and at the boundary;
// skewness at the boundary only), boxes (aspect and volume ratios), a face whose centre is off the line between
// the cell centres (skewness), a 2D mesh measured as its one-layer extrusion of hexes and
// prisms, and invariance under a rigid motion and a scaling. tests/app/test_solver_quality.cpp
// compares them with OpenFOAM's checkMesh.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "hotmesh/mesh/solver_quality.hpp"
#include "test_support.hpp"

namespace hotmesh::mesh {
namespace {

constexpr double kDegree = 180.0 / std::numbers::pi;

/// A row of `n` parallelograms of unit width and height, their upper edges shifted by `shear`.
Mesh sheared_row(int n, double shear) {
  Mesh m;
  m.dimension = 2;
  for (int i = 0; i <= n; ++i) {
    m.points.push_back({double(i), 0, 0});
    m.points.push_back({double(i) + shear, 1, 0});
  }
  for (int i = 0; i < n; ++i) m.cells.add(ElementType::quad4, {2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1});
  return m;
}

/// Hexahedral boxes side by side along x with the given widths, `height` in y and `depth` in z.
Mesh boxes(const std::vector<double>& widths, double height, double depth) {
  Mesh m;
  double x = 0.0;
  for (std::size_t i = 0; i <= widths.size(); ++i) {
    for (const auto& [y, z] : {std::pair{0.0, 0.0}, {height, 0.0}, {height, depth}, {0.0, depth}}) m.points.push_back({x, y, z});
    if (i < widths.size()) x += widths[i];
  }
  for (int i = 0; i < static_cast<int>(widths.size()); ++i) {
    const int a = 4 * i, b = 4 * i + 4;
    // Bottom face 0-1-2-3 (z = 0), top above it: right-handed.
    m.cells.add(ElementType::hex8, {a, b, b + 1, a + 1, a + 3, b + 3, b + 2, a + 2});
  }
  return m;
}

TEST(SolverQuality, ShearedQuadsAreAsNonOrthogonalAsTheirShear) {
  for (const double shear : {0.0, 0.3, 1.0, 2.5}) {
    const Mesh m = sheared_row(4, shear);
    const SolverQuality q = solver_quality(m, m.points);
    const double angle = std::atan(shear) * kDegree;
    EXPECT_NEAR(q.summary.max_non_orthogonality.value, angle, 1e-9) << shear;
    EXPECT_NEAR(q.summary.mean_non_orthogonality, angle, 1e-9) << shear;
    EXPECT_EQ(q.summary.internal_faces, 3u);
    // The slanted ends: the line from the cell centre to the edge's middle is horizontal.
    EXPECT_NEAR(q.summary.max_boundary_non_orthogonality.value, angle, 1e-9) << shear;
    // The line between the centres crosses each internal face at its centre; a boundary face
    // is measured against the cell's mirror image across it: on the upper and lower edges the
    // cell centre lies shear/2 along the edge from the edge's middle, half an edge length.
    EXPECT_NEAR(q.summary.max_skewness.value, shear, 1e-12) << shear;
    EXPECT_NEAR(q.summary.max_volume_ratio.value, 1.0, 1e-12);
    EXPECT_EQ(q.summary.severely_non_orthogonal_faces, angle > kSevereNonOrthogonality ? 3u : 0u);
    for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(q.non_orthogonality[c], angle, 1e-9);
  }
}

TEST(SolverQuality, BoxesHaveTheirAspectAndVolumeRatios) {
  const Mesh m = boxes({1.0, 2.0, 0.5}, 1.0, 1.0);
  const SolverQuality q = solver_quality(m, m.points);
  EXPECT_NEAR(q.summary.max_non_orthogonality.value, 0.0, 1e-9);
  EXPECT_NEAR(q.summary.max_skewness.value, 0.0, 1e-12);
  // Face areas projected on x, y, z: a box a x 1 x 1 has 2, 2a, 2a; 1/6 of their sum over
  // V^(2/3) is at most that for these.
  EXPECT_NEAR(q.aspect_ratio[0], 1.0, 1e-12);
  EXPECT_NEAR(q.aspect_ratio[1], 2.0, 1e-12);
  EXPECT_NEAR(q.aspect_ratio[2], 2.0, 1e-12);  // 0.5 x 1 x 1: 2 against 1
  EXPECT_NEAR(q.summary.max_aspect_ratio.value, 2.0, 1e-12);
  EXPECT_NEAR(q.volume_ratio[0], 2.0, 1e-12);
  EXPECT_NEAR(q.volume_ratio[1], 4.0, 1e-12);  // 2 against 0.5
  EXPECT_NEAR(q.summary.max_volume_ratio.value, 4.0, 1e-12);
  EXPECT_EQ(q.summary.max_volume_ratio.cell, 1);
  // A flat cube: the hydraulic ratio of a 1 x 1 x 0.01 box, 1/6 (2 + 0.04) / 0.01^(2/3), is
  // below the projected ratio 100.
  const Mesh flat = boxes({1.0}, 1.0, 0.01);
  EXPECT_NEAR(solver_quality(flat, flat.points).aspect_ratio[0], 100.0, 1e-9);
}

TEST(SolverQuality, AFaceOffTheLineBetweenTheCentresIsSkewed) {
  // Two unit squares, the right one's upper corners raised by 1: a trapezoid. Its centre lies
  // above the line y = 0.5 through the left square's, so the line between the centres crosses
  // the common edge x = 1 above its middle.
  Mesh m;
  m.dimension = 2;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 3, 0}};
  m.cells.add(ElementType::quad4, {0, 1, 2, 3});
  m.cells.add(ElementType::quad4, {1, 4, 5, 2});
  const SolverQuality q = solver_quality(m, m.points);
  // The trapezoid (1,0) (2,0) (2,3) (1,1) of two parts of area 1, the square [1,2] x [0,1]
  // (centroid (1.5, 0.5)) and the triangle (1,1) (2,1) (2,3) (centroid (5/3, 5/3)): its centre
  // (19/12, 13/12).
  const double cx = 19.0 / 12.0, cy = 13.0 / 12.0;
  const double crossing = 0.5 + (cy - 0.5) * (1.0 - 0.5) / (cx - 0.5);  // y where the line meets x = 1
  const double sv = crossing - 0.5;                                     // from the face centre (1, 0.5)
  const double d = std::hypot(cx - 0.5, cy - 0.5);
  const double reach = std::max(0.2 * d, 0.5);  // the face's half length along it
  EXPECT_NEAR(q.skewness[0], sv / reach, 1e-12);
  EXPECT_NEAR(q.summary.max_non_orthogonality.value, std::atan2(cy - 0.5, cx - 0.5) * kDegree, 1e-9);
}

/// A 2D mesh's cells extruded over z in [0, depth]: quads to hexes, triangles to prisms.
Mesh extruded(const Mesh& flat, double depth) {
  Mesh m;
  const auto n = static_cast<NodeId>(flat.node_count());
  for (const Vec3& p : flat.points) m.points.push_back({p.x, p.y, 0.0});
  for (const Vec3& p : flat.points) m.points.push_back({p.x, p.y, depth});
  for (std::size_t c = 0; c < flat.cell_count(); ++c) {
    const auto v = flat.cells.nodes(c);
    if (v.size() == 4) {
      m.cells.add(ElementType::hex8, {v[0], v[1], v[2], v[3], v[0] + n, v[1] + n, v[2] + n, v[3] + n});
    } else {
      m.cells.add(ElementType::wedge6, {v[0], v[1], v[2], v[0] + n, v[1] + n, v[2] + n});
    }
  }
  return m;
}

TEST(SolverQuality, TwoDimensionalMeshMeasuresAsItsOneLayerExtrusion) {
  Mesh flat = test::hybrid_ring(4, 6, 1.0, 3.0, 0, 0.0, 1.3, 2);
  test::jiggle_interior(flat, 0.3);
  const Mesh layer = extruded(flat, 0.37);
  const SolverQuality q2 = solver_quality(flat, flat.points, Extrusion{{}, {{0, 0, 0.37}}});
  const SolverQuality q3 = solver_quality(layer, layer.points);
  ASSERT_EQ(q2.non_orthogonality.size(), q3.non_orthogonality.size());
  for (std::size_t c = 0; c < q2.non_orthogonality.size(); ++c) {
    EXPECT_NEAR(q2.non_orthogonality[c], q3.non_orthogonality[c], 1e-9) << c;
    EXPECT_NEAR(q2.skewness[c], q3.skewness[c], 1e-9) << c;
    EXPECT_NEAR(q2.volume_ratio[c], q3.volume_ratio[c], 1e-9) << c;
  }
  EXPECT_NEAR(q2.summary.mean_non_orthogonality, q3.summary.mean_non_orthogonality, 1e-9);
  EXPECT_GT(q2.summary.max_non_orthogonality.value, 5.0);
  EXPECT_EQ(q2.by_type.size(), 2u);  // quads and triangles
  // The slab's thickness and side do not matter.
  const SolverQuality thin = solver_quality(flat, flat.points, Extrusion{{{0, 0, 1}}, {{0, 0, 0.9}}});
  EXPECT_NEAR(thin.summary.max_non_orthogonality.value, q2.summary.max_non_orthogonality.value, 1e-9);
  EXPECT_NEAR(thin.summary.max_aspect_ratio.value, q2.summary.max_aspect_ratio.value, 1e-9);
}

TEST(SolverQuality, RigidMotionAndScalingChangeNoAngleOrRatio) {
  Mesh m = test::hybrid_ring(3, 4, 1.0, 2.5, 3, 1.0, 1.2, 2);
  test::jiggle_interior(m, 0.3);
  const SolverQuality q = solver_quality(m, m.points);
  std::vector<Vec3> moved;
  const double a = 0.7, s = 3.5;
  for (const Vec3& p : m.points) {
    moved.push_back(Vec3{s * (std::cos(a) * p.x - std::sin(a) * p.z), s * p.y, s * (std::sin(a) * p.x + std::cos(a) * p.z)} +
                    Vec3{10, -4, 2});
  }
  const SolverQuality r = solver_quality(m, moved);
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    EXPECT_NEAR(q.non_orthogonality[c], r.non_orthogonality[c], 1e-7) << c;
    EXPECT_NEAR(q.skewness[c], r.skewness[c], 1e-9) << c;
    EXPECT_NEAR(q.volume_ratio[c], r.volume_ratio[c], 1e-9) << c;
  }
  EXPECT_GE(q.by_type.size(), 3u);
  EXPECT_GT(q.summary.max_skewness.value, 0.05);
}

}  // namespace
}  // namespace hotmesh::mesh
