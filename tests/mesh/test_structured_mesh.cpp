// Tests of the structured block builders used by samples, benchmarks and tests.
#include <gtest/gtest.h>

#include <cmath>

#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/mesh/validate.hpp"

namespace hotmesh::mesh {
namespace {

TEST(StructuredLines, StretchedLineHasRequestedFirstSpacingAndEnds) {
  const auto y = stretched_line(0.0, 1.0, 40, 0.001);
  ASSERT_EQ(y.size(), 41u);
  EXPECT_EQ(y.front(), 0.0);
  EXPECT_EQ(y.back(), 1.0);
  EXPECT_NEAR(y[1] - y[0], 0.001, 1e-12);
  const double ratio = (y[2] - y[1]) / (y[1] - y[0]);
  for (std::size_t i = 2; i + 1 < y.size(); ++i) EXPECT_NEAR((y[i + 1] - y[i]) / (y[i] - y[i - 1]), ratio, 1e-9);
}

TEST(StructuredLines, GeometricLineWithUnitRatioIsUniform) {
  const auto x = uniform_line(-1.0, 3.0, 8);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], -1.0 + 0.5 * static_cast<double>(i), 1e-15);
}

TEST(StructuredMesh, QuadsAndHexesAreValidWithPatchesOnEverySide) {
  const auto x = uniform_line(0, 2, 4), y = stretched_line(0, 1, 5, 0.05), z = uniform_line(0, 1, 2);
  Mesh quads = structured_quads(x, y);
  EXPECT_EQ(quads.cell_count(), 20u);
  EXPECT_EQ(validate_mesh(quads).boundary_faces, 18u);
  Mesh hexes = structured_hexes(x, y, z);
  EXPECT_EQ(hexes.cell_count(), 40u);
  EXPECT_EQ(validate_mesh(hexes).boundary_faces, 2u * (20 + 8 + 10));
  EXPECT_EQ(validate_mesh(hexes).reoriented_cells, 0u);
  for (const Patch& p : hexes.patches) EXPECT_FALSE(p.faces.empty()) << p.name;
}

TEST(StructuredMesh, RejectsNonIncreasingCoordinates) {
  const std::vector<double> bad{0.0, 1.0, 1.0};
  const auto good = uniform_line(0, 1, 2);
  EXPECT_THROW(structured_quads(bad, good), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::mesh
