// Tests of the new OpenFOAM polyMesh written from a hex mesh (write_foam): read back by
// hotmesh's reader to the same points, cells and patches, in ASCII and binary; OpenFOAM's
// checkMesh passes it (skipped if OpenFOAM is not installed); 2D meshes and faces in no cell
// are refused naming the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "foam_fixtures.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using geometry::Vec3;
using mesh::NodeId;
using ::testing::HasSubstr;
namespace tf = test::foam;

/// An nx x ny x nz block of hexes, sheared a little, with patches inlet (x = 0), outlet
/// (x = max) and walls (the four other sides).
mesh::Mesh sheared_block(int nx, int ny, int nz) {
  mesh::Mesh m;
  const auto id = [&](int i, int j, int k) { return static_cast<NodeId>(i + (nx + 1) * (j + (ny + 1) * k)); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.points.push_back({i + 0.2 * j + 0.05 * i * k, j + 0.1 * k * k, 0.7 * k});
  const auto quad = [&](mesh::Patch& p, NodeId a, NodeId b, NodeId c, NodeId d) {
    p.faces.add(mesh::ElementType::quad4, {a, b, c, d});
  };
  mesh::Patch inlet{"inlet", 1, {}, {}}, outlet{"outlet", 2, {}, {}}, walls{"walls", 3, {}, {}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        m.cells.add(mesh::ElementType::hex8, {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                                              id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                                              id(i, j + 1, k + 1)});
        if (i == 0) quad(inlet, id(0, j, k), id(0, j, k + 1), id(0, j + 1, k + 1), id(0, j + 1, k));
        if (i == nx - 1) quad(outlet, id(nx, j, k), id(nx, j + 1, k), id(nx, j + 1, k + 1), id(nx, j, k + 1));
        if (j == 0) quad(walls, id(i, 0, k), id(i + 1, 0, k), id(i + 1, 0, k + 1), id(i, 0, k + 1));
        if (j == ny - 1) quad(walls, id(i, ny, k), id(i, ny, k + 1), id(i + 1, ny, k + 1), id(i + 1, ny, k));
        if (k == 0) quad(walls, id(i, j, 0), id(i, j + 1, 0), id(i + 1, j + 1, 0), id(i + 1, j, 0));
        if (k == nz - 1) quad(walls, id(i, j, nz), id(i + 1, j, nz), id(i + 1, j + 1, nz), id(i, j + 1, nz));
      }
  m.patches = {inlet, outlet, walls};
  m.derive_node_sets();
  return m;
}

/// Each element's nodes sorted, the list sorted: the elements as sets of nodes.
std::vector<std::vector<NodeId>> node_sets(const mesh::ElementList& elements, bool sort_list) {
  std::vector<std::vector<NodeId>> sets;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto nodes = elements.nodes(e);
    sets.emplace_back(nodes.begin(), nodes.end());
    std::sort(sets.back().begin(), sets.back().end());
  }
  if (sort_list) std::sort(sets.begin(), sets.end());
  return sets;
}

void expect_same_mesh(const mesh::Mesh& read, const mesh::Mesh& written) {
  EXPECT_EQ(read.points, written.points);
  EXPECT_EQ(node_sets(read.cells, false), node_sets(written.cells, false));  // cells keep their numbers
  ASSERT_EQ(read.patches.size(), written.patches.size());
  for (std::size_t p = 0; p < read.patches.size(); ++p) {
    EXPECT_EQ(read.patches[p].name, written.patches[p].name);
    EXPECT_EQ(node_sets(read.patches[p].faces, true), node_sets(written.patches[p].faces, true));
  }
}

TEST(FoamMeshWriter, AsciiAndBinaryReadBackToTheSameMesh) {
  test::TempDir dir;
  const mesh::Mesh m = sheared_block(4, 3, 2);
  write_foam(dir / "ascii" / "constant" / "polyMesh", m, m.points);
  write_foam(dir / "binary", m, m.points, {.binary = true});  // a case folder
  EXPECT_THAT(test::read_text(dir / "binary" / "constant" / "polyMesh" / "faces"), HasSubstr("faceCompactList"));
  const LoadedMesh ascii = read_mesh(dir / "ascii");
  EXPECT_EQ(ascii.validation.reoriented_cells, 0u);
  expect_same_mesh(ascii.mesh, m);
  expect_same_mesh(read_mesh(dir / "binary").mesh, m);
  const std::string boundary = test::read_text(dir / "ascii" / "constant" / "polyMesh" / "boundary");
  EXPECT_THAT(boundary, HasSubstr("inlet\n    {\n        type            patch;"));
  EXPECT_THAT(boundary, HasSubstr("walls\n    {\n        type            wall;"));
}

TEST(FoamMeshWriter, InternalFacesAreUpperTriangularAndPointFromOwnerToNeighbour) {
  test::TempDir dir;
  const mesh::Mesh m = sheared_block(3, 2, 2);
  write_foam(dir / "polyMesh", m, m.points);
  const std::string owner = test::read_text(dir / "polyMesh" / "owner");
  EXPECT_THAT(owner, HasSubstr("nPoints:36  nCells:12  nFaces:"));
  // Through write_mesh (a path named polyMesh is an OpenFOAM folder) and checkMesh.
  if (tf::block_mesh_command().empty()) GTEST_SKIP() << "OpenFOAM is not installed: scripts/install-deps.sh";
  tf::write_block_mesh_case(dir / "case", "");
  write_mesh(dir / "case" / "constant" / "polyMesh", m, m.points);
  const auto r = tf::check_mesh(dir / "case", dir / "case" / "constant" / "polyMesh", dir / "check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Mesh OK."));
  EXPECT_THAT(r.output, HasSubstr("Upper triangular ordering OK."));
}

TEST(FoamMeshWriter, BinaryPassesCheckMesh) {
  if (tf::block_mesh_command().empty()) GTEST_SKIP() << "OpenFOAM is not installed: scripts/install-deps.sh";
  test::TempDir dir;
  const mesh::Mesh m = sheared_block(5, 4, 3);
  tf::write_block_mesh_case(dir / "case", "", true);
  write_foam(dir / "case", m, m.points, {.binary = true});
  const auto r = tf::check_mesh(dir / "case", dir / "case" / "constant" / "polyMesh", dir / "check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Mesh OK."));
}

TEST(FoamMeshWriter, BoundaryFacesInNoPatchBecomeDefaultFaces) {
  test::TempDir dir;
  mesh::Mesh m = sheared_block(2, 2, 1);
  m.patches.pop_back();  // the walls
  write_foam(dir / "polyMesh", m, m.points);
  const mesh::Mesh read = read_mesh(dir / "polyMesh").mesh;
  ASSERT_EQ(read.patches.size(), 3u);
  EXPECT_EQ(read.patches[2].name, "defaultFaces");
  EXPECT_EQ(read.patches[2].faces.size(), 2u * (2 * 1) + 2u * (2 * 2));  // y sides, z sides
}

TEST(FoamMeshWriter, RefusesTwoDimensionalMeshesAndFacesInNoCellNamingTheFolder) {
  test::TempDir dir;
  mesh::Mesh flat;
  flat.dimension = 2;
  flat.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  flat.cells.add(mesh::ElementType::quad4, {0, 1, 2, 3});
  try {
    write_foam(dir / "flat" / "polyMesh", flat, flat.points);
    ADD_FAILURE() << "2D mesh written";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("flat/polyMesh"));
    EXPECT_THAT(e.what(), HasSubstr("3D meshes only"));
  }
  mesh::Mesh m = sheared_block(2, 1, 1);
  m.patches[0].faces.add(mesh::ElementType::quad4, {0, 4, 10, 6});  // a diagonal quad through a cell
  try {
    write_foam(dir / "bad" / "polyMesh", m, m.points);
    ADD_FAILURE() << "a face in no cell written";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad/polyMesh"));
    EXPECT_THAT(e.what(), HasSubstr("patch 'inlet' is not a boundary face of a cell"));
  }
}

}  // namespace
}  // namespace hotmesh::io
