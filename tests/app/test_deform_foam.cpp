// Tests of `hotmesh deform` on OpenFOAM cases made by blockMesh (skipped if it is not
// installed): the ramp channel of samples/ramp2d as a one-cell-thick case with empty front
// and back moves exactly as the same mesh does as a .msh file, its written polyMesh passes
// checkMesh, --foam-time writes only the new time folder into the case, and bad requests exit
// with code 2 before any work; as a wedge case, axisymmetric with its axis, its wall taken from
// a revolved CAD part.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "deform_cases.hpp"
#include "foam_fixtures.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using geometry::Vec3;
using test::hotmesh;
using test::shell_quote;
using ::testing::Eq;
using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
namespace tf = test::foam;


std::string ramp_case(const std::string& mesh) {
  return fmt::format(
      "mesh: {}\nsolver: {{increments: 8, newton_tolerance: 1.0e-6, pcg_tolerance: 1.0e-6}}\npatches:\n"
      "  left: {{role: fixed}}\n  right: {{role: slip}}\n  top: {{role: sliding}}\n"
      "  bottom: {{role: sliding, deflection: {{file: ramp.csv, degree: 1}}}}\n",
      mesh);
}

/// Every file under `folder` with its content.
std::map<std::string, std::string> snapshot(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(folder)) {
    if (e.is_regular_file()) files[fs::relative(e.path(), folder).string()] = test::read_text(e.path());
  }
  return files;
}

/// The ramp channel case by blockMesh in `dir`/cfd, with the sample's ramp.csv and foam.yaml.
/// `binary_gz`: blockMesh writes binary, and every polyMesh file is then gzipped.
struct RampFoamCase {
  test::TempDir dir;
  fs::path cfd = dir / "cfd";
  explicit RampFoamCase(bool binary_gz = false) {
    tf::write_block_mesh_case(cfd, tf::kRampChannel, binary_gz);
    const auto r = tf::run_block_mesh(cfd);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    if (binary_gz) {
      for (const char* name : {"points", "faces", "owner", "neighbour", "boundary"}) {
        const auto file = cfd / "constant" / "polyMesh" / name;
        test::write_text(fs::path(file.string() + ".gz"), tf::gzipped(test::read_text(file)));
        fs::remove(file);
      }
    }
    fs::copy_file(test::kSample / "ramp.csv", dir / "ramp.csv");
    test::write_text(dir / "foam.yaml", ramp_case("cfd"));
  }
  std::string case_file() const { return shell_quote((dir / "foam.yaml").string()); }
};

#define SKIP_WITHOUT_BLOCKMESH()                 \
  if (tf::block_mesh_command().empty())          \
  GTEST_SKIP() << "blockMesh is not installed: " \
                  "run scripts/install-deps.sh (Debian's openfoam)"

TEST(DeformFoam, RampChannelMovesAsItsGmshTwinAndTheWrittenMeshPassesCheckMesh) {
  SKIP_WITHOUT_BLOCKMESH();
  RampFoamCase c;
  const auto polymesh = c.cfd / "constant" / "polyMesh";
  const auto before = snapshot(c.cfd);
  const auto out = c.dir / "out";
  const auto r = hotmesh("deform " + c.case_file() + " -o " + shell_quote(out.string()) + " --threads 1 --foam-time 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // The same mesh as a .msh file, moved by the same case.
  const mesh::Mesh flat = io::read_mesh(c.cfd).mesh;
  io::write_gmsh(c.dir / "twin.msh", flat);
  test::write_text(c.dir / "twin.yaml", ramp_case("twin.msh"));
  const auto twin_out = c.dir / "twin-out";
  const auto t = hotmesh("deform " + shell_quote((c.dir / "twin.yaml").string()) + " -o " +
                         shell_quote(twin_out.string()) + " --threads 1");
  ASSERT_EQ(t.exit_code, 0) << t.output;
  const mesh::Mesh twin = io::read_gmsh(twin_out / "deformed.msh");
  EXPECT_EQ(io::read_gmsh(out / "deformed.msh").points, twin.points);

  // The written points: each back point at its twin's node, each front point over it, both
  // planes exactly flat; the lower wall on the ramp.
  const auto original = tf::ascii_points(polymesh / "points");
  const auto moved = tf::ascii_points(out / "polyMesh" / "points");
  ASSERT_EQ(moved.size(), original.size());
  const std::size_t half = moved.size() / 2;  // blockMesh: the back plane's points, then the front's
  double front = 0.0;  // blockMesh's 0.05 may be an ulp off: the plane stays where its farthest point was
  for (const Vec3& p : original) front = std::max(front, p.z);
  EXPECT_NEAR(front, 0.05, 1e-15);
  for (std::size_t n = 0; n < twin.node_count(); ++n) {
    const auto q = static_cast<std::size_t>(twin.node_id(static_cast<mesh::NodeId>(n)) - 1);
    ASSERT_LT(q, half);
    EXPECT_EQ(moved[q], (Vec3{twin.points[n].x, twin.points[n].y, 0.0}));
    EXPECT_EQ(moved[q + half], (Vec3{twin.points[n].x, twin.points[n].y, front}));
  }
  double lowest_past_ramp = 9.0;
  for (const Vec3& p : moved) {
    if (p.x > 1.1) lowest_past_ramp = std::min(lowest_past_ramp, p.y);
  }
  EXPECT_NEAR(lowest_past_ramp, 0.5, 1e-9);  // the lower wall past the ramp, raised by h/2

  // The other polyMesh files are copied byte for byte; the case got 1/polyMesh/points only.
  for (const char* name : {"faces", "owner", "neighbour", "boundary"}) {
    EXPECT_EQ(test::read_text(out / "polyMesh" / name), test::read_text(polymesh / name)) << name;
  }
  auto after = snapshot(c.cfd);
  ASSERT_EQ(after.count("1/polyMesh/points"), 1u);
  EXPECT_EQ(tf::ascii_points(c.cfd / "1" / "polyMesh" / "points"), moved);
  after.erase("1/polyMesh/points");
  EXPECT_EQ(after, before);

  // checkMesh on the written polyMesh in a case of its own, and on the case at time 1.
  for (const auto& k :
       {tf::check_mesh(c.cfd, out / "polyMesh", c.dir / "check"),
        test::run_command(tf::check_mesh_command() + " -case " + shell_quote(c.cfd.string()) + " -time 1")}) {
    EXPECT_EQ(k.exit_code, 0) << k.output;
    EXPECT_THAT(k.output, HasSubstr("Mesh OK.")) << k.output;
  }
}

TEST(DeformFoam, BinaryGzippedCaseIsWrittenBackBinaryGzippedWithTheSamePoints) {
  SKIP_WITHOUT_BLOCKMESH();
  RampFoamCase ascii, binary(true);
  for (const RampFoamCase* c : {&ascii, &binary}) {
    const auto r =
        hotmesh("deform " + c->case_file() + " -o " + shell_quote((c->dir / "out").string()) + " --threads 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const auto written = binary.dir / "out" / "polyMesh";
  EXPECT_THAT(test::read_text(written / "owner.gz"),
              Eq(test::read_text(binary.cfd / "constant" / "polyMesh" / "owner.gz")));
  ASSERT_TRUE(fs::exists(written / "points.gz"));
  EXPECT_FALSE(fs::exists(written / "points"));
  EXPECT_THAT(tf::gunzipped(test::read_text(written / "points.gz")), HasSubstr("format      binary;"));
  // Binary doubles and shortest round-trip text hold the same points.
  EXPECT_EQ(io::read_mesh(written).mesh.points, io::read_mesh(ascii.dir / "out" / "polyMesh").mesh.points);
  const auto k = tf::check_mesh(binary.cfd, written, binary.dir / "check");
  EXPECT_EQ(k.exit_code, 0) << k.output;
  EXPECT_THAT(k.output, HasSubstr("Mesh OK.")) << k.output;
}

/// The ramp channel as an annulus r in [1, 2] about the x axis: a 5-degree wedge case.
std::string ramp_wedge() {
  const double a = 2.5 * std::numbers::pi / 180.0;
  std::string vertices;
  for (const double side : {-1.0, 1.0}) {
    for (const auto& [x, r] : {std::pair{0.0, 1.0}, {2.0, 1.0}, {2.0, 2.0}, {0.0, 2.0}}) {
      vertices += fmt::format("({} {:.17g} {:.17g}) ", x, r * std::cos(a), side * r * std::sin(a));
    }
  }
  return "vertices (" + vertices + R"();
blocks (hex (0 1 2 3 4 5 6 7) (21 12 1) simpleGrading (1 20 1));
boundary (
  left {type patch; faces ((0 4 7 3));}
  right {type patch; faces ((1 2 6 5));}
  bottom {type wall; faces ((0 1 5 4));}
  top {type wall; faces ((3 7 6 2));}
  back {type wedge; faces ((0 3 2 1));}
  front {type wedge; faces ((4 5 6 7));}
);
)";
}

/// The ramp channel's wedge case made by blockMesh in a temporary folder (cfd/), and its
/// points moved by `hotmesh deform`.
struct RampWedge {
  test::TempDir dir;
  RampWedge() {
    tf::write_block_mesh_case(dir / "cfd", ramp_wedge());
    const auto b = tf::run_block_mesh(dir / "cfd");
    EXPECT_EQ(b.exit_code, 0) << b.output;
  }

  struct Moved {
    test::CommandResult result;
    std::vector<Vec3> original, moved;  ///< the case's points, before and after
  };
  /// `hotmesh deform` of the case `yaml` (as wedge.yaml, mesh: cfd) into out/.
  Moved deform(const std::string& yaml) const {
    test::write_text(dir / "wedge.yaml", yaml);
    Moved m;
    m.result = hotmesh("deform " + shell_quote((dir / "wedge.yaml").string()) + " -o " + shell_quote((dir / "out").string()));
    if (m.result.exit_code != 0) return m;
    m.original = tf::ascii_points(dir / "cfd" / "constant" / "polyMesh" / "points");
    m.moved = tf::ascii_points(dir / "out" / "polyMesh" / "points");
    return m;
  }
};

TEST(DeformFoam, RampAsAWedgeCaseMovesInTheMeridionalPlaneAndPassesCheckMesh) {
  SKIP_WITHOUT_BLOCKMESH();
  const RampWedge wedge;
  // The sample's table in the meridional plane: the lower wall at radius 1.
  std::istringstream sample(test::read_text(test::kSample / "ramp.csv"));
  std::string table;
  for (std::string line; std::getline(sample, line);) {
    double x = 0, y = 0, dx = 0, dy = 0;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &x, &y, &dx, &dy) == 4) {
      table += fmt::format("{},{},{},{}\n", x, y + 1.0, dx, dy);
    } else {
      table += line + "\n";
    }
  }
  test::write_text(wedge.dir / "ramp.csv", table);
  const RampWedge::Moved m = wedge.deform(ramp_case("cfd"));
  ASSERT_EQ(m.result.exit_code, 0) << m.result.output;
  ASSERT_EQ(m.moved.size(), m.original.size());
  const double tan_a = std::tan(2.5 * std::numbers::pi / 180.0);
  double lowest_past_ramp = 9.0;
  for (std::size_t q = 0; q < m.moved.size(); ++q) {
    const Vec3& p = m.moved[q];
    EXPECT_NEAR(p.z, (m.original[q].z < 0 ? -tan_a : tan_a) * p.y, 1e-14) << q;  // on its own wedge plane
    if (p.x > 1.1) lowest_past_ramp = std::min(lowest_past_ramp, std::hypot(p.y, p.z));
  }
  EXPECT_NEAR(lowest_past_ramp, 1.5, 1e-9);  // the inner wall past the ramp, raised by h/2
  const auto k = tf::check_mesh(wedge.dir / "cfd", wedge.dir / "out" / "polyMesh", wedge.dir / "check");
  EXPECT_EQ(k.exit_code, 0) << k.output;
  EXPECT_THAT(k.output, HasSubstr("Mesh OK.")) << k.output;
}

// A wedge case is axisymmetric: with the wedge's axis in the case file, its inner wall (radius 1
// about the x axis) is the cylinder face of a revolved CAD part (hub_axisymmetric.geo, drawn by
// gmsh), deflected by a meridional (r, z) table that grows the radius by 0.05: the inner wall's
// points end at radius 1.05 on both wedge planes.
TEST(DeformFoam, WedgeCaseTakesItsWallFromTheRevolvedCadAboutItsAxis) {
  SKIP_WITHOUT_BLOCKMESH();
  const RampWedge wedge;
  const std::string geo = shell_quote(test::data_path("gmsh/hub_axisymmetric.geo").string());
  const auto cad = test::run_command("gmsh -0 -setnumber part 3 " + geo + " -o " + shell_quote((wedge.dir / "hub.step").string()));
  ASSERT_EQ(cad.exit_code, 0) << cad.output;
  std::string table = "r,z,dr,dz\n";
  for (int j = 0; j <= 20; ++j) table += fmt::format("1,{},0.05,0\n", 0.1 * j);
  test::write_text(wedge.dir / "hub.csv", table);
  // Face 1 of the hub: its cylinder of radius 1 (hotmesh cad lists it first, see test_deform_cad_2d.cpp).
  const RampWedge::Moved m =
      wedge.deform("mesh: cfd\ncad: hub.step\nlength_unit: mm\naxis: {origin: [0, 0, 0], direction: [1, 0, 0]}\n"
                   "patches:\n  left: {role: slip}\n  right: {role: slip}\n  top: {role: fixed}\n"
                   "  bottom: {role: sliding, deflection: {file: hub.csv, faces: [1], form: displacement}}\n");
  ASSERT_EQ(m.result.exit_code, 0) << m.result.output;
  ASSERT_EQ(m.moved.size(), m.original.size());
  int inner = 0;
  for (std::size_t q = 0; q < m.moved.size(); ++q) {
    if (std::abs(std::hypot(m.original[q].y, m.original[q].z) - 1.0) > 1e-12) continue;
    ++inner;
    EXPECT_NEAR(std::hypot(m.moved[q].y, m.moved[q].z), 1.05, 1e-9) << q;
  }
  EXPECT_EQ(inner, 44);  // 22 points along the wall on each wedge plane
}

TEST(DeformFoam, InfoShowsTheCasesPatchesAndConvertWritesItsMeshAsMsh) {
  SKIP_WITHOUT_BLOCKMESH();
  RampFoamCase c;
  const auto info = hotmesh("info " + shell_quote(c.cfd.string()));
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_THAT(info.output, HasSubstr("dimension   2D"));
  EXPECT_THAT(info.output, HasSubstr("cells       252 (252 quad4)"));
  EXPECT_THAT(info.output, Not(HasSubstr("frontAndBack")));
  const auto msh = c.dir / "ramp.msh";
  const auto convert =
      hotmesh("convert " + shell_quote((c.cfd / "constant" / "polyMesh").string()) + " " + shell_quote(msh.string()));
  ASSERT_EQ(convert.exit_code, 0) << convert.output;
  const mesh::Mesh converted = io::read_gmsh(msh), read = io::read_mesh(c.cfd).mesh;
  EXPECT_EQ(converted.points, read.points);
  EXPECT_EQ(converted.node_ids, read.node_ids);  // OpenFOAM labels + 1
  EXPECT_EQ(converted.cells, read.cells);
  ASSERT_EQ(converted.patches.size(), read.patches.size());
  for (std::size_t i = 0; i < read.patches.size(); ++i) {
    EXPECT_EQ(converted.patches[i].name, read.patches[i].name);
    EXPECT_EQ(converted.patches[i].faces, read.patches[i].faces);
  }
}

TEST(DeformFoam, BadFoamTimesAndNonHexMeshesExitWithCode2BeforeAnyWork) {
  SKIP_WITHOUT_BLOCKMESH();
  RampFoamCase c;
  const auto before = snapshot(c.cfd);
  for (const char* time : {"constant", "../system"}) {
    const auto out = c.dir / fmt::format("out-{}", time[0] == '.' ? "up" : time);
    const auto r = hotmesh("deform " + c.case_file() + " -o " + shell_quote(out.string()) + " --foam-time " + time);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr("is not a time folder's name"));
    EXPECT_FALSE(fs::exists(out));
  }
  EXPECT_EQ(snapshot(c.cfd), before);
  // --foam-time with a .msh mesh.
  test::RampCase msh(
      "mesh: ramp2d.msh\npatches: {left: {role: fixed}, right: {role: fixed}, top: {role: fixed}, "
      "bottom: {role: fixed}}\n");
  const auto r =
      hotmesh("deform " + msh.case_file() + " -o " + shell_quote((c.dir / "msh-out").string()) + " --foam-time 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("is not an OpenFOAM polyMesh"));
  // A polyhedron whose faces do not close: named with its shape.
  auto open = tf::split_top_cube();
  open.faces.erase(open.faces.begin() + 2);
  open.owner.pop_back();
  open.patches[0].count = 6;
  tf::write_poly_mesh(c.dir / "prism" / "constant" / "polyMesh", open);
  test::write_text(c.dir / "prism.yaml", "mesh: prism\npatches: {walls: {role: fixed}}\n");
  const auto p = hotmesh("deform " + shell_quote((c.dir / "prism.yaml").string()) + " -o " +
                         shell_quote((c.dir / "prism-out").string()));
  EXPECT_EQ(p.exit_code, 2) << p.output;
  EXPECT_THAT(p.output, HasSubstr("cell 0 has 6 faces (a polyhedron"));
}

TEST(ConvertFoam, WritesANewPolyMeshFromAHexMeshAndRefusesA2dMeshNamingTheFolder) {
  test::TempDir dir;
  const fs::path samples = fs::path(HOTMESH_SOURCE_DIR) / "samples";
  const fs::path polymesh = dir / "case" / "constant" / "polyMesh";
  const auto to_foam = hotmesh("convert --binary " + shell_quote((samples / "stator_well" / "stator_well.msh").string()) +
                               " " + shell_quote(polymesh.string()));
  ASSERT_EQ(to_foam.exit_code, 0) << to_foam.output;
  EXPECT_THAT(test::read_text(polymesh / "faces"), HasSubstr("faceCompactList"));
  const io::LoadedMesh back = io::read_mesh(dir / "case");
  EXPECT_EQ(back.mesh.node_count(), 25408u);
  EXPECT_EQ(back.mesh.cell_count(), 17979u);
  EXPECT_EQ(back.mesh.patches.size(), 17u);
  // The polyMesh just written, converted onto itself through its case folder: refused.
  const auto onto_itself = hotmesh("convert " + shell_quote((dir / "case").string()) + " " + shell_quote(polymesh.string()));
  EXPECT_EQ(onto_itself.exit_code, 2);
  EXPECT_THAT(onto_itself.output, HasSubstr("would replace an input file"));
  const fs::path flat = dir / "flat" / "constant" / "polyMesh";
  const auto refused =
      hotmesh("convert " + shell_quote((samples / "ramp2d" / "ramp2d.msh").string()) + " " + shell_quote(flat.string()));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.output, HasSubstr(flat.string()));
  EXPECT_THAT(refused.output, HasSubstr("3D meshes only"));
  EXPECT_FALSE(fs::exists(flat));
}

}  // namespace
}  // namespace hotmesh::app
