// Tests of hotmesh::mesh::validate_mesh: each class of broken mesh gives an InputError
// naming the offending node, cell or patch; valid meshes pass, reversed ones are reoriented.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/core/input_error.hpp"
#include "test_support.hpp"

namespace hotmesh::mesh {
namespace {

using ::testing::HasSubstr;
using test::unit_cube;
using test::unit_square;

std::string validation_error(Mesh mesh) {
  try {
    validate_mesh(mesh);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

void reverse_all_cells(Mesh& mesh) {
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    auto nodes = mesh.cells.nodes(c);
    const auto perm = reversal(mesh.cells.type(c));
    std::vector<NodeId> old(nodes.begin(), nodes.end());
    for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i] = old[perm[i]];
  }
}

TEST(ValidateMesh, AcceptsStructuredSquareAndCube) {
  Mesh square = unit_square(4, 3);
  const auto r2 = validate_mesh(square);
  EXPECT_EQ(r2.reoriented_cells, 0u);
  EXPECT_EQ(r2.boundary_faces, 2u * (4 + 3));
  Mesh cube = unit_cube(3);
  const auto r3 = validate_mesh(cube);
  EXPECT_EQ(r3.boundary_faces, 6u * 9);
  EXPECT_EQ(cube.find_patch("zmax")->nodes.size(), 16u);
}

TEST(ValidateMesh, ReorientsMeshNumberedTheOtherWayRound) {
  for (Mesh mesh : {unit_square(3, 2), unit_cube(2)}) {
    const Mesh original = mesh;
    reverse_all_cells(mesh);
    const auto report = validate_mesh(mesh);
    EXPECT_EQ(report.reoriented_cells, mesh.cell_count());
    EXPECT_EQ(mesh.cells, original.cells);
    const auto q = summarize_quality(scaled_jacobians(mesh.cells, mesh.points));
    EXPECT_DOUBLE_EQ(q.min_scaled_jacobian, 1.0);
  }
}

TEST(ValidateMesh, ReorientsSingleReversedCellWhenConsistent) {
  // A 2D mesh whose left and right halves came from surfaces of opposite orientation.
  Mesh mesh = unit_square(4, 2);
  for (std::size_t c = 0; c < mesh.cells.size(); c += 4) {
    auto nodes = mesh.cells.nodes(c);
    std::swap(nodes[1], nodes[3]);
  }
  EXPECT_EQ(validate_mesh(mesh).reoriented_cells, 2u);
}

TEST(ValidateMesh, RejectsFoldedCellNamingIt) {
  Mesh mesh = unit_square(3, 3);
  mesh.points[5] = {2.5 / 3.0, 2.5 / 3.0, 0.0};  // interior node (1,1) pushed past node (2,2)
  const std::string error = validation_error(mesh);
  EXPECT_THAT(error, HasSubstr("3 cells are folded or degenerate"));
  EXPECT_THAT(error, HasSubstr("cell 5 (quad4) with nodes 6, 7, 11, 10 has scaled Jacobian -0.8"));
}

TEST(ValidateMesh, RejectsCellFlippedOverItsNeighbour) {
  // 1x2 strip: the top cell's far nodes are moved below the bottom cell, so the top cell is
  // mirrored as a whole. Reorienting it would hide a tangle: the shared edge shows it.
  Mesh mesh = unit_square(1, 2);
  mesh.points[4].y = -0.5;
  mesh.points[5].y = -0.5;
  mesh.patches.clear();  // the tangle must be found before boundary coverage
  const std::string error = validation_error(mesh);
  EXPECT_THAT(error, HasSubstr("same side"));
}

TEST(ValidateMesh, RejectsUnusedNode) {
  Mesh mesh = unit_square(2, 2);
  mesh.points.push_back({5, 5, 0});
  const std::string error = validation_error(mesh);
  EXPECT_THAT(error, HasSubstr("1 nodes are not used by any cell"));
  EXPECT_THAT(error, HasSubstr("node 10 at (5, 5, 0)"));
}

TEST(ValidateMesh, RejectsDuplicateNodes) {
  // Two unit squares side by side that do not share their common edge.
  Mesh mesh = unit_square(1, 1);
  const auto n = static_cast<NodeId>(mesh.points.size());
  for (int i = 0; i < 4; ++i) mesh.points.push_back(mesh.points[static_cast<std::size_t>(i)] + Vec3{1, 0, 0});
  mesh.cells.add(ElementType::quad4, {n, n + 1, n + 3, n + 2});
  const std::string error = validation_error(mesh);
  EXPECT_THAT(error, HasSubstr("2 pairs of nodes are duplicates"));
  EXPECT_THAT(error, HasSubstr("node 2 at (1, 0, 0) and node 5"));
}

TEST(ValidateMesh, FindsDuplicatesAcrossGridCellWalls) {
  // Nodes closer than the tolerance but on either side of a hash-grid wall are still found.
  Mesh mesh = unit_cube(1);
  for (Vec3 p : std::vector<Vec3>(mesh.points)) mesh.points.push_back(p + Vec3{1e-13, -1e-13, 1e-13});
  mesh.cells.add(ElementType::hex8, {8, 9, 11, 10, 12, 13, 15, 14});
  EXPECT_THAT(validation_error(mesh), HasSubstr("8 pairs of nodes are duplicates"));
}

TEST(ValidateMesh, RejectsBoundaryFaceWithoutPatch) {
  Mesh mesh = unit_cube(2);
  mesh.patches.erase(mesh.patches.begin() + 3);  // ymax
  const std::string error = validation_error(mesh);
  EXPECT_THAT(error, HasSubstr("4 boundary faces are not in any patch"));
}

TEST(ValidateMesh, RejectsPatchWithMissingNode) {
  Mesh mesh = unit_square(2, 2);
  mesh.patches[1].faces.add(ElementType::line2, {2, 42});
  const std::string error = validation_error(mesh);
  EXPECT_THAT(error, HasSubstr("patch 'xmax' face 3 refers to missing node index 42"));
}

TEST(ValidateMesh, RejectsPatchFaceThatIsNoCellFace) {
  Mesh mesh = unit_square(2, 2);
  mesh.patches[0].faces.add(ElementType::line2, {0, 8});
  EXPECT_THAT(validation_error(mesh), HasSubstr("patch 'xmin' face 3 (nodes 1, 9)"));
}

TEST(ValidateMesh, RejectsDuplicatePatchNames) {
  Mesh mesh = unit_square(2, 2);
  mesh.patches[1].name = "xmin";
  EXPECT_THAT(validation_error(mesh), HasSubstr("'xmin' names groups 1 and 2"));
}

TEST(ValidateMesh, RejectsNonFiniteCoordinates) {
  Mesh mesh = unit_cube(1);
  mesh.points[3].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(validation_error(mesh), HasSubstr("node 4 at (1, nan, 0)"));
}

/// The unit cube scaled by `scale` and moved by `shift` along x.
Mesh scaled_cube(double scale, double shift = 0.0) {
  Mesh mesh = unit_cube(2);
  for (Vec3& p : mesh.points) p = scale * p + Vec3{shift, 0.0, 0.0};
  return mesh;
}

// Issue 18, item 8: coordinates near 1e155 were reported as "190 pairs of nodes are
// duplicates (closer than inf)", near 1e-300 as "all nodes at the same point", and a scale of
// 1e100 later as a stiffness that is not positive definite.
TEST(ValidateMesh, NamesCoordinatesOutsideTheRangeItMovesMeshesAt) {
  EXPECT_THAT(validation_error(scaled_cube(1e155)), HasSubstr("the mesh reaches 1e+155 from the origin"));
  EXPECT_THAT(validation_error(scaled_cube(1e100)), HasSubstr("coordinates stay within 1e+30"));
  EXPECT_THAT(validation_error(scaled_cube(1e-300)), HasSubstr("the mesh is 1e-300 across"));
  EXPECT_THAT(validation_error(scaled_cube(1e-3, 1e10)),
              HasSubstr("the mesh is 0.001 across but lies 1e+10 from the origin"));
  Mesh point = unit_cube(1);
  for (Vec3& p : point.points) p = {1, 2, 3};
  EXPECT_THAT(validation_error(point), HasSubstr("all 8 nodes of the mesh are at the same point (1, 2, 3)"));
  // Micrometres to kilometres, in metres, and a part far from the engine axis.
  for (const double scale : {1e-6, 1.0, 1e3, 1e25}) EXPECT_EQ(validation_error(scaled_cube(scale)), "no error") << scale;
  EXPECT_EQ(validation_error(scaled_cube(1e-3, 1e4)), "no error");
}

TEST(ValidateMesh, RejectsTwoDimensionalMeshOffItsPlane) {
  Mesh mesh = unit_square(2, 2);
  mesh.points[4].z = 0.1;
  EXPECT_THAT(validation_error(mesh), HasSubstr("off the plane"));
}

TEST(ValidateMesh, RejectsNonManifoldFace) {
  Mesh mesh = unit_square(1, 1);
  mesh.points.push_back({0.5, -1.0, 0});
  mesh.points.push_back({0.6, -1.0, 0});
  mesh.cells.add(ElementType::quad4, {4, 5, 1, 0});  // below edge 0-1, fine
  mesh.points.push_back({0.5, -2.0, 0});
  mesh.cells.add(ElementType::tri3, {6, 1, 0});       // also below edge 0-1: three cells share it
  EXPECT_THAT(validation_error(mesh), HasSubstr("shared by more than two cells"));
}

}  // namespace
}  // namespace hotmesh::mesh
