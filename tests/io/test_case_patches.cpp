// Tests of a case file's patches (hotmesh::io::read_case, check_case_against_mesh): roles and
// where deflections are allowed, deflection tables and their modes, CAD faces and edges, the
// axis, periodic pairs, and the case checked against the mesh's patches and dimension.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "case_file_fixture.hpp"

namespace hotmesh::io {
namespace {

using namespace test_case;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::SizeIs;
using ::testing::StartsWith;

TEST_F(CaseFile, ChecksRolesAndWhereDeflectionsAreAllowed) {
  const auto lines = lines_of(error_with(
      "  a: {}\n"                                                        // 4
      "  b: {role: fixed, deflection: {file: plane.csv}}\n"              // 5
      "  c: {role: slip, deflection: {file: plane.csv}}\n"               // 6
      "  d: {role: passive, deflection: {file: plane.csv}}\n"            // 7
      "  e: {role: sliding, partner: a}\n"                               // 8
      "  f: {role: fixed, angle_deg: 10}\n"                              // 9
      "  g:\n"));                                                        // 10
  ASSERT_THAT(lines, SizeIs(7));
  EXPECT_EQ(lines[0], at(4) + "patches.a.role: missing; expected one of fixed, prescribed, slip, sliding, passive, periodic");
  EXPECT_EQ(lines[1], at(5) + "patches.b.deflection: not allowed for role fixed; only prescribed and sliding patches "
                              "take a deflection table");
  EXPECT_THAT(lines[2], StartsWith(at(6) + "patches.c.deflection: not allowed for role slip"));
  EXPECT_THAT(lines[3], StartsWith(at(7) + "patches.d.deflection: not allowed for role passive"));
  EXPECT_EQ(lines[4], at(8) + "patches.e.partner: only periodic patches have partner (this patch is sliding)");
  EXPECT_EQ(lines[5], at(9) + "patches.f.angle_deg: only periodic patches have angle_deg (this patch is fixed)");
  EXPECT_THAT(lines[6], StartsWith(at(10) + "patches.g.role: missing"));
  // Sliding without a table slides over its own undeformed shape.
  EXPECT_EQ(parse(std::string(kBase) + "  s: {role: sliding}\n").find_patch("s")->role, PatchRole::sliding);
}

TEST_F(CaseFile, RejectsDeflectionOnPeriodicPatch) {
  EXPECT_THAT(error_with_axis("  p: {role: periodic, partner: q, angle_deg: 5, deflection: {file: blade.csv}}\n"
                              "  q: {role: periodic}\n"),
              StartsWith(at(5) + "patches.p.deflection: not allowed for role periodic"));
}

TEST_F(CaseFile, IncludesDeflectionTableErrors) {
  EXPECT_EQ(error_with("  ramp: {role: sliding, deflection: {file: bad.csv}}\n"),
            at(4) + "patches.ramp.deflection.file: " + (dir / "bad.csv").string() +
                ":1: unknown column 'dq'; expected x,y,dx,dy (planar), x,y,z,dx,dy,dz (cartesian) or r,z,dr,dz "
                "(meridional), plus an optional id");
}

TEST_F(CaseFile, FacesNeedCad) {
  EXPECT_EQ(error_with("  blade: {role: prescribed, deflection: {file: blade.csv, faces: [1]}}\n"),
            at(4) + "patches.blade.deflection.faces: CAD face numbers need a CAD file; add `cad: <file.step>` at the "
                    "top level");
}

TEST_F(CaseFile, RejectsPlanarTableBesideThreeDimensionalOne) {
  EXPECT_EQ(error_with("  a: {role: sliding, deflection: {file: blade.csv}}\n"
                       "  b: {role: sliding, deflection: {file: plane.csv}}\n"),
            at(5) + "patches.b.deflection: its table is planar (x, y) but the table of patch 'a' (line 4) is "
                    "cartesian (x, y, z); planar tables are for 2D meshes, the others for 3D meshes");
}

TEST_F(CaseFile, MeridionalTableNeedsAxis) {
  EXPECT_EQ(error_with("  disc:\n    role: sliding\n    deflection: {file: ramp.csv}\n"),
            at(4) + "patches.disc: its deflection table is meridional (r, z), which needs the top-level axis, e.g. "
                    "axis: {origin: [0, 0, 0], direction: [0, 0, 1]}");
  EXPECT_NO_THROW(parse(std::string(kBaseWithAxis) + "  disc: {role: sliding, deflection: {file: ramp.csv}}\n"));
}

TEST_F(CaseFile, AxisNeedsOriginAndDirection) {
  EXPECT_EQ(error_with("axis: {direction: [0, 0, 1]}\n"),
            at(4) + "axis.origin: missing; the axis needs both, e.g. axis: {origin: [0, 0, 0], direction: [0, 0, 1]}");
}

TEST_F(CaseFile, PeriodicPairNeedsAxis) {
  EXPECT_THAT(error_with("  lo: {role: periodic}\n  hi: {role: periodic, partner: lo, angle_deg: -3.6}\n"),
              StartsWith(at(5) + "patches.hi: the periodic pair hi/lo needs the top-level axis"));
}

TEST_F(CaseFile, AcceptsPeriodicPairDeclaredEitherWay) {
  const Case c = parse(std::string(kBaseWithAxis) +
                       "  a: {role: periodic, partner: b, angle_deg: 180}\n"
                       "  b: {role: periodic, partner: a}\n"
                       "  c: {role: periodic}\n"
                       "  d: {role: periodic, partner: c, angle_deg: -10}\n");
  EXPECT_EQ(c.find_patch("a")->angle_deg, 180.0);
  EXPECT_EQ(c.find_patch("b")->partner, "a");
  EXPECT_EQ(c.find_patch("c")->partner, "d");
  EXPECT_EQ(c.find_patch("d")->angle_deg, -10.0);
}

TEST_F(CaseFile, RejectsBadPeriodicAngles) {
  const auto lines = lines_of(error_with_axis(
      "  a: {role: periodic, partner: b, angle_deg: 0}\n"       // 5
      "  b: {role: periodic}\n"                                 // 6
      "  c: {role: periodic, partner: d, angle_deg: 190}\n"     // 7
      "  d: {role: periodic}\n"                                 // 8
      "  e: {role: periodic, partner: f, angle_deg: .inf}\n"    // 9
      "  f: {role: periodic}\n"));                              // 10
  ASSERT_THAT(lines, SizeIs(3));
  EXPECT_EQ(lines[0], at(5) + "patches.a.angle_deg: must be a non-zero angle in degrees with |angle_deg| <= 180, got 0");
  EXPECT_EQ(lines[1], at(7) + "patches.c.angle_deg: must be a non-zero angle in degrees with |angle_deg| <= 180, got 190");
  EXPECT_EQ(lines[2], at(9) + "patches.e.angle_deg: must be a finite number, got .inf");
}

TEST_F(CaseFile, RejectsBrokenPeriodicPairs) {
  const auto lines = lines_of(error_with_axis(
      "  a: {role: periodic}\n"                                  // 5  not paired
      "  b: {role: periodic, angle_deg: 5}\n"                    // 6  angle without partner
      "  c: {role: periodic, partner: c, angle_deg: 5}\n"        // 7  itself
      "  d: {role: periodic, partner: nowhere, angle_deg: 5}\n"  // 8  not a patch
      "  e: {role: periodic, partner: wall, angle_deg: 5}\n"     // 9  not periodic
      "  f: {role: periodic, partner: g, angle_deg: 5}\n"        // 10 both give the angle
      "  g: {role: periodic, partner: f, angle_deg: -5}\n"       // 11
      "  h: {role: periodic, partner: i}\n"                      // 12 no angle in the pair
      "  i: {role: periodic}\n"));                               // 13
  ASSERT_THAT(lines, SizeIs(7));
  EXPECT_EQ(lines[0], at(5) + "patches.a: periodic patch without a partner; declare the pair on one side with "
                              "`partner: <other>` and `angle_deg: <degrees>`");
  EXPECT_EQ(lines[1], at(6) + "patches.b.angle_deg: needs `partner: <other periodic patch>` beside it");
  EXPECT_EQ(lines[2], at(7) + "patches.c.partner: a patch cannot be its own partner; name the other side");
  EXPECT_EQ(lines[3], at(8) + "patches.d.partner: 'nowhere' is not a patch of this case; periodic patches: a, b, c, d, "
                              "e, f, g, h, i");
  EXPECT_EQ(lines[4], at(9) + "patches.e.partner: 'wall' has role fixed; the partner must be periodic too");
  EXPECT_EQ(lines[5], at(11) + "patches.g.angle_deg: 'f' gives angle_deg too; give it on one side of the pair only");
  EXPECT_EQ(lines[6], at(12) + "patches.h: the periodic pair h/i has no angle_deg; add angle_deg (the rotation "
                               "from one patch to the other, in degrees) on one side");
}

TEST_F(CaseFile, RejectsPatchInTwoPairsAndConflictingPartners) {
  const auto lines = lines_of(error_with_axis(
      "  a: {role: periodic, partner: c, angle_deg: 5}\n"   // 5
      "  b: {role: periodic, partner: c, angle_deg: 5}\n"   // 6
      "  c: {role: periodic}\n"                             // 7 in two pairs
      "  d: {role: periodic, partner: e, angle_deg: 5}\n"   // 8 e points elsewhere
      "  e: {role: periodic, partner: f}\n"                 // 9
      "  f: {role: periodic, partner: e, angle_deg: 5}\n"    // 10
      "  g: {role: periodic, partner: h}\n"                  // 11 h is paired with i
      "  h: {role: periodic}\n"                              // 12
      "  i: {role: periodic, partner: h, angle_deg: 5}\n"));  // 13
  ASSERT_THAT(lines, SizeIs(3));
  EXPECT_EQ(lines[0], at(7) + "patches.c: is in more than one periodic pair (with a, b); each periodic patch pairs "
                              "with exactly one other");
  EXPECT_EQ(lines[1], at(8) + "patches.d.partner: 'e' names 'f' as its partner, not 'd'");
  EXPECT_EQ(lines[2], at(11) + "patches.g.partner: 'h' is already paired with 'i'");
}

TEST_F(CaseAgainstMesh, AcceptsCaseCoveringEveryPatch) {
  EXPECT_EQ(mesh_error("mesh: mesh.msh\npatches:\n  xmin: {role: fixed}\n  xmax: {role: slip}\n"
                       "  ymin: {role: sliding, deflection: {file: plane.csv}}\n  ymax: {role: passive}\n",
                       test::unit_square(2, 2)),
            "no error");
}

TEST_F(CaseAgainstMesh, ReportsMeshPatchesWithoutRoleAndUnknownPatches) {
  const auto lines = lines_of(mesh_error(
      "mesh: mesh.msh\n"
      "patches:\n"                       // 2
      "  xmin: {role: fixed}\n"
      "  outlet: {role: passive}\n"      // 4
      "  ymin: {role: fixed}\n",
      test::unit_square(2, 2)));
  ASSERT_THAT(lines, SizeIs(3));
  EXPECT_EQ(lines[0], at(2) + "patches: mesh patch 'xmax' has no role; add `xmax: {role: ...}` under patches");
  EXPECT_EQ(lines[1], at(2) + "patches: mesh patch 'ymax' has no role; add `ymax: {role: ...}` under patches");
  EXPECT_EQ(lines[2], at(4) + "patches.outlet: no patch 'outlet' in the mesh mesh.msh; its patches are: xmin, xmax, "
                              "ymin, ymax");
}

/// A case of test::unit_square (`top`: top-level keys after `mesh`): patch ymin sliding with
/// `deflection`, on the last line (6, plus the lines of `top`).
std::string square_case(std::string_view top, std::string_view deflection) {
  return "mesh: mesh.msh\n" + std::string(top) + "patches:\n  xmin: {role: fixed}\n  xmax: {role: fixed}\n" +
         "  ymax: {role: fixed}\n  ymin: {role: sliding, deflection: " + std::string(deflection) + "}\n";
}

/// The same for test::unit_cube(1): ymin on line 8, plus the lines of `top`.
std::string cube_case(std::string_view top, std::string_view deflection) {
  return "mesh: mesh.msh\n" + std::string(top) + "patches:\n  xmin: {role: fixed}\n  xmax: {role: fixed}\n" +
         "  ymax: {role: fixed}\n  zmin: {role: fixed}\n  zmax: {role: fixed}\n  ymin: {role: sliding, deflection: " +
         std::string(deflection) + "}\n";
}

constexpr std::string_view kAxisX = "axis: {origin: [0, 0, 0], direction: [1, 0, 0]}\n";

TEST_F(CaseAgainstMesh, ChecksTableFrameAgainstMeshDimension) {
  EXPECT_EQ(mesh_error(square_case("", "{file: blade.csv}"), test::unit_square(2, 2)),
            at(6) + "patches.ymin.deflection: a cartesian (x, y, z) table is for 3D meshes but the mesh is 2D; give "
                    "its columns as x,y,dx,dy (or r,z,dr,dz in an axisymmetric case, with the axis)");
  EXPECT_EQ(mesh_error(cube_case("", "{file: plane.csv}"), test::unit_cube(1)),
            at(8) + "patches.ymin.deflection: a planar (x, y) table is for 2D meshes but the mesh is 3D; give its "
                    "columns as x,y,z,dx,dy,dz or r,z,dr,dz");
  // With an axis a 2D case is axisymmetric: its (x, y) are (z, r), and a meridional table fits.
  EXPECT_EQ(mesh_error(square_case(kAxisX, "{file: ramp.csv}"), test::unit_square(2, 2)), "no error");
}

TEST_F(CaseFile, EdgesNeedCadAndAreNotGivenWithFaces) {
  const auto lines = lines_of(error_with("  a: {role: sliding, deflection: {file: plane.csv, edges: [1, 2, 1]}}\n"
                                         "  b: {role: sliding, deflection: {file: plane.csv, edges: []}}\n"));
  ASSERT_THAT(lines, SizeIs(3));
  EXPECT_EQ(lines[0], at(4) + "patches.a.deflection.edges[2]: edge 1 is listed twice");
  EXPECT_EQ(lines[1], at(4) + "patches.a.deflection.edges: CAD edge numbers need a CAD file; add `cad: <file.step>` at "
                              "the top level");
  EXPECT_EQ(lines[2], at(5) + "patches.b.deflection.edges: expected a list of CAD edge numbers (>= 1), e.g. [3, 4], "
                              "got an empty list");
  EXPECT_THAT(error_of(square_case("cad: part.step\n", "{file: plane.csv, faces: [1], edges: [2]}")),
              StartsWith(at(7) + "patches.ymin.deflection.edges: give either `faces:` (CAD faces: 3D walls, or an "
                                 "axisymmetric 2D case's) or `edges:`"));
  EXPECT_EQ(parse(square_case("cad: part.step\n", "{file: plane.csv, edges: [4, 2]}")).find_patch("ymin")->deflection->edges,
            (std::vector<int>{4, 2}));
}

// A 3D wall is on CAD faces, a planar 2D wall on CAD edges, and an axisymmetric 2D case (one
// with an axis) takes faces, whose meridional curve it reads in its (z, r) plane.
TEST_F(CaseAgainstMesh, EdgesAreFor2DMeshesAndFacesIn2DNeedTheAxis) {
  EXPECT_EQ(mesh_error(cube_case("cad: part.step\n", "{file: blade.csv, edges: [1]}"), test::unit_cube(1)),
            at(9) + "patches.ymin.deflection.edges: CAD edges are the walls of 2D cases (curves in the plane z = 0); a "
                    "3D wall is on CAD faces: give them, `faces: [...]`");
  EXPECT_THAT(mesh_error(square_case("cad: part.step\n", "{file: plane.csv, faces: [1]}"), test::unit_square(2, 2)),
              StartsWith(at(7) + "patches.ymin.deflection.faces: CAD faces are surfaces: a 2D case takes them only when "
                                 "it is axisymmetric, with the top-level axis"));
  EXPECT_EQ(mesh_error(square_case("cad: part.step\n" + std::string(kAxisX), "{file: ramp.csv, faces: [1]}"), test::unit_square(2, 2)),
            "no error");
}

// The deflection's `mode` (how a 3D wall is built): its values, a meridional wall without the
// axis it needs, and the key on a 2D mesh, each refused at its line.
TEST_F(CaseFile, DeflectionModeChoosesHowA3DWallIsBuilt) {
  EXPECT_EQ(parse(std::string(kBase) + "  ramp: {role: sliding, deflection: {file: plane.csv, mode: surface}}\n")
                .find_patch("ramp")
                ->deflection->mode,
            WallMode::surface);
  EXPECT_EQ(parse(std::string(kBase) + "  ramp: {role: sliding, deflection: {file: plane.csv}}\n")
                .find_patch("ramp")
                ->deflection->mode,
            WallMode::automatic);
  EXPECT_THAT(error_with("  ramp: {role: sliding, deflection: {file: plane.csv, mode: revolved}}\n"),
              StartsWith(at(4) + "patches.ramp.deflection.mode: "));
  EXPECT_THAT(error_with("  ramp: {role: sliding, deflection: {file: plane.csv, mode: meridional}}\n"),
              StartsWith(at(4) + "patches.ramp.deflection.mode: a meridional wall is a surface of revolution about "
                                 "the top-level axis"));
}

TEST_F(CaseAgainstMesh, DeflectionModeIsFor3DWalls) {
  EXPECT_THAT(mesh_error("mesh: mesh.msh\npatches:\n  xmin: {role: fixed}\n  xmax: {role: slip}\n"
                         "  ymin: {role: sliding, deflection: {file: plane.csv, mode: surface}}\n  ymax: {role: passive}\n",
                         test::unit_square(2, 2)),
              HasSubstr(":5: patches.ymin.deflection.mode: is for the walls of 3D meshes"));
}

}  // namespace
}  // namespace hotmesh::io
