// Tests of hotmesh::mesh::split_cells: the hybrid meshes it makes from quad and hex meshes are
// conforming (validate_mesh finds every face matched or in a patch), positively oriented, and
// fill exactly the cells they come from.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hybrid_meshes.hpp"
#include "test_support.hpp"

namespace hotmesh::mesh {
namespace {

/// Volume (3D) or area (2D) of a cell with planar faces: the pyramids from its centroid over
/// its outward faces (fans from each face's first corner).
double measure(ElementType type, const ElementPoints& e) {
  Vec3 c;
  for (int a = 0; a < e.count; ++a) c += e.p[static_cast<std::size_t>(a)];
  c = c / static_cast<double>(e.count);
  double sum = 0.0;
  for (const LocalFace& f : faces(type)) {
    const Vec3& a = e.p[f.nodes[0]];
    if (f.count == 2) {
      const Vec3& b = e.p[f.nodes[1]];
      sum += 0.5 * ((b - a).x * (c - a).y - (b - a).y * (c - a).x);
      continue;
    }
    for (std::size_t i = 1; i + 1 < f.count; ++i) {
      sum += dot(cross(e.p[f.nodes[i]] - a, e.p[f.nodes[i + 1]] - a), a - c) / 6.0;
    }
  }
  return sum;
}

double total_measure(const Mesh& mesh) {
  double sum = 0.0;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) sum += measure(mesh.cells.type(c), gather(mesh.cells.nodes(c), mesh.points));
  return sum;
}


/// Valid as validate_mesh sees it, nothing reoriented, every corner Jacobian positive.
void expect_valid_and_oriented(Mesh mesh) {
  const ValidationReport report = validate_mesh(mesh);
  EXPECT_EQ(report.reoriented_cells, 0u);
  test::expect_positively_oriented(mesh);
}

TEST(SplitCells, QuadsIntoTrianglesAnywhereKeepTheAreaAndTheEdges) {
  const Mesh quads = test::unit_square(4, 3);
  std::vector<CellSplit> split(quads.cell_count(), CellSplit::keep);
  for (std::size_t c = 0; c < split.size(); c += 2) split[c] = CellSplit::triangles;
  const Mesh hybrid = split_cells(quads, split);
  expect_valid_and_oriented(hybrid);
  EXPECT_EQ(test::type_counts(hybrid.cells), (std::map<ElementType, std::size_t>{{ElementType::tri3, 12}, {ElementType::quad4, 6}}));
  EXPECT_NEAR(total_measure(hybrid), 1.0, 1e-14);
  EXPECT_EQ(hybrid.patches, quads.patches);  // boundary edges are not split
}

TEST(SplitCells, PrismLayersUnderTetrahedraBesideHexesAreConforming) {
  // Layer z = 0: prisms; z = 1: tetrahedra (their bottoms triangulated as the prisms' tops);
  // z = 2: hexes and tetrahedra in a checkerboard (pyramids where a tetrahedral cell meets a hex).
  const Mesh hexes = test::unit_cube(3);
  std::vector<CellSplit> split(hexes.cell_count());
  for (std::size_t c = 0; c < split.size(); ++c) {
    const Vec3 p = hexes.points[static_cast<std::size_t>(hexes.cells.nodes(c)[0])];  // corner 0: the cell's lowest
    const int i = static_cast<int>(std::lround(p.x * 3)), j = static_cast<int>(std::lround(p.y * 3));
    const int k = static_cast<int>(std::lround(p.z * 3));
    split[c] = k == 0 ? CellSplit::prisms : k == 1 || (i + j) % 2 == 0 ? CellSplit::tetrahedra : CellSplit::keep;
  }
  const Mesh hybrid = split_cells(hexes, split);
  expect_valid_and_oriented(hybrid);
  const auto counts = test::type_counts(hybrid.cells);
  EXPECT_EQ(counts.at(ElementType::wedge6), 18u);
  EXPECT_EQ(counts.at(ElementType::hex8), 4u);
  // 14 cells about a centre, 6 faces each: 2 tetrahedra per triangulated face, 1 pyramid per quad.
  EXPECT_EQ(counts.at(ElementType::tet4) / 2 + counts.at(ElementType::pyramid5), 14u * 6u);
  EXPECT_GT(counts.at(ElementType::pyramid5), 0u);
  EXPECT_EQ(hybrid.node_count(), hexes.node_count() + 14u);
  EXPECT_NEAR(total_measure(hybrid), 1.0, 1e-14);
  // Patches keep their area: zmin all triangles (the prisms' ends), zmax quads and triangles.
  const auto zmin = test::type_counts(hybrid.find_patch("zmin")->faces);
  EXPECT_EQ(zmin, (std::map<ElementType, std::size_t>{{ElementType::tri3, 18}}));
  const auto zmax = test::type_counts(hybrid.find_patch("zmax")->faces);
  EXPECT_EQ(zmax.at(ElementType::quad4), 4u);
  EXPECT_EQ(zmax.at(ElementType::tri3), 10u);
}

TEST(SplitCells, PyramidsAboutTheCentreBesideHexesAndTetrahedraAreConforming) {
  const Mesh hexes = test::unit_cube(3);
  std::vector<CellSplit> split(hexes.cell_count(), CellSplit::pyramids);
  split[13] = CellSplit::tetrahedra;  // the middle cell: all its faces meet pyramids' bases
  split[0] = CellSplit::keep;
  const Mesh hybrid = split_cells(hexes, split);
  expect_valid_and_oriented(hybrid);
  const auto counts = test::type_counts(hybrid.cells);
  EXPECT_EQ(counts.at(ElementType::pyramid5), 25u * 6u + 6u);  // 25 cells of six, the middle one's six
  EXPECT_EQ(counts.count(ElementType::tet4), 0u);
  EXPECT_EQ(counts.at(ElementType::hex8), 1u);
  EXPECT_NEAR(total_measure(hybrid), 1.0, 1e-14);
}

TEST(SplitCells, AHexBesideAPrismsEndIsNotConforming) {
  const Mesh hexes = test::unit_cube(2);
  std::vector<CellSplit> split(hexes.cell_count(), CellSplit::keep);
  split[0] = CellSplit::prisms;  // its top meets the hex above as two triangles against a quad
  Mesh hybrid = split_cells(hexes, split);
  EXPECT_THROW(validate_mesh(hybrid), InputError);
}

TEST(SplitCells, SplitsACellHasNotAreRefused) {
  const Mesh quads = test::unit_square(1, 1);
  EXPECT_THROW(split_cells(quads, std::vector<CellSplit>{CellSplit::prisms}), std::invalid_argument);
  EXPECT_THROW(split_cells(quads, std::vector<CellSplit>{}), std::invalid_argument);
  const Mesh hexes = test::unit_cube(1);
  EXPECT_THROW(split_cells(hexes, std::vector<CellSplit>{CellSplit::triangles}), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::mesh
