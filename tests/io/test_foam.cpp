// Tests of reading OpenFOAM polyMesh folders (hotmesh/io/foam.hpp) written in code: the 2x1x1
// block in every file form the reader takes, and broken folders (prism cells, indices out of
// range, truncated files, missing files), which give an InputError naming the file and the
// problem, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "read_error.hpp"
#include "foam_fixtures.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using test::foam::block_2x1x1;
using test::foam::Layout;
using test::foam::write_poly_mesh;
using ::testing::HasSubstr;

/// The message of the InputError that reading `folder` throws ("" if none).
using test_io::read_error;

TEST(FoamReader, ReadsTheBlockAsTwoUnitCubesWithItsPatches) {
  test::TempDir dir;
  write_poly_mesh(dir / "polyMesh", block_2x1x1());
  const LoadedMesh loaded = read_mesh(dir / "polyMesh");
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.dimension, 3);
  ASSERT_EQ(m.node_count(), 12u);
  EXPECT_EQ(m.points[11].x, 2.0);
  ASSERT_EQ(m.cell_count(), 2u);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);  // built with positive volume
  const auto quality = mesh::scaled_jacobians(m.cells, m.points);
  for (const double q : quality) EXPECT_DOUBLE_EQ(q, 1.0);  // unit cubes, corners in hex8 order
  ASSERT_EQ(m.patches.size(), 3u);
  EXPECT_EQ(m.patches[0].name, "inlet");
  EXPECT_EQ(m.patches[0].faces.size(), 1u);
  EXPECT_EQ(m.patches[2].name, "walls");
  EXPECT_EQ(m.patches[2].faces.size(), 8u);
  EXPECT_EQ(m.find_patch("inlet")->nodes, (std::vector<mesh::NodeId>{0, 3, 6, 9}));
  ASSERT_NE(loaded.write_back, nullptr);
  EXPECT_THAT(loaded.write_back->output_names(),
              ::testing::ElementsAre("polyMesh/points", "polyMesh/boundary", "polyMesh/faces", "polyMesh/neighbour",
                                     "polyMesh/owner"));
}

TEST(FoamReader, EveryFileFormGivesTheSameMesh) {
  test::TempDir dir;
  write_poly_mesh(dir / "ascii", block_2x1x1());
  const mesh::Mesh ascii = read_mesh(dir / "ascii").mesh;
  const std::vector<std::pair<std::string, Layout>> layouts{
      {"binary", {.binary = true}},
      {"binary64", {.binary = true, .label_bits = 64}},
      {"binary_scalar32", {.binary = true, .scalar_bits = 32}},
      {"gz", {.gzip = true}},
      {"binary_gz_compact", {.binary = true, .gzip = true, .compact_faces = true}},
      {"ascii_compact", {.compact_faces = true}},
  };
  for (const auto& [name, layout] : layouts) {
    write_poly_mesh(dir / name, block_2x1x1(), layout);
    EXPECT_EQ(read_mesh(dir / name).mesh, ascii) << name;
  }
  // A gzipped folder lists its .gz files as inputs and outputs.
  EXPECT_THAT(read_mesh(dir / "gz").write_back->output_names(), ::testing::Contains("polyMesh/points.gz"));
}

TEST(FoamReader, ReadsACaseFolderAndListsThePolyMeshFilesAsInputs) {
  test::TempDir dir;
  write_poly_mesh(dir / "case" / "constant" / "polyMesh", block_2x1x1());
  test::write_text(dir / "case" / "constant" / "transportProperties", "nu 1e-5;\n");
  EXPECT_EQ(mesh_format(dir / "case"), MeshFormat::foam);
  EXPECT_EQ(read_mesh(dir / "case").mesh.cell_count(), 2u);
  const auto files = mesh_input_files(dir / "case");
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files.front(), dir / "case" / "constant" / "polyMesh" / "boundary");
}

TEST(FoamReader, ReadsUniformListsCommentsAndTypedLists) {
  // One cube: owner as the uniform list 6{0}, no neighbours, comments between tokens.
  test::TempDir dir;
  test::foam::PolyMeshData m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  m.owner = {0, 0, 0, 0, 0, 0};
  m.patches = {{"walls", "wall", 0, 6}};
  write_poly_mesh(dir / "p", m);
  const Layout ascii;
  test::write_text(dir / "p" / "owner",
                   test::foam::foam_header(ascii, "labelList", "owner") + "/* all */ 6 // six\n{0}\n");
  test::write_text(dir / "p" / "neighbour",
                   test::foam::foam_header(ascii, "labelList", "neighbour") + "List<label> 0()\n");
  const LoadedMesh loaded = read_mesh(dir / "p");
  EXPECT_EQ(loaded.mesh.cell_count(), 1u);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  EXPECT_DOUBLE_EQ(mesh::scaled_jacobians(loaded.mesh.cells, loaded.mesh.points)[0], 1.0);
}

TEST(FoamReaderErrors, APolyhedronWhoseFacesDoNotCloseIsNamedWithItsShape) {
  test::TempDir dir;
  auto open = test::foam::split_top_cube();
  open.faces.erase(open.faces.begin() + 2);  // one of the top's two triangles
  open.owner.pop_back();
  open.patches[0].count = 6;
  write_poly_mesh(dir / "p", open);
  const std::string error = read_error(dir / "p");
  EXPECT_THAT(error, HasSubstr("cell 0 has 6 faces (a polyhedron, faces of 4, 3, 4, 4, 4, 4 points) that do not "
                               "close a cell"));
}

TEST(FoamReaderErrors, APointIndexOutOfRangeNamesTheFaceAndTheFile) {
  test::TempDir dir;
  auto m = block_2x1x1();
  m.faces[4][2] = 99;
  write_poly_mesh(dir / "p", m);
  const std::string error = read_error(dir / "p");
  EXPECT_THAT(error, HasSubstr("faces"));
  EXPECT_THAT(error, HasSubstr("face 4 refers to point 99, but the points file has 12 points"));
}

TEST(FoamReaderErrors, InconsistentOwnersAndPatchesAreNamed) {
  test::TempDir dir;
  auto m = block_2x1x1();
  m.owner.pop_back();
  write_poly_mesh(dir / "owner", m);
  EXPECT_THAT(read_error(dir / "owner"), HasSubstr("10 cells are listed for 11 faces"));
  m = block_2x1x1();
  m.neighbour = {0};
  write_poly_mesh(dir / "self", m);
  EXPECT_THAT(read_error(dir / "self"), HasSubstr("face 0 has cell 0 as both owner and neighbour"));
  m = block_2x1x1();
  m.patches[2].count = 9;
  write_poly_mesh(dir / "patch", m);
  EXPECT_THAT(read_error(dir / "patch"), HasSubstr("boundary:"));
  EXPECT_THAT(read_error(dir / "patch"),
              HasSubstr("patch 'walls' has faces 3 to 11, but the boundary faces are 1 to 10"));
}

TEST(FoamReaderErrors, AMissingFileIsNamed) {
  test::TempDir dir;
  write_poly_mesh(dir / "p", block_2x1x1());
  std::filesystem::remove(dir / "p" / "neighbour");
  EXPECT_THAT(read_error(dir / "p"), HasSubstr("the polyMesh folder has no 'neighbour' file (nor neighbour.gz)"));
  EXPECT_THAT(read_error(dir / "nothing-here"), HasSubstr("unknown mesh format"));
  std::filesystem::create_directories(dir / "empty");
  EXPECT_THAT(read_error(dir / "empty"), HasSubstr("neither an OpenFOAM polyMesh folder"));
}

TEST(FoamReaderErrors, ABadHeaderNamesTheLine) {
  test::TempDir dir;
  write_poly_mesh(dir / "p", block_2x1x1());
  test::write_text(dir / "p" / "owner", "// no header\n11 (0 0 1 0 1 0 1 0 1 0 1)\n");
  EXPECT_THAT(read_error(dir / "p"), HasSubstr("owner:2: expected the FoamFile { ... } header"));
  test::write_text(dir / "p" / "owner", "FoamFile { format binary; arch \"MSB;label=32;scalar=64\"; }\n");
  EXPECT_THAT(read_error(dir / "p"), HasSubstr("big-endian"));
}

TEST(FoamReaderErrors, ACutListNamesTheLineOrTheByteOffset) {
  test::TempDir dir;
  write_poly_mesh(dir / "ascii", block_2x1x1());
  std::string text = test::read_text(dir / "ascii" / "owner");
  test::write_text(dir / "ascii" / "owner", text.substr(0, text.find("\n1\n0\n1\n0\n1\n)")));
  EXPECT_THAT(read_error(dir / "ascii"),
              HasSubstr("owner:15: the list of owner cells should hold 11 entries, but only 12 "
                        "bytes are left in the file: is it truncated?"));
  const std::size_t close = text.rfind(')');  // all 11 owners, no ')'
  test::write_text(dir / "ascii" / "owner", text.substr(0, close));
  const auto last_line = std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(close), '\n') + 1;
  EXPECT_THAT(read_error(dir / "ascii"),
              HasSubstr(fmt::format("owner:{}: the file ends where ')' was expected (the end "
                                    "of the list of owner cells (11 read, as its count says))",
                                    last_line)));
  write_poly_mesh(dir / "binary", block_2x1x1(), {.binary = true});
  text = test::read_text(dir / "binary" / "points");
  const std::size_t data = text.find("12\n(") + 4;
  test::write_text(dir / "binary" / "points", text.substr(0, data + 100));  // 4 points and a bit
  EXPECT_THAT(read_error(dir / "binary"),
              HasSubstr(fmt::format("points: byte {}: the list of points should hold 12 "
                                    "entries, but only 100 bytes are left in the file: is it "
                                    "truncated?",
                                    data - 4)));
}

/// Every file of the block cut at many places, ASCII and binary, plain and gzipped: always an
/// InputError naming that file.
TEST(FoamReaderErrors, TruncatedFilesGiveAnErrorNamingTheFile) {
  for (const Layout& layout : {Layout{}, Layout{.binary = true}, Layout{.binary = true, .gzip = true}}) {
    test::TempDir dir;
    write_poly_mesh(dir / "whole", block_2x1x1(), layout);
    for (const char* base : {"points", "faces", "owner", "neighbour", "boundary"}) {
      const std::string name = std::string(base) + (layout.gzip ? ".gz" : "");
      const std::string text = test::read_text(dir / "whole" / name);
      // Up to the list's closing parenthesis (only the trailing comment may go).
      const std::size_t end = layout.gzip ? text.size() : text.rfind(')') + 1;
      for (std::size_t cut = 0; cut < end; cut += std::max<std::size_t>(1, end / 40)) {
        const auto folder = dir / fmt::format("{}-{}", base, cut);
        std::filesystem::copy(dir / "whole", folder);
        test::write_text(folder / name, text.substr(0, cut));
        const std::string error = read_error(folder);
        EXPECT_THAT(error, HasSubstr(name)) << name << " cut at " << cut << " (binary " << layout.binary << ")";
      }
    }
  }
}

}  // namespace
}  // namespace hotmesh::io
