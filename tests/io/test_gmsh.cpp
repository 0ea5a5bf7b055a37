// Tests of hotmesh::io's Gmsh reader and writer against the real gmsh (4.8.4, a required test
// dependency): meshes of tests/data/gmsh/*.geo saved by gmsh in formats 2.2 and 4.1, ASCII and
// binary, all read to the same valid mesh with the counts the .geo files imply; our files
// read back equal (ASCII and binary) and gmsh opens them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "test_support.hpp"

namespace hotmesh::geometry {
void PrintTo(const Vec3& p, std::ostream* out) { *out << "(" << p.x << ", " << p.y << ", " << p.z << ")"; }
}  // namespace hotmesh::geometry

namespace hotmesh::io {
namespace {

using mesh::ElementList;
using mesh::ElementType;
using mesh::Mesh;
using test::TempDir;

struct Flavour {
  const char* format;  // gmsh's -format value
  bool binary;
  const char* label;
};
constexpr Flavour kFlavours[] = {{"msh22", false, "2.2 ASCII"},
                                 {"msh22", true, "2.2 binary"},
                                 {"msh41", false, "4.1 ASCII"},
                                 {"msh41", true, "4.1 binary"}};

/// A path quoted for the shell.
std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

/// Runs gmsh with `arguments`; fails the test (with gmsh's output) if it does not succeed.
void run_gmsh(const std::string& arguments, const TempDir& dir) {
  const auto log = dir / "gmsh.log";
  const std::string command = "gmsh " + arguments + " > " + quoted(log) + " 2>&1";
  const int status = std::system(command.c_str());
  std::string output;
  if (std::filesystem::exists(log)) output = test::read_text(log);
  ASSERT_EQ(status, 0) << "gmsh is a required test dependency (scripts/install-deps.sh); `" << command << "` failed:\n"
                       << output;
}

/// Meshes tests/data/gmsh/<name>.geo in `dimension` with gmsh and returns the file it wrote.
std::filesystem::path mesh_with_gmsh(const std::string& name, int dimension, const Flavour& flavour, const TempDir& dir,
                                     const std::string& extra = "") {
  const auto out = dir / (name + "-" + flavour.format + (flavour.binary ? "-bin" : "") + ".msh");
  run_gmsh("-" + std::to_string(dimension) + " -nt 1 " + quoted(test::data_path("gmsh/" + name + ".geo")) +
               " -format " + flavour.format + (flavour.binary ? " -bin " : " ") + extra + " -o " + quoted(out),
           dir);
  return out;
}

/// Points equal up to the last bit: gmsh writes ASCII with 16 digits, which does not always
/// give back the double its binary files hold.
void expect_same_points(const Mesh& a, const Mesh& b, const std::string& label) {
  ASSERT_EQ(a.points.size(), b.points.size()) << label;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a.points[i][k], b.points[i][k], 1e-15 * std::max(1.0, std::abs(a.points[i][k])))
          << label << ", node " << i;
    }
  }
  EXPECT_EQ(a.node_ids, b.node_ids) << label;
}

/// A mesh in terms of coordinates only: each element as its type and node coordinates (in
/// element order, rounded to 1e-9 as gmsh's ASCII output is not exact), sorted; so meshes equal
/// up to node/element numbering and order compare equal.
using Shape = std::pair<ElementType, std::vector<std::array<double, 3>>>;
std::vector<Shape> shapes(const ElementList& list, const std::vector<geometry::Vec3>& points) {
  std::vector<Shape> result;
  for (std::size_t i = 0; i < list.size(); ++i) {
    Shape s{list.type(i), {}};
    for (mesh::NodeId n : list.nodes(i)) {
      const geometry::Vec3& p = points[static_cast<std::size_t>(n)];
      auto round = [](double v) { return std::round(v * 1e9) / 1e9; };
      s.second.push_back({round(p.x), round(p.y), round(p.z)});
    }
    result.push_back(std::move(s));
  }
  std::sort(result.begin(), result.end());
  return result;
}
struct Geometry {
  int dimension = 0;
  std::vector<Shape> cells;
  std::map<std::string, std::vector<Shape>> patches;
  std::map<std::string, std::vector<Shape>> groups;
  std::map<std::string, int> tags;
  friend bool operator==(const Geometry&, const Geometry&) = default;
};
Geometry geometry_of(const Mesh& mesh) {
  Geometry g;
  g.dimension = mesh.dimension;
  g.cells = shapes(mesh.cells, mesh.points);
  for (const mesh::Patch& p : mesh.patches) {
    g.patches[p.name] = shapes(p.faces, mesh.points);
    g.tags["patch " + p.name] = p.tag;
  }
  for (const mesh::CellGroup& group : mesh.cell_groups) {
    ElementList cells;
    for (mesh::CellId c : group.cells)
      cells.add(mesh.cells.type(static_cast<std::size_t>(c)), mesh.cells.nodes(static_cast<std::size_t>(c)));
    g.groups[group.name] = shapes(cells, mesh.points);
    g.tags["group " + group.name] = group.tag;
  }
  return g;
}

std::size_t count_type(const Mesh& mesh, ElementType type) {
  return static_cast<std::size_t>(std::count(mesh.cells.types().begin(), mesh.cells.types().end(), type));
}

std::vector<mesh::CellId> all_cells(std::size_t n) {
  std::vector<mesh::CellId> cells(n);
  for (std::size_t i = 0; i < n; ++i) cells[i] = static_cast<mesh::CellId>(i);
  return cells;
}

/// Reads the four flavours gmsh writes of one .geo and checks they give the same mesh. ASCII and
/// binary of one version give the same mesh (up to the last bit of coordinates); 2.2 and 4.1 may
/// list elements in another order (2.2 sorts them by type, 4.1 by geometric entity) and give
/// repeated elements their own tags, so across versions elements are compared as sets.
Mesh read_all_flavours(const std::string& name, int dimension, const TempDir& dir) {
  std::vector<Mesh> meshes;
  for (const Flavour& flavour : kFlavours) {
    meshes.push_back(read_gmsh(mesh_with_gmsh(name, dimension, flavour, dir)));
  }
  for (std::size_t i = 1; i < meshes.size(); ++i) {
    const std::string label = name + ": " + kFlavours[0].label + " vs " + kFlavours[i].label;
    expect_same_points(meshes[0], meshes[i], label);
    EXPECT_EQ(geometry_of(meshes[0]), geometry_of(meshes[i])) << label;
    EXPECT_EQ(meshes[0].cell_count(), meshes[i].cell_count()) << label;
  }
  for (std::size_t i : {1u, 3u}) {  // binary against ASCII of the same version
    Mesh binary = meshes[i];
    binary.points = meshes[i - 1].points;
    EXPECT_EQ(binary, meshes[i - 1]) << name << ": " << kFlavours[i].label;
  }
  return meshes[2];
}

std::string gmsh_string(const Mesh& mesh, bool binary) {
  std::ostringstream out;
  write_gmsh(out, mesh, {.binary = binary});
  return out.str();
}

// ---- the real gmsh writes, we read ------------------------------------------------------

TEST(GmshFromGmsh, QuadChannelIsTheSameInAllFourFormats) {
  TempDir dir;
  Mesh mesh = read_all_flavours("quad_channel", 2, dir);
  constexpr std::size_t nx = 10, ny = 4;  // quad_channel.geo
  EXPECT_EQ(mesh.dimension, 2);
  EXPECT_EQ(mesh.node_count(), (nx + 1) * (ny + 1));
  EXPECT_EQ(mesh.cell_count(), nx * ny);  // not 2 * nx * ny: each cell is in two groups
  EXPECT_EQ(count_type(mesh, ElementType::quad4), nx * ny);
  ASSERT_EQ(mesh.patches.size(), 4u);
  EXPECT_EQ(mesh.patches[0].name, "inlet");
  EXPECT_EQ(mesh.patches[0].faces.size(), ny);
  EXPECT_EQ(mesh.patches[1].name, "outlet");
  EXPECT_EQ(mesh.patches[2].name, "walls");
  EXPECT_EQ(mesh.patches[2].faces.size(), 2 * nx);
  EXPECT_EQ(mesh.patches[3].name, "floor");
  EXPECT_EQ(mesh.patches[3].tag, 4);
  EXPECT_EQ(mesh.patches[3].faces.size(), nx);
  EXPECT_EQ(mesh.patches[3].nodes.size(), nx + 1);
  ASSERT_EQ(mesh.cell_groups.size(), 2u);
  EXPECT_EQ(mesh.cell_groups[0].name, "fluid");
  EXPECT_EQ(mesh.cell_groups[1].name, "zone");
  EXPECT_EQ(mesh.cell_groups[0].cells, all_cells(nx * ny));
  EXPECT_EQ(mesh.cell_groups[1].cells, all_cells(nx * ny));
  for (const geometry::Vec3& p : mesh.points) EXPECT_EQ(p.z, 0.0);

  const auto report = mesh::validate_mesh(mesh);
  EXPECT_EQ(report.boundary_faces, 2 * (nx + ny));
  const auto q = mesh::summarize_quality(mesh::scaled_jacobians(mesh.cells, mesh.points));
  EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-9);  // all rectangles
}

TEST(GmshFromGmsh, ExtrudedHexBoxIsTheSameInAllFourFormats) {
  TempDir dir;
  Mesh mesh = read_all_flavours("hex_box", 3, dir);
  constexpr std::size_t nx = 6, ny = 3, nz = 2;  // hex_box.geo
  EXPECT_EQ(mesh.dimension, 3);
  EXPECT_EQ(mesh.node_count(), (nx + 1) * (ny + 1) * (nz + 1));
  EXPECT_EQ(count_type(mesh, ElementType::hex8), nx * ny * nz);
  EXPECT_EQ(mesh.cell_count(), nx * ny * nz);
  ASSERT_EQ(mesh.patches.size(), 5u);
  const std::array<std::pair<const char*, std::size_t>, 5> expected{
      {{"bottom", nx * ny}, {"top", nx * ny}, {"xmin", ny * nz}, {"xmax", ny * nz}, {"sides", 2 * nx * nz}}};
  for (std::size_t p = 0; p < expected.size(); ++p) {
    EXPECT_EQ(mesh.patches[p].name, expected[p].first);
    EXPECT_EQ(mesh.patches[p].tag, static_cast<int>(p) + 1);
    EXPECT_EQ(mesh.patches[p].faces.size(), expected[p].second) << expected[p].first;
    for (ElementType t : mesh.patches[p].faces.types()) EXPECT_EQ(t, ElementType::quad4);
  }
  ASSERT_EQ(mesh.cell_groups.size(), 1u);
  EXPECT_EQ(mesh.cell_groups[0].name, "solid");
  EXPECT_EQ(mesh.cell_groups[0].tag, 20);
  EXPECT_EQ(mesh.cell_groups[0].cells.size(), nx * ny * nz);

  const auto report = mesh::validate_mesh(mesh);
  EXPECT_EQ(report.boundary_faces, 2 * (nx * ny + ny * nz + nx * nz));
  EXPECT_EQ(report.interior_patch_faces, 0u);
}

TEST(GmshFromGmsh, MixedHexPrismMeshIsTheSameInAllFourFormats) {
  TempDir dir;
  Mesh mesh = read_all_flavours("hex_prism", 3, dir);
  EXPECT_EQ(count_type(mesh, ElementType::hex8), 12u);    // 2 x 2 quads x 3 layers (hex_prism.geo)
  EXPECT_EQ(count_type(mesh, ElementType::wedge6), 24u);  // 8 triangles x 3 layers
  EXPECT_EQ(mesh.cell_count(), 36u);
  ASSERT_EQ(mesh.patches.size(), 6u);
  const ElementList& bottom = mesh.patches[0].faces;
  EXPECT_EQ(bottom.size(), 12u);
  EXPECT_EQ(std::count(bottom.types().begin(), bottom.types().end(), ElementType::tri3), 8);
  EXPECT_EQ(std::count(bottom.types().begin(), bottom.types().end(), ElementType::quad4), 4);
  EXPECT_EQ(mesh.patches[4].name, "front");
  EXPECT_EQ(mesh.patches[4].faces.size(), 12u);
  ASSERT_EQ(mesh.cell_groups.size(), 2u);
  EXPECT_EQ(mesh.cell_groups[0].name, "hexes");
  EXPECT_EQ(mesh.cell_groups[0].cells.size(), 12u);
  EXPECT_EQ(mesh.cell_groups[1].name, "prisms");
  EXPECT_EQ(mesh.cell_groups[1].cells.size(), 24u);
  for (mesh::CellId c : mesh.cell_groups[1].cells) {
    EXPECT_EQ(mesh.cells.type(static_cast<std::size_t>(c)), ElementType::wedge6);
  }
  const auto report = mesh::validate_mesh(mesh);
  EXPECT_EQ(report.boundary_faces, 60u);
}

TEST(GmshFromGmsh, TetCubeIsTheSameInAllFourFormatsAndFillsTheCube) {
  TempDir dir;
  Mesh mesh = read_all_flavours("tet_cube", 3, dir);
  ASSERT_GT(mesh.cell_count(), 100u);
  EXPECT_EQ(count_type(mesh, ElementType::tet4), mesh.cell_count());
  ASSERT_EQ(mesh.patches.size(), 1u);
  for (ElementType t : mesh.patches[0].faces.types()) EXPECT_EQ(t, ElementType::tri3);
  const auto report = mesh::validate_mesh(mesh);  // also reorients
  EXPECT_EQ(report.boundary_faces, mesh.patches[0].faces.size());
  double volume = 0.0;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const auto e = mesh::gather(mesh.cells.nodes(c), mesh.points);
    volume += geometry::triple(e.p[1] - e.p[0], e.p[2] - e.p[0], e.p[3] - e.p[0]) / 6.0;
  }
  EXPECT_NEAR(volume, 1.0, 1e-12);
}

TEST(GmshFromGmsh, ParametricCoordinatesAreSkipped) {
  TempDir dir;
  for (const Flavour& flavour : {kFlavours[2], kFlavours[3]}) {
    const Mesh plain = read_gmsh(mesh_with_gmsh("quad_channel", 2, flavour, dir));
    const auto path = dir / (std::string("parametric-") + (flavour.binary ? "bin" : "ascii") + ".msh");
    run_gmsh("-2 -nt 1 " + quoted(test::data_path("gmsh/quad_channel.geo")) + " -format msh41 -parametric" +
                 (flavour.binary ? " -bin" : "") + " -o " + quoted(path),
             dir);
    EXPECT_THAT(test::read_text(path), ::testing::HasSubstr(flavour.binary ? "$Nodes" : "\n1 1 1 9\n"));
    EXPECT_EQ(read_gmsh(path), plain) << flavour.label;
  }
}

TEST(GmshFromGmsh, PartitionedMeshIsReadWholeFrom22AndRejectedFrom41) {
  TempDir dir;
  const Mesh whole = read_gmsh(mesh_with_gmsh("hex_box", 3, kFlavours[0], dir));
  const auto v2 = mesh_with_gmsh("hex_box", 3, kFlavours[0], dir, "-part 2");
  // 2.2 lists each element once, with its partition as extra tags: the mesh is complete.
  EXPECT_EQ(geometry_of(read_gmsh(v2)), geometry_of(whole));
  const auto v4 = mesh_with_gmsh("hex_box", 3, kFlavours[2], dir, "-part 2");
  try {
    read_gmsh(v4);
    FAIL() << "a partitioned 4.1 file was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr(v4.string() + ":"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("partitioned meshes are not supported"));
  }
}

// ---- we write, we read ------------------------------------------------------------------

/// Mesh ids as the reader gives them: the file's tags, here 1, 2, 3, ...
Mesh with_default_ids(Mesh mesh) {
  mesh.node_ids.resize(mesh.node_count());
  for (std::size_t i = 0; i < mesh.node_count(); ++i) mesh.node_ids[i] = static_cast<std::int64_t>(i) + 1;
  mesh.cell_ids.resize(mesh.cell_count());
  for (std::size_t i = 0; i < mesh.cell_count(); ++i) mesh.cell_ids[i] = static_cast<std::int64_t>(i) + 1;
  return mesh;
}

/// A 3D mesh exercising what the writer must keep: sparse node tags (some far beyond the node
/// count, but below 2^31: gmsh 4.8.4 crashes on larger ones), cell tags out of order, hexes and prisms interleaved,
/// cells in zero, one and two groups, a patch of mixed quads and triangles, a patch and a group without elements,
/// non-round coordinates.
Mesh awkward_mesh() {
  Mesh mesh = test::unit_cube(2);  // 27 nodes, 8 hexes, 6 patches
  const std::size_t n = mesh.node_count();
  for (std::size_t i = 0; i < n; ++i) {
    geometry::Vec3& p = mesh.points[i];
    p = p * (1.0 / 3.0) + geometry::Vec3{0.1, -1e-300, 1e17};
    p.x += 1e-9 * static_cast<double>(i);
    mesh.node_ids.push_back(i % 5 == 0 ? std::int64_t{2'000'000'000} + static_cast<std::int64_t>(i)
                                       : 7 * static_cast<std::int64_t>(n - i));
  }
  // Two prisms on top of the cube's zmax face, between hexes in cell order.
  const auto a = static_cast<mesh::NodeId>(mesh.points.size());
  mesh.points.push_back({0.0, 0.0, 2.0});
  mesh.points.push_back({0.5, 0.0, 2.0});
  mesh.points.push_back({0.0, 0.5, 2.0});
  mesh.points.push_back({0.5, 0.5, 2.0});
  mesh.node_ids.insert(mesh.node_ids.end(), {3, 5, 2, 4});
  ElementList cells;
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    cells.add(mesh.cells.type(c), mesh.cells.nodes(c));
    if (c == 3) cells.add(ElementType::wedge6, {18, 19, 21, a, a + 1, a + 2});
    if (c == 5) cells.add(ElementType::wedge6, {19, 22, 21, a + 1, a + 3, a + 2});
  }
  mesh.cells = cells;
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) mesh.cell_ids.push_back(100 - 3 * static_cast<std::int64_t>(c));
  mesh.patches[5].faces.add(ElementType::tri3, {a, a + 1, a + 2});
  mesh.patches.push_back({"empty", 40, {}, {}});
  mesh.cell_groups = {
      {"first_half", 2, {0, 1, 2, 3, 4}}, {"prisms", 5, {4, 7}}, {"nothing", 6, {}}, {"middle", 9, {3, 4, 5, 6}}};
  mesh.derive_node_sets();
  return mesh;
}

TEST(GmshRoundTrip, StructuredSquareAndCubeComeBackEqual) {
  for (const Mesh& original : {test::unit_square(5, 3), test::unit_cube(3)}) {
    const Mesh mesh = with_default_ids(original);
    for (bool binary : {false, true}) {
      const Mesh back = parse_gmsh(gmsh_string(original, binary), "ours.msh");
      EXPECT_EQ(back, mesh) << (binary ? "binary" : "ASCII") << ", dimension " << mesh.dimension;
    }
  }
}

TEST(GmshRoundTrip, SparseTagsMixedCellsAndOverlappingGroupsComeBackEqual) {
  const Mesh mesh = awkward_mesh();
  for (bool binary : {false, true}) {
    const std::string text = gmsh_string(mesh, binary);
    const Mesh back = parse_gmsh(text, "awkward.msh");
    EXPECT_EQ(back.points, mesh.points);
    EXPECT_EQ(back.node_ids, mesh.node_ids);
    EXPECT_EQ(back.cells, mesh.cells);
    EXPECT_EQ(back.cell_ids, mesh.cell_ids);
    EXPECT_EQ(back.patches, mesh.patches);
    EXPECT_EQ(back.cell_groups, mesh.cell_groups);
    EXPECT_EQ(back, mesh) << (binary ? "binary" : "ASCII");
    EXPECT_EQ(gmsh_string(back, binary), text) << "writing is deterministic";
  }
}

TEST(GmshRoundTrip, TagsBeyond32BitsComeBackEqual) {
  Mesh mesh = awkward_mesh();
  mesh.node_ids[3] = std::int64_t{1} << 53;
  mesh.node_ids[4] = std::numeric_limits<std::int64_t>::max();
  mesh.cell_ids[2] = std::int64_t{1} << 40;
  for (bool binary : {false, true}) EXPECT_EQ(parse_gmsh(gmsh_string(mesh, binary), "big.msh"), mesh);
}

TEST(GmshRoundTrip, GmshMeshesComeBackEqual) {
  TempDir dir;
  const Mesh mesh = read_gmsh(mesh_with_gmsh("hex_prism", 3, kFlavours[2], dir));
  for (bool binary : {false, true}) EXPECT_EQ(parse_gmsh(gmsh_string(mesh, binary), "x.msh"), mesh);
}

TEST(GmshRoundTrip, FileIsWrittenAtomically) {
  TempDir dir;
  const Mesh mesh = awkward_mesh();
  const auto path = dir / "mesh.msh";
  write_gmsh(path, test::unit_square(2, 2));
  write_gmsh(path, mesh, {.binary = true});  // replaces the earlier file
  EXPECT_EQ(read_gmsh(path), mesh);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u) << "no temporary file is left behind";
}

TEST(GmshRoundTrip, AsciiLayoutIsPlain41) {
  const std::string text = gmsh_string(test::unit_square(1, 1), false);
  EXPECT_THAT(text, ::testing::StartsWith("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n4\n1 1 \"xmin\"\n"));
  EXPECT_THAT(text, ::testing::HasSubstr("$Entities\n0 4 1 0\n"));
  EXPECT_THAT(text,
              ::testing::HasSubstr("$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n$EndNodes\n"));
  // One quad (tag 1), then the four patch edges with tags 2..5.
  EXPECT_THAT(text, ::testing::HasSubstr("$Elements\n5 5 1 5\n2 1 3 1\n1 1 2 4 3\n1 1 1 1\n2 3 1\n"));
  EXPECT_THAT(text, ::testing::EndsWith("$EndElements\n"));
}

TEST(GmshRoundTrip, WriterRenumbersMissingAndRepeatedGroupTags) {
  Mesh mesh = test::unit_square(2, 1);
  mesh.patches[0].tag = 0;
  mesh.patches[2].tag = 2;  // the same as patches[1]
  const Mesh back = parse_gmsh(gmsh_string(mesh, false), "x.msh");
  ASSERT_EQ(back.patches.size(), 4u);
  std::map<std::string, int> tags;
  for (const mesh::Patch& p : back.patches) tags[p.name] = p.tag;
  EXPECT_EQ(tags["xmax"], 2);
  EXPECT_EQ(tags["ymax"], 4);
  EXPECT_EQ(tags["xmin"], 5);
  EXPECT_EQ(tags["ymin"], 6);
}

TEST(GmshRoundTrip, WriterRejectsMeshItCannotStore) {
  Mesh mesh = test::unit_square(1, 1);
  mesh.patches[0].name = "say \"hi\"";
  EXPECT_THROW(gmsh_string(mesh, false), std::invalid_argument);
  mesh = test::unit_square(1, 1);
  mesh.cells.add(ElementType::quad4, {0, 1, 2, 9});
  EXPECT_THROW(gmsh_string(mesh, false), std::invalid_argument);
}

// ---- we write, gmsh reads ---------------------------------------------------------------

TEST(GmshToGmsh, GmshOpensOurFilesAndSavesTheSameMesh) {
  TempDir dir;
  const Mesh from_gmsh = read_gmsh(mesh_with_gmsh("hex_prism", 3, kFlavours[3], dir));
  const Mesh quads = read_gmsh(mesh_with_gmsh("quad_channel", 2, kFlavours[3], dir));
  // gmsh saves only elements in physical groups (Mesh.SaveAll = 0), drops groups without
  // elements and renumbers nodes: give every cell a group and compare by coordinates.
  Mesh awkward = awkward_mesh();
  awkward.cell_groups.erase(awkward.cell_groups.begin() + 2);
  awkward.cell_groups.push_back({"rest", 12, {8, 9}});
  awkward.patches.pop_back();
  for (const Mesh* mesh : std::vector<const Mesh*>{&from_gmsh, &quads, &awkward}) {
    for (bool binary : {false, true}) {
      const auto ours = dir / "ours.msh";
      write_gmsh(ours, *mesh, {.binary = binary});
      for (const char* resave_binary : {"", " -bin"}) {
        const auto resaved = dir / "resaved.msh";
        run_gmsh(quoted(ours) + " -0 -format msh22" + resave_binary + " -o " + quoted(resaved), dir);
        const Mesh back = read_gmsh(resaved);
        const std::string label = std::string(binary ? "binary" : "ASCII") + " resaved as 2.2" + resave_binary;
        EXPECT_EQ(geometry_of(back), geometry_of(*mesh)) << label;
        EXPECT_EQ(back.cell_count(), mesh->cell_count()) << label;
      }
    }
  }
}

}  // namespace
}  // namespace hotmesh::io
