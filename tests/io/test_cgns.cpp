// Tests of reading CGNS meshes (hotmesh::io::read_cgns through read_mesh): unstructured zones
// with MIXED and boundary sections, BCs by points and by elements, families; structured zones
// joined by a 1-to-1 interface with a transform, or by coincident nodes; the files are written
// by tests/support/cgns_files.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "cgns_files.hpp"
#include "hotmesh/io/cgns.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

std::map<std::string, std::size_t> patch_faces(const mesh::Mesh& m) {
  std::map<std::string, std::size_t> faces;
  for (const auto& p : m.patches) faces[p.name] = p.faces.size();
  return faces;
}

void expect_positive_cells(const mesh::Mesh& m) {
  for (const double q : mesh::scaled_jacobians(m.cells, m.points)) EXPECT_GT(q, 0.99);
}

TEST(CgnsRead, Unstructured2dMixedSectionsAndBcsByPointsAndElements) {
  test::TempDir dir;
  test::write_unstructured_2d(dir / "u2.cgns");
  const LoadedMesh loaded = read_mesh(dir / "u2.cgns");
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.dimension, 2);
  EXPECT_EQ(m.node_count(), 12u);
  EXPECT_EQ(m.cell_count(), 6u);
  const std::map<std::string, std::size_t> expected{{"bottom", 3}, {"left", 2}, {"right", 2}, {"TopEdges", 3}};
  EXPECT_EQ(patch_faces(m), expected);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  expect_positive_cells(m);
  ASSERT_NE(loaded.write_back, nullptr);
  EXPECT_EQ(loaded.write_back->output_names(), std::vector<std::string>{"deformed.cgns"});
}

TEST(CgnsRead, Unstructured3dMixedHexesAndFacesWithAFamilyMergingFourBcs) {
  test::TempDir dir;
  test::write_unstructured_3d(dir / "u3.cgns");
  const LoadedMesh loaded = read_mesh(dir / "u3.cgns");
  EXPECT_EQ(loaded.mesh.dimension, 3);
  EXPECT_EQ(loaded.mesh.node_count(), 27u);
  EXPECT_EQ(loaded.mesh.cell_count(), 8u);
  const std::map<std::string, std::size_t> expected{{"floor", 4}, {"Casing", 16}, {"top", 4}};
  EXPECT_EQ(patch_faces(loaded.mesh), expected);
  expect_positive_cells(loaded.mesh);
}

TEST(CgnsRead, Structured2dZonesJoinedThroughOneToOneWithTransformShareInterfaceNodes) {
  test::TempDir dir;
  test::write_structured_2d(dir / "s2.cgns");
  const LoadedMesh loaded = read_mesh(dir / "s2.cgns");
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.node_count(), 21u);  // 12 + 12 - 3 shared on x = 1
  EXPECT_EQ(m.cell_count(), 12u);
  const std::map<std::string, std::size_t> expected{{"inlet", 2}, {"Walls", 6}, {"top", 6}, {"outlet", 2}};
  EXPECT_EQ(patch_faces(m), expected);
  // Zone B is left-handed: its cells are renumbered, not left to validation to flip.
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  expect_positive_cells(m);
  EXPECT_EQ(loaded.validation.boundary_faces, 16u);  // the interface is inside the mesh
}

TEST(CgnsRead, Structured3dZonesWithCoincidentInterfaceNodesAreMerged) {
  test::TempDir dir;
  test::write_structured_3d(dir / "s3.cgns");
  const LoadedMesh loaded = read_mesh(dir / "s3.cgns");
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.node_count(), 45u);  // 27 + 27 - 9 on x = 1
  EXPECT_EQ(m.cell_count(), 16u);
  const std::map<std::string, std::size_t> expected{{"xmin", 4}, {"xmax", 4}, {"ymin", 8},
                                                    {"ymax", 8}, {"zmin", 8}, {"zmax", 8}};
  EXPECT_EQ(patch_faces(m), expected);
  EXPECT_EQ(loaded.validation.boundary_faces, 40u);
  expect_positive_cells(m);
}

TEST(CgnsRead, UnstructuredZonesJoinedThroughAbuttingOneToOnePointLists) {
  test::TempDir dir;
  test::write_unstructured_two_zones(dir / "u2z.cgns", true);
  const LoadedMesh loaded = read_mesh(dir / "u2z.cgns");
  EXPECT_EQ(loaded.mesh.node_count(), 21u);  // 12 + 12 - 3 on x = 3
  EXPECT_EQ(loaded.mesh.cell_count(), 12u);
  const std::map<std::string, std::size_t> expected{{"left", 2}, {"Walls", 12}, {"right", 2}};
  EXPECT_EQ(patch_faces(loaded.mesh), expected);
  EXPECT_EQ(loaded.validation.boundary_faces, 16u);
}

TEST(CgnsRead, UnstructuredZonesWithoutConnectivityJoinAtCoincidentBoundaryNodes) {
  test::TempDir dir;
  test::write_unstructured_two_zones(dir / "u2z.cgns", false);
  const LoadedMesh loaded = read_mesh(dir / "u2z.cgns");
  EXPECT_EQ(loaded.mesh.node_count(), 21u);
  EXPECT_EQ(loaded.validation.boundary_faces, 16u);
  const std::map<std::string, std::size_t> expected{{"left", 2}, {"Walls", 12}, {"right", 2}};
  EXPECT_EQ(patch_faces(loaded.mesh), expected);
}

TEST(CgnsRead, PeriodicConnectionsJoinNoNodesAndBecomePatches) {
  test::TempDir dir;
  test::write_structured_periodic_2d(dir / "p.cgns");
  const LoadedMesh loaded = read_mesh(dir / "p.cgns");
  EXPECT_EQ(loaded.mesh.node_count(), 12u);
  EXPECT_EQ(loaded.mesh.cell_count(), 6u);
  const std::map<std::string, std::size_t> expected{{"inlet", 2}, {"outlet", 2}, {"per_lo", 3}, {"per_hi", 3}};
  EXPECT_EQ(patch_faces(loaded.mesh), expected);
}

TEST(CgnsRead, SummaryListsZonesSectionsBcsConnectionsAndFamilies) {
  test::TempDir dir;
  test::write_structured_2d(dir / "s2.cgns");
  const CgnsSummary s = describe_cgns(dir / "s2.cgns");
  ASSERT_EQ(s.bases.size(), 1u);
  EXPECT_EQ(s.file_type, "HDF5");
  const auto& base = s.bases[0];
  EXPECT_EQ(base.families, std::vector<std::string>{"Walls"});
  ASSERT_EQ(base.zones.size(), 2u);
  EXPECT_EQ(base.zones[1].type, "Structured");
  EXPECT_EQ(base.zones[1].size, (std::vector<std::int64_t>{3, 4, 2, 3, 0, 0}));
  ASSERT_EQ(base.zones[1].bcs.size(), 3u);
  EXPECT_EQ(base.zones[1].bcs[0].family, "Walls");
  EXPECT_EQ(base.zones[0].bcs[2].location, "EdgeCenter");
  ASSERT_EQ(base.zones[0].connections.size(), 1u);
  EXPECT_EQ(base.zones[0].connections[0].donor, "B");
  EXPECT_EQ(base.zones[0].solutions, 1);
}

}  // namespace
}  // namespace hotmesh::io
