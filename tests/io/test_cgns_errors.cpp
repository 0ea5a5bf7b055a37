// Tests of CGNS input hotmesh cannot move: each gives an InputError naming the file and the
// zone, section or BC, and what is wrong.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "read_error.hpp"
#include "cgns_files.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/cgns.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

using test_io::read_error;

TEST(CgnsErrors, HigherOrderElementTypeNamesZoneSectionTypeAndCount) {
  test::TempDir dir;
  test::write_with_quadratic_triangles(dir / "tri.cgns");
  EXPECT_THAT(read_error(dir / "tri.cgns"),
              AllOf(HasSubstr((dir / "tri.cgns").string()), HasSubstr("zone 'Fluid' section 'Tris' holds 2 TRI_6"),
                    HasSubstr("hotmesh reads TRI_3 and QUAD_4 cells and BAR_2 boundary faces in a 2D base")));
}

TEST(CgnsErrors, BcNamingNoBoundaryFace) {
  test::TempDir dir;
  test::write_bc_without_faces(dir / "lonely.cgns");
  EXPECT_THAT(read_error(dir / "lonely.cgns"),
              AllOf(HasSubstr((dir / "lonely.cgns").string()), HasSubstr("zone 'Fluid' BC 'lonely'"),
                    HasSubstr("no boundary face")));
}

TEST(CgnsErrors, OneToOneInterfaceWhoseTransformJoinsNodesApart) {
  test::TempDir dir;
  test::write_structured_2d(dir / "wrong.cgns", true);
  EXPECT_THAT(read_error(dir / "wrong.cgns"),
              AllOf(HasSubstr((dir / "wrong.cgns").string()), HasSubstr("the connectivity of zone 'A'"),
                    HasSubstr("does not match point to point")));
}

TEST(CgnsErrors, MissingFile) {
  test::TempDir dir;
  EXPECT_THAT(read_error(dir / "none.cgns"), AllOf(HasSubstr((dir / "none.cgns").string()), HasSubstr("no such file")));
}

TEST(CgnsErrors, TextFileIsNotCgns) {
  test::TempDir dir;
  test::write_text(dir / "text.cgns", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
  EXPECT_THAT(read_error(dir / "text.cgns"), AllOf(HasSubstr((dir / "text.cgns").string()), HasSubstr("not a CGNS file")));
}

TEST(CgnsErrors, TruncatedFileIsAnInputError) {
  test::TempDir dir;
  test::write_structured_2d(dir / "s2.cgns");
  const std::string bytes = test::read_text(dir / "s2.cgns");
  test::write_text(dir / "cut.cgns", std::string_view(bytes).substr(0, bytes.size() / 2));
  EXPECT_THAT(read_error(dir / "cut.cgns"), HasSubstr((dir / "cut.cgns").string()));
}

TEST(CgnsErrors, WritingAVolumeCellInA2dMeshIsRefused) {
  test::TempDir dir;
  mesh::Mesh m;
  m.dimension = 2;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.cells.add(mesh::ElementType::tri3, {0, 1, 2});
  m.cells.add(mesh::ElementType::tet4, {0, 1, 2, 3});
  try {
    write_cgns(dir / "t.cgns", m, m.points);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cell 2 is a tet4 in a 2D mesh"));
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "t.cgns"));
}

}  // namespace
}  // namespace hotmesh::io
