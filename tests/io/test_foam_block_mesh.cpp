// Tests of the OpenFOAM reader and write-back on meshes made by OpenFOAM's own blockMesh
// (Debian's openfoam package; skipped if it is not installed): a graded 3D block in ASCII and
// binary, one-cell-thick 2D cases with empty front and back (normal to z and to x) and an
// axisymmetric wedge, each moved and written back, and checkMesh on what was written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <regex>

#include "foam_fixtures.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using geometry::Vec3;
using ::testing::HasSubstr;
namespace tf = test::foam;

#define SKIP_WITHOUT_BLOCKMESH()                 \
  if (tf::block_mesh_command().empty())          \
  GTEST_SKIP() << "blockMesh is not installed: " \
                  "run scripts/install-deps.sh (Debian's openfoam)"

constexpr const char* kBlock3d = R"(
vertices ((0 0 0) (2 0 0) (2 1 0) (0 1 0) (0 0 1) (2 0 1) (2 1 1) (0 1 1));
blocks (hex (0 1 2 3 4 5 6 7) (4 3 2) simpleGrading (2 1 0.5));
boundary (
  inlet {type patch; faces ((0 4 7 3));}
  outlet {type patch; faces ((1 2 6 5));}
  walls {type wall; faces ((0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7));}
);
)";

/// A 2 x 1 channel, 4 x 2 cells (graded across), one cell thick in z from -0.1 to 0.1.
/// `vertex` writes a vertex from its 2D position and thickness coordinate.
std::string channel_2d(const std::function<std::string(double, double, double)>& vertex) {
  std::string vertices;
  for (const double t : {-0.1, 0.1}) {
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {0.0, 1.0}})
      vertices += vertex(x, y, t) + " ";
  }
  return "vertices (" + vertices + R"();
blocks (hex (0 1 2 3 4 5 6 7) (4 2 1) simpleGrading (1 3 1));
boundary (
  left {type patch; faces ((0 4 7 3));}
  right {type patch; faces ((1 2 6 5));}
  bottom {type wall; faces ((0 1 5 4));}
  top {type wall; faces ((3 7 6 2));}
  frontAndBack {type empty; faces ((0 3 2 1) (4 5 6 7));}
);
)";
}

std::string vec(double x, double y, double z) { return fmt::format("({} {} {})", x, y, z); }

/// An annular channel x in [0, 3], r in [1, 2] as a 5-degree wedge about the x axis
/// (planes at -2.5 and +2.5 degrees from the x-y plane), 6 x 4 cells; `place` moves each
/// vertex (the identity: as described).
std::string wedge_2d(const std::function<Vec3(const Vec3&)>& place = [](const Vec3& p) { return p; }) {
  const double a = 2.5 * std::numbers::pi / 180.0;
  std::string vertices;
  for (const double side : {-1.0, 1.0}) {
    for (const auto& [x, r] : {std::pair{0.0, 1.0}, {3.0, 1.0}, {3.0, 2.0}, {0.0, 2.0}}) {
      const Vec3 p = place({x, r * std::cos(a), side * r * std::sin(a)});
      vertices += fmt::format("({:.17g} {:.17g} {:.17g}) ", p.x, p.y, p.z);
    }
  }
  return "vertices (" + vertices + R"();
blocks (hex (0 1 2 3 4 5 6 7) (6 4 1) simpleGrading (1 1 1));
boundary (
  inlet {type patch; faces ((0 4 7 3));}
  outlet {type patch; faces ((1 2 6 5));}
  inner {type wall; faces ((0 1 5 4));}
  outer {type wall; faces ((3 7 6 2));}
  back {type wedge; faces ((0 3 2 1));}
  front {type wedge; faces ((4 5 6 7));}
);
)";
}

/// blockMesh on a new case folder `name` in `dir`; the case folder.
std::filesystem::path block_mesh(const test::TempDir& dir, const std::string& name, const std::string& dict,
                                 bool binary = false) {
  const auto folder = dir / name;
  tf::write_block_mesh_case(folder, dict, binary);
  const auto r = tf::run_block_mesh(folder);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return folder;
}

bool all_cells_valid(const mesh::Mesh& m) {
  const auto q = mesh::scaled_jacobians(m.cells, m.points);
  return std::all_of(q.begin(), q.end(), [](double v) { return v > 0.0; });
}

TEST(FoamBlockMesh, Graded3dBlockReadsTheSameInAsciiAndBinary) {
  SKIP_WITHOUT_BLOCKMESH();
  test::TempDir dir;
  const auto ascii = block_mesh(dir, "ascii", kBlock3d);
  const auto binary = block_mesh(dir, "binary", kBlock3d, true);
  EXPECT_THAT(test::read_text(binary / "constant" / "polyMesh" / "faces"), HasSubstr("faceCompactList"));
  const LoadedMesh a = read_mesh(ascii);
  EXPECT_EQ(a.mesh.dimension, 3);
  EXPECT_EQ(a.mesh.node_count(), 5u * 4u * 3u);
  EXPECT_EQ(a.mesh.cell_count(), 24u);
  EXPECT_EQ(a.validation.reoriented_cells, 0u);
  EXPECT_TRUE(all_cells_valid(a.mesh));
  EXPECT_EQ(a.mesh.points, tf::ascii_points(ascii / "constant" / "polyMesh" / "points"));
  ASSERT_EQ(a.mesh.patches.size(), 3u);
  EXPECT_EQ(a.mesh.find_patch("walls")->faces.size(), 2u * (4 * 2 + 4 * 3 + 3 * 2) - 2u * 3 * 2);
  EXPECT_EQ(read_mesh(binary).mesh, a.mesh);
}

TEST(FoamBlockMesh, EmptyCaseIsTheQuadMeshOfItsBackPlane) {
  SKIP_WITHOUT_BLOCKMESH();
  test::TempDir dir;
  const auto folder = block_mesh(dir, "channel", channel_2d([](double x, double y, double t) { return vec(x, y, t); }));
  const LoadedMesh loaded = read_mesh(folder);
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.dimension, 2);
  EXPECT_EQ(m.node_count(), 15u);
  EXPECT_EQ(m.cell_count(), 8u);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  EXPECT_TRUE(all_cells_valid(m));
  std::vector<std::string> names;
  for (const auto& p : m.patches) names.push_back(p.name);
  EXPECT_THAT(names, ::testing::ElementsAre("left", "right", "bottom", "top"));  // frontAndBack dropped
  EXPECT_EQ(m.find_patch("bottom")->faces.size(), 4u);
  const auto foam = tf::ascii_points(folder / "constant" / "polyMesh" / "points");
  for (std::size_t n = 0; n < m.node_count(); ++n) {
    const Vec3& p = foam[static_cast<std::size_t>(m.node_id(static_cast<mesh::NodeId>(n)) - 1)];
    EXPECT_NEAR(p.z, -0.1, 1e-15);  // blockMesh's -0.1 may be an ulp off
    EXPECT_EQ(m.points[n], (Vec3{p.x, p.y, 0.0}));
  }
}

TEST(FoamBlockMesh, EmptyCaseNormalToXMapsYzToTheXyPlane) {
  SKIP_WITHOUT_BLOCKMESH();
  test::TempDir dir;
  const auto z = block_mesh(dir, "z", channel_2d([](double u, double v, double t) { return vec(u, v, t); }));
  const auto x = block_mesh(dir, "x", channel_2d([](double u, double v, double t) { return vec(t, u, v); }));
  const mesh::Mesh normal_z = read_mesh(z).mesh, normal_x = read_mesh(x).mesh;
  EXPECT_EQ(normal_x.dimension, 2);
  EXPECT_EQ(normal_x.points, normal_z.points);
  EXPECT_EQ(normal_x.cells, normal_z.cells);
}

TEST(FoamBlockMesh, EmptyCaseWrittenBackKeepsBothPlanesAndPassesCheckMesh) {
  SKIP_WITHOUT_BLOCKMESH();
  test::TempDir dir;
  const auto folder = block_mesh(dir, "channel", channel_2d([](double x, double y, double t) { return vec(x, y, t); }));
  const LoadedMesh loaded = read_mesh(folder);
  std::vector<Vec3> moved = loaded.mesh.points;
  for (Vec3& p : moved) p = {p.x + 0.05 * std::sin(3.0 * p.y), p.y * (1.0 + 0.1 * p.x), 0.0};
  loaded.write_back->write(dir / "out", moved, {});
  const auto before = tf::ascii_points(folder / "constant" / "polyMesh" / "points");
  const auto after = tf::ascii_points(dir / "out" / "polyMesh" / "points");
  ASSERT_EQ(after.size(), 30u);
  // blockMesh numbers the back plane's points first, then the front's in the same order. Each
  // plane is exactly flat afterwards, at the extreme z its points had.
  double back = 1.0, front = -1.0;
  for (const Vec3& p : before) {
    back = std::min(back, p.z);
    front = std::max(front, p.z);
  }
  EXPECT_NEAR(back, -0.1, 1e-15);
  EXPECT_NEAR(front, 0.1, 1e-15);
  for (std::size_t q = 0; q < 15; ++q) {
    const Vec3& m = moved[q];
    EXPECT_EQ(after[q], (Vec3{m.x, m.y, back}));
    EXPECT_EQ(after[q + 15], (Vec3{m.x, m.y, front}));
  }
  const auto r = tf::check_mesh(folder, dir / "out" / "polyMesh", dir / "check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Mesh OK."));
}

/// The points of a wedge case written back into dir/out: each 2D node's point at its moved
/// (axial coordinate, radius); and checkMesh's "Mesh OK." on them (OpenFOAM checks that the
/// wedge planes are planar when it reads the mesh).
void expect_wedge_written_back(const mesh::Mesh& m, std::span<const Vec3> moved, const std::filesystem::path& folder,
                               const test::TempDir& dir) {
  const auto after = tf::ascii_points(dir / "out" / "polyMesh" / "points");
  for (std::size_t n = 0; n < m.node_count(); ++n) {
    const Vec3& p = after[static_cast<std::size_t>(m.node_id(static_cast<mesh::NodeId>(n)) - 1)];
    EXPECT_NEAR(p.x, moved[n].x, 1e-14);
    EXPECT_NEAR(std::hypot(p.y, p.z), moved[n].y, 1e-14);
  }
  const auto r = tf::check_mesh(folder, dir / "out" / "polyMesh", dir / "check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Mesh OK.")) << r.output;
}

TEST(FoamBlockMesh, WedgeCaseIsTheMeridionalMeshAndWritesBackOntoBothWedgePlanes) {
  SKIP_WITHOUT_BLOCKMESH();
  test::TempDir dir;
  const auto folder = block_mesh(dir, "wedge", wedge_2d());
  const LoadedMesh loaded = read_mesh(folder);
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.dimension, 2);
  EXPECT_EQ(m.node_count(), 7u * 5u);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  EXPECT_TRUE(all_cells_valid(m));
  EXPECT_EQ(m.patches.size(), 4u);
  const auto foam = tf::ascii_points(folder / "constant" / "polyMesh" / "points");
  for (std::size_t n = 0; n < m.node_count(); ++n) {  // x axial, y the radius
    const Vec3& p = foam[static_cast<std::size_t>(m.node_id(static_cast<mesh::NodeId>(n)) - 1)];
    EXPECT_NEAR(m.points[n].x, p.x, 1e-14);
    EXPECT_NEAR(m.points[n].y, std::hypot(p.y, p.z), 1e-14);
    EXPECT_EQ(m.points[n].z, 0.0);
  }
  std::vector<Vec3> moved = m.points;
  for (Vec3& p : moved) p = {p.x + 0.1 * p.y, 1.1 * p.y, 0.0};
  loaded.write_back->write(dir / "out", moved, {});
  const auto after = tf::ascii_points(dir / "out" / "polyMesh" / "points");
  ASSERT_EQ(after.size(), foam.size());
  const double tan_a = std::tan(2.5 * std::numbers::pi / 180.0);
  std::size_t on_back = 0;
  for (std::size_t q = 0; q < after.size(); ++q) {
    const Vec3& p = after[q];
    const double side = foam[q].z < 0 ? -1.0 : 1.0;
    on_back += side < 0;
    EXPECT_NEAR(p.z, side * tan_a * p.y, 1e-14) << q;  // on its own wedge plane
    // The same 2D point as its partner on the other plane (blockMesh: back plane first).
    const Vec3& partner = after[q < after.size() / 2 ? q + after.size() / 2 : q - after.size() / 2];
    EXPECT_EQ(p.x, partner.x);
    EXPECT_NEAR(std::hypot(p.y, p.z), std::hypot(partner.y, partner.z), 1e-14);
  }
  EXPECT_EQ(on_back, after.size() / 2);
  expect_wedge_written_back(m, moved, folder, dir);
}

TEST(FoamBlockMesh, WedgeAboutAnyAxisGivesTheSameMeridionalMesh) {
  SKIP_WITHOUT_BLOCKMESH();
  // Rotated by 40 degrees about (1, 1, 1) and moved off the origin across the new axis: the
  // axial coordinate is measured from the axis point nearest the origin, so nothing changes.
  const Vec3 k = Vec3{1, 1, 1} / std::sqrt(3.0);
  const double c = std::cos(0.7), s = std::sin(0.7);
  const auto rotate = [&](const Vec3& p) {
    return c * p + s * geometry::cross(k, p) + (1 - c) * geometry::dot(k, p) * k;
  };
  const Vec3 axis = rotate({1, 0, 0});
  const Vec3 shift = geometry::cross(axis, Vec3{0.3, -1.2, 2.0});  // normal to the axis
  test::TempDir dir;
  const mesh::Mesh plain = read_mesh(block_mesh(dir, "plain", wedge_2d())).mesh;
  const mesh::Mesh turned =
      read_mesh(block_mesh(dir, "turned", wedge_2d([&](const Vec3& p) { return rotate(p) + shift; }))).mesh;
  ASSERT_EQ(turned.node_count(), plain.node_count());
  EXPECT_GT(axis.x, std::max(std::abs(axis.y), std::abs(axis.z)));  // x stays the axial direction's sign
  for (std::size_t n = 0; n < plain.node_count(); ++n) {
    EXPECT_NEAR(turned.points[n].x, plain.points[n].x, 1e-12) << n;
    EXPECT_NEAR(turned.points[n].y, plain.points[n].y, 1e-12) << n;
  }
  EXPECT_EQ(turned.cells, plain.cells);
}

TEST(FoamBlockMesh, AOneCellThickCaseOfPrismsIsATriangleMesh) {
  SKIP_WITHOUT_BLOCKMESH();  // for checkMesh
  // Triangles extruded one cell in z (prisms, written by hotmesh), the ends made empty.
  const auto xs = mesh::uniform_line(0.0, 2.0, 6), ys = mesh::uniform_line(0.0, 1.0, 3);
  const mesh::Mesh hexes = mesh::structured_hexes(xs, ys, std::vector<double>{0.0, 0.1},
                                                  {"inlet", "outlet", "bottom", "top", "back", "front"});
  const mesh::Mesh prisms = mesh::split_cells(hexes, std::vector<mesh::CellSplit>(hexes.cell_count(), mesh::CellSplit::prisms));
  test::TempDir dir;
  tf::write_block_mesh_case(dir / "case", "");  // the system folder checkMesh needs
  write_foam(dir / "case", prisms, prisms.points);
  const auto boundary = dir / "case" / "constant" / "polyMesh" / "boundary";
  std::string text = test::read_text(boundary);
  for (const char* plane : {"back", "front"}) {
    text = std::regex_replace(text, std::regex(std::string(plane) + R"((\s*\{\s*type\s+)wall)"), std::string(plane) + "$1empty");
  }
  test::write_text(boundary, text);
  const LoadedMesh loaded = read_mesh(dir / "case");
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.dimension, 2);
  ASSERT_EQ(m.cell_count(), 2u * 6u * 3u);
  for (std::size_t c = 0; c < m.cell_count(); ++c) EXPECT_EQ(m.cells.type(c), mesh::ElementType::tri3);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  EXPECT_TRUE(all_cells_valid(m));
  ASSERT_EQ(m.patches.size(), 4u);
  EXPECT_EQ(m.find_patch("inlet")->faces.size(), 3u);
  std::vector<Vec3> moved = m.points;
  for (Vec3& p : moved) p = {p.x + 0.1 * p.y * p.y, p.y, 0.0};
  loaded.write_back->write(dir / "out", moved, {});
  const auto after = tf::ascii_points(dir / "out" / "polyMesh" / "points");
  const auto before = tf::ascii_points(boundary.parent_path() / "points");
  for (std::size_t q = 0; q < after.size(); ++q) {
    EXPECT_NEAR(after[q].x, before[q].x + 0.1 * before[q].y * before[q].y, 1e-14) << q;  // both planes follow
    EXPECT_EQ(after[q].z, before[q].z);
  }
  const auto r = tf::check_mesh(dir / "case", dir / "out" / "polyMesh", dir / "check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Mesh OK.")) << r.output;
}

TEST(FoamBlockMesh, AWedgeReachingTheAxisGetsAnAxisPatchAndWritesBackOnIt) {
  SKIP_WITHOUT_BLOCKMESH();
  // A wedge that reaches the axis: blockMesh collapses the cells at r = 0 (their face there
  // vanishes, the points on the axis are on both wedge planes). Their edges on the axis become
  // the 2D patch "axis", named as the case's empty patch without faces.
  test::TempDir dir;
  std::string dict = wedge_2d();
  dict =
      std::regex_replace(dict, std::regex(R"(\(0 0\.99\d+ -0\.04\d+\) \(3 0\.99\d+ -0\.04\d+\))"), "(0 0 0) (3 0 0)");
  dict = std::regex_replace(dict, std::regex(R"(\(0 0\.99\d+ 0\.04\d+\) \(3 0\.99\d+ 0\.04\d+\))"), "(0 0 0) (3 0 0)");
  dict = std::regex_replace(dict, std::regex(R"(inner \{type wall; faces \(\(0 1 5 4\)\);\})"),
                            "axis {type empty; faces ((0 1 5 4));}");
  const auto folder = block_mesh(dir, "axis", dict);
  const LoadedMesh loaded = read_mesh(folder);
  const mesh::Mesh& m = loaded.mesh;
  EXPECT_EQ(m.dimension, 2);
  EXPECT_EQ(m.cell_count(), 24u);
  for (double q : mesh::scaled_jacobians(m.cells, m.points)) EXPECT_GT(q, 0.0);
  const mesh::Patch* axis = m.find_patch("axis");
  ASSERT_NE(axis, nullptr);
  EXPECT_EQ(axis->faces.size(), 6u);  // one edge per cell along the axis
  for (mesh::NodeId n : axis->nodes) EXPECT_NEAR(m.points[static_cast<std::size_t>(n)].y, 0.0, 1e-14);
  // Moved along the axis and outwards: the points on the axis stay on it, in the file too.
  std::vector<Vec3> moved = m.points;
  for (Vec3& p : moved) p = {p.x + 0.05 * (1.0 + p.y), 1.1 * p.y, 0.0};
  loaded.write_back->write(dir / "out", moved, {});
  expect_wedge_written_back(m, moved, folder, dir);
}

}  // namespace
}  // namespace hotmesh::io
