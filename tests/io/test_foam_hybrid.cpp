// Tests of OpenFOAM polyMesh folders of hybrid meshes: single tetrahedra, pyramids and prisms
// written here read with Gmsh's node order and positive orientation; other polyhedra read as
// pieces about their centres; faces that do not close refused naming the cell; gmsh's hybrid box converted by OpenFOAM's
// gmshToFoam read with every cell type; the box written by hotmesh (ASCII and binary) passes
// checkMesh and reads back. The OpenFOAM parts are skipped if OpenFOAM is not installed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "read_error.hpp"
#include "foam_fixtures.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hybrid_meshes.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using mesh::ElementType;
using mesh::NodeId;
using ::testing::HasSubstr;
namespace tf = test::foam;

std::vector<NodeId> nodes_of(const mesh::Mesh& m, std::size_t c) {
  return {m.cells.nodes(c).begin(), m.cells.nodes(c).end()};
}

TEST(FoamHybrid, OneTetrahedronPyramidAndPrismGetGmshNodeOrderAndPositiveVolume) {
  test::TempDir dir;
  struct Case {
    const char* name;
    tf::PolyMeshData data;
    ElementType type;
    std::vector<NodeId> nodes;
    std::map<ElementType, std::size_t> faces;
  };
  const std::vector<Case> cases{
      // Bottom: the first triangle {0, 2, 1} (outward) reversed; apex 3.
      {"tet", tf::one_tetrahedron(), ElementType::tet4, {0, 1, 2, 3}, {{ElementType::tri3, 4}}},
      // Bottom: the quad {0, 3, 2, 1} reversed; apex 4.
      {"pyramid", tf::one_pyramid(), ElementType::pyramid5, {0, 1, 2, 3, 4},
       {{ElementType::tri3, 4}, {ElementType::quad4, 1}}},
      // Bottom: the first triangle {0, 2, 1} reversed; above 0, 1, 2 the points 3, 4, 5.
      {"prism", tf::one_prism(), ElementType::wedge6, {0, 1, 2, 3, 4, 5},
       {{ElementType::tri3, 2}, {ElementType::quad4, 3}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    tf::write_poly_mesh(dir / c.name, c.data);
    const LoadedMesh loaded = read_mesh(dir / c.name);
    ASSERT_EQ(loaded.mesh.cell_count(), 1u);
    EXPECT_EQ(loaded.mesh.cells.type(0), c.type);
    EXPECT_EQ(nodes_of(loaded.mesh, 0), c.nodes);
    EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
    test::expect_positively_oriented(loaded.mesh);
    mesh::ElementList faces;
    for (const mesh::Patch& p : loaded.mesh.patches) {
      for (std::size_t f = 0; f < p.faces.size(); ++f) faces.add(p.faces.type(f), p.faces.nodes(f));
    }
    EXPECT_EQ(test::type_counts(faces), c.faces);
  }
}

TEST(FoamHybrid, CellsOwnedAcrossAnInternalTriangleAreReadFromTheirReversedFaces) {
  // The tetrahedron of one_tetrahedron() and a second one below its base, sharing face
  // {0, 2, 1}: owned by cell 0 (normal -z, into cell 1), which cell 1 sees reversed; the
  // faces only close if it does.
  tf::PolyMeshData m = tf::one_tetrahedron();
  m.points.push_back({0.3, 0.3, -1});
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 1}, {1, 4, 2}, {2, 4, 0}};
  m.owner = {0, 0, 0, 0, 1, 1, 1};
  m.neighbour = {1};
  m.patches = {{"walls", "wall", 1, 6}};
  test::TempDir dir;
  tf::write_poly_mesh(dir / "p", m);
  const LoadedMesh loaded = read_mesh(dir / "p");
  ASSERT_EQ(loaded.mesh.cell_count(), 2u);
  EXPECT_EQ(test::type_counts(loaded.mesh.cells), (std::map<ElementType, std::size_t>{{ElementType::tet4, 2}}));
  EXPECT_EQ(nodes_of(loaded.mesh, 1), (std::vector<NodeId>{0, 1, 4, 2}));  // its first face {0, 4, 1} reversed
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  test::expect_positively_oriented(loaded.mesh);
}

using test_io::read_error;

TEST(FoamHybrid, APolyhedronIsReadAsPiecesAboutItsCentreAndMeasuredAsOneCell) {
  // The unit cube with its top split into two triangles: five pyramids on its quads and two
  // tetrahedra on its triangles, about a point added at its centre.
  test::TempDir dir;
  tf::write_poly_mesh(dir / "poly", tf::split_top_cube());
  const LoadedMesh loaded = read_mesh(dir / "poly");
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(test::type_counts(m.cells),
            (std::map<ElementType, std::size_t>{{ElementType::pyramid5, 5}, {ElementType::tet4, 2}}));
  ASSERT_EQ(m.node_count(), 9u);
  EXPECT_NEAR(geometry::norm(m.points[8] - geometry::Vec3{0.5, 0.5, 0.5}), 0.0, 1e-15);
  EXPECT_EQ(m.polyhedra.cells, std::vector<mesh::CellId>{0});
  EXPECT_EQ(m.polyhedra.file_points, 8u);
  EXPECT_EQ(m.polyhedra.piece_of, std::vector<mesh::CellId>(6, 0));
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  test::expect_positively_oriented(m);
  // The pieces fill the cube; the flow solver's measures are the cube's (aspect ratio 1; the
  // skewness of its top triangles, whose centres lie off the cell centre's normal line),
  // given to each piece.
  const mesh::SolverQuality q = mesh::solver_quality(m, m.points);
  EXPECT_EQ(q.summary.cells, 1u);
  EXPECT_EQ(q.summary.internal_faces, 0u);
  EXPECT_TRUE(q.by_type.empty());
  ASSERT_EQ(q.aspect_ratio.size(), 7u);
  for (const double a : q.aspect_ratio) EXPECT_NEAR(a, 1.0, 1e-12);
  EXPECT_GT(q.summary.max_skewness.value, 0.1);
  for (const double k : q.skewness) EXPECT_EQ(k, q.summary.max_skewness.value);
  tf::PolyMeshData flipped = tf::one_tetrahedron();
  std::swap(flipped.faces[3][1], flipped.faces[3][2]);  // the slanted face turned inward
  tf::write_poly_mesh(dir / "flipped", flipped);
  EXPECT_THAT(read_error(dir / "flipped"), HasSubstr("cell 0 has 4 faces that do not close a tet4"));
  tf::PolyMeshData pinched = tf::one_prism();
  pinched.faces[1] = {3, 4, 0};  // the top triangle reuses a bottom point: 5 points, not 6
  tf::write_poly_mesh(dir / "pinched", pinched);
  EXPECT_THAT(read_error(dir / "pinched"), HasSubstr("cell 0 has 5 faces that do not close a wedge6"));
}

/// Runs `command` on the case folder and fails the test with its output if it fails.
void run_in_case(const std::string& command, const std::filesystem::path& folder) {
  const auto r = test::run_command(command + " -case " + test::shell_quote(folder.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

TEST(FoamHybrid, GmshToFoamOfTheHybridBoxReadsEveryCellTypePositively) {
  if (tf::gmsh_to_foam_command().empty()) GTEST_SKIP() << "OpenFOAM is not installed: scripts/install-deps.sh";
  test::TempDir dir;
  const auto msh = test::hybrid_msh("hybrid_box", 3, dir.path(), "msh22");
  const mesh::Mesh gmsh = read_mesh(msh).mesh;
  tf::write_block_mesh_case(dir / "case", "");
  run_in_case(tf::gmsh_to_foam_command() + " " + test::shell_quote(msh.string()), dir / "case");
  const LoadedMesh loaded = read_mesh(dir / "case");
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(test::type_counts(m.cells), test::type_counts(gmsh.cells));
  EXPECT_EQ(test::type_counts(m.cells).size(), 4u);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  test::expect_positively_oriented(m);
  // The same cells as gmsh's, each as the set of its corners (OpenFOAM renumbers them).
  EXPECT_EQ(test::element_node_sets(m.cells, m.points), test::element_node_sets(gmsh.cells, gmsh.points));
  for (const mesh::Patch& p : gmsh.patches) {
    const mesh::Patch* q = m.find_patch(p.name);
    ASSERT_NE(q, nullptr) << p.name;
    EXPECT_EQ(test::element_node_sets(q->faces, m.points), test::element_node_sets(p.faces, gmsh.points)) << p.name;
  }
  EXPECT_EQ(test::type_counts(m.find_patch("bottom")->faces).size(), 2u);  // triangles and quads
}

TEST(FoamHybrid, TheHybridBoxWrittenByHotmeshPassesCheckMeshAndReadsBack) {
  test::TempDir dir;
  const mesh::Mesh m = read_mesh(test::hybrid_msh("hybrid_box", 3, dir.path())).mesh;
  for (const bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const auto folder = dir / (binary ? "binary" : "ascii");
    tf::write_block_mesh_case(folder, "", binary);
    write_foam(folder, m, m.points, {.binary = binary});
    const LoadedMesh back = read_mesh(folder);
    EXPECT_EQ(back.mesh.points, m.points);
    ASSERT_EQ(back.mesh.cell_count(), m.cell_count());
    for (std::size_t c = 0; c < m.cell_count(); ++c) {  // cells keep their numbers and types
      ASSERT_EQ(back.mesh.cells.type(c), m.cells.type(c)) << c;
      auto a = nodes_of(back.mesh, c), b = nodes_of(m, c);
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      ASSERT_EQ(a, b) << c;
    }
    EXPECT_EQ(back.validation.reoriented_cells, 0u);
    test::expect_positively_oriented(back.mesh);
    for (const mesh::Patch& p : m.patches) {
      const mesh::Patch* q = back.mesh.find_patch(p.name);
      ASSERT_NE(q, nullptr) << p.name;
      EXPECT_EQ(test::element_node_sets(q->faces, m.points), test::element_node_sets(p.faces, m.points)) << p.name;
    }
    if (tf::block_mesh_command().empty()) continue;
    const auto r = tf::check_mesh(folder, folder / "constant" / "polyMesh", dir / (binary ? "check-binary" : "check-ascii"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("Mesh OK."));
    EXPECT_THAT(r.output, HasSubstr("Upper triangular ordering OK."));
    EXPECT_THAT(r.output, HasSubstr("hexahedra:     16\n    prisms:        28\n"));
    EXPECT_THAT(r.output, HasSubstr("pyramids:      4\n"));
    EXPECT_THAT(r.output, HasSubstr("tetrahedra:    106\n    polyhedra:     0\n"));
  }
}

}  // namespace
}  // namespace hotmesh::io
