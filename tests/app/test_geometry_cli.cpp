// Tests of `hotmesh cad` and `hotmesh curve`: face and edge listings of real CAD files, the
// outputs of a reconstruction with and without CAD (checked values, not just files), and user
// errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <utility>

#include <cmath>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cone_nodes.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using test::run_command;
using test::shell_quote;

test::CommandResult hotmesh(const std::string& arguments) {
  return run_command(std::string(HOTMESH_EXE) + " " + arguments);
}

std::string cad(const std::string& name) { return shell_quote(test::data_path("cad/" + name).string()); }

using test::cone_nodes;

std::vector<std::vector<double>> read_csv(const std::filesystem::path& path, std::string& header) {
  std::ifstream in(path);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

TEST(CadCli, CadAndCurveHaveHelp) {
  for (const std::string command : {"cad", "curve"}) {
    const auto r = hotmesh(command + " --help");
    EXPECT_EQ(r.exit_code, 0) << command;
    EXPECT_THAT(r.output, HasSubstr("Usage:")) << command;
  }
  EXPECT_THAT(hotmesh("curve --help").output, HasSubstr("--drop-far-nodes"));
}

TEST(CadCli, ListsFacesWithKindsAndAxes) {
  const auto text = hotmesh("cad --unit mm " + cad("OCC8842_cone_CATIA.igs"));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_THAT(text.output, HasSubstr("3 faces, 6 edges, lengths in mm"));
  EXPECT_THAT(text.output, Not(HasSubstr("edge  kind")));  // a 3D part: its edges on request (--edges)
  EXPECT_THAT(text.output, HasSubstr("revolution  (0, 0, 80) along (0, 0, 1) [analytic]"));

  const auto json = hotmesh("-q cad --json " + cad("OCC8842_cone_Ideas.igs"));
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto j = nlohmann::json::parse(json.output);
  EXPECT_EQ(j["unit"], "m");
  ASSERT_EQ(j["faces"].size(), 2u);
  EXPECT_EQ(j["faces"][0]["kind"], "bspline");
  EXPECT_EQ(j["faces"][0]["name"], "F1(1)");
  EXPECT_EQ(j["faces"][0]["axis"]["source"], "fitted");
  EXPECT_NEAR(std::abs(j["faces"][0]["axis"]["direction"][1].get<double>()), 1.0, 1e-9);
  EXPECT_TRUE(j["faces"][1]["axis"].is_null());
  EXPECT_NEAR(j["faces"][0]["bounds"]["max"][1].get<double>(), 0.1, 1e-6);  // 100 mm
}

// The walls of 2D cases are CAD edges: listed by default for a drawing without faces (or in one
// plane), on request (--edges) for any other file, and always in the JSON.
TEST(CadCli, ListsEdgesOfDrawingsAndOnRequest) {
  const auto disc = hotmesh("cad " + cad("Disc.igs"));
  ASSERT_EQ(disc.exit_code, 0) << disc.output;
  EXPECT_THAT(disc.output, HasSubstr("Disc.igs: 0 faces, 46 edges, lengths in m"));
  EXPECT_THAT(disc.output, HasSubstr("\n  46  "));
  const auto asked = hotmesh("cad --edges --unit mm " + cad("OCC8842_cone_CATIA.igs"));
  ASSERT_EQ(asked.exit_code, 0) << asked.output;
  EXPECT_THAT(asked.output, HasSubstr("edge  kind        start"));
  EXPECT_THAT(asked.output, HasSubstr("circle"));
  const auto json = hotmesh("-q cad --json " + cad("Disc.igs"));
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto edges = nlohmann::json::parse(json.output)["edges"];
  ASSERT_EQ(edges.size(), 46u);
  EXPECT_EQ(edges[0]["id"], 1);
  EXPECT_EQ(edges[0]["kind"], "line");
  EXPECT_NEAR(edges[0]["length"].get<double>(), 0.1116, 1e-6);  // from (-0.500716, -0.657282) to (-0.612316, -0.657282)
}

TEST(CadCli, FilesWithoutShapesOrNotCadAreUserErrors) {
  test::TempDir dir;
  test::write_text(dir / "notes.step", "not a step file\n");
  const auto notes = hotmesh("cad " + shell_quote((dir / "notes.step").string()));
  EXPECT_EQ(notes.exit_code, 2);
  EXPECT_THAT(notes.output, HasSubstr("not a STEP file"));
  EXPECT_EQ(hotmesh("cad --unit furlong " + cad("screw.step")).exit_code, 2);
}

// Issue 18, item 3: the issue's own command, which ended in a segmentation fault (exit 139).
TEST(CadCli, StepFileWithABadReferenceIsAUserError) {
  test::TempDir dir;
  const std::filesystem::path step = std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples" / "stator_well" / "stator_well.step";
  const auto bad = dir / "bad.step";
  ASSERT_EQ(run_command("sed \"s/^#62 = VERTEX_POINT('',#63);/#62 = VERTEX_POINT('',#9999999);/\" " +
                        shell_quote(step.string()) + " > " + shell_quote(bad.string()))
                .exit_code,
            0);
  const auto r = hotmesh("cad " + shell_quote(bad.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(bad.string() + ": the STEP file is damaged"));
}

TEST(CurveCli, ReconstructsTheConeFromCartesianNodes) {
  test::TempDir dir;
  test::write_text(dir / "nodes.csv", cone_nodes(21));
  const auto out = dir / "out";
  const auto r = hotmesh("curve --cad " + cad("OCC8842_cone_CATIA.igs") + " --faces 1,2 --unit mm --fem " +
                         shell_quote((dir / "nodes.csv").string()) + " -o " + shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const auto summary = nlohmann::json::parse(test::read_text(out / "summary.json"));
  EXPECT_EQ(summary["nodes"], 21);
  EXPECT_EQ(summary["degree"], 1);
  EXPECT_EQ(summary["form"], "curve");
  EXPECT_EQ(summary["frame"], "rz");
  EXPECT_LT(summary["max_node_distance_to_cad"].get<double>(), 1e-6);  // the file's accuracy
  EXPECT_LT(summary["max_node_residual"].get<double>(), 1e-12);
  EXPECT_EQ(summary["rejected_nodes"].size(), 0u);
  EXPECT_NEAR(summary["parameter_range"][0].get<double>(), 0.0, 1e-8);
  EXPECT_NEAR(summary["parameter_range"][1].get<double>(), 1.0, 1e-8);

  // (r, z) about the axis through the apex: the profile runs from the base rim (60, -150) to the
  // apex; the deformed curve is the profile moved by the deflection (exact at the ends).
  std::string header;
  const auto undeformed = read_csv(out / "undeformed.csv", header);
  EXPECT_EQ(header, "t,r,z");
  EXPECT_GE(undeformed.size(), 2001u);
  EXPECT_NEAR(undeformed.front()[1], 60.0, 1e-6);
  EXPECT_NEAR(undeformed.front()[2], -150.0, 1e-6);
  const auto deformed = read_csv(out / "deformed.csv", header);
  EXPECT_NEAR(deformed.front()[1], 60.5, 1e-6);
  EXPECT_NEAR(deformed.front()[2], -150.2, 1e-6);
  EXPECT_NEAR(deformed.back()[1], 0.0, 1e-6);
  const auto& mid = deformed[deformed.size() / 2];  // t = 0.5: s = 0.5, on a node
  EXPECT_NEAR(mid[1], 30.0 + 0.125, 1e-6);
  EXPECT_NEAR(mid[2], -75.0 - 0.1, 1e-6);

  EXPECT_THAT(test::read_text(out / "curves.step"), HasSubstr("GEOMETRIC_CURVE_SET('deformed'"));
  EXPECT_THAT(test::read_text(out / "curves.step"), HasSubstr("SI_UNIT(.MILLI.,.METRE.)"));
  EXPECT_THAT(test::read_text(out / "curves.igs"), HasSubstr("undeform"));
  const std::string svg = test::read_text(out / "plot.svg");
  EXPECT_THAT(svg, HasSubstr("<svg"));
  EXPECT_EQ(summary["amplification"], 20.0);  // 10 % of a 162 mm curve over a 0.54 mm deflection
}

TEST(CurveCli, FarNodesAreNamedOrDropped) {
  test::TempDir dir;
  test::write_text(dir / "nodes.csv", cone_nodes(11, 2.0));  // node 103 is 2 mm off the cone
  const std::string common = "curve --cad " + cad("OCC8842_cone_CATIA.igs") + " --faces 1,2 --unit mm --fem " +
                             shell_quote((dir / "nodes.csv").string());
  const auto fail = hotmesh(common + " -o " + shell_quote((dir / "a").string()));
  EXPECT_EQ(fail.exit_code, 2);
  EXPECT_THAT(fail.output, HasSubstr("1 of 11 FEM nodes are farther than"));
  EXPECT_THAT(fail.output, HasSubstr("node 103 (line 9) at distance 1.85"));  // written out of order
  const auto drop = hotmesh(common + " --drop-far-nodes --degree 3 --form displacement -o " + shell_quote((dir / "b").string()));
  ASSERT_EQ(drop.exit_code, 0) << drop.output;
  const auto summary = nlohmann::json::parse(test::read_text(dir / "b" / "summary.json"));
  EXPECT_EQ(summary["used_nodes"], 10);
  EXPECT_EQ(summary["degree"], 3);
  EXPECT_EQ(summary["form"], "displacement");
  ASSERT_EQ(summary["rejected_nodes"].size(), 1u);
  EXPECT_EQ(summary["rejected_nodes"][0]["id"], 103);
  EXPECT_EQ(summary["rejected_nodes"][0]["line"], 9);
}

TEST(CurveCli, TwoDimensionalNodesWithoutCad) {
  test::TempDir dir;
  // An L-shaped wall sampled out of order, pushed up by 0.01 x.
  test::write_text(dir / "wall.csv", "x,y,dx,dy\n2,0,0,0.02\n0,0,0,0\n2,1,0,0.02\n1,0,0,0.01\n2,0.5,0,0.02\n");
  const auto r = hotmesh("curve --fem " + shell_quote((dir / "wall.csv").string()) + " --samples 4 -o " +
                         shell_quote((dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string header;
  const auto deformed = read_csv(dir / "out" / "deformed.csv", header);
  EXPECT_EQ(header, "t,x,y");
  // t is the chord length along (0,0) (1,0) (2,0) (2,0.5) (2,1), over 3: the uniform samples
  // 0, 1/4, ..., 1 and the nodes at 1/3, 2/3 and 5/6.
  ASSERT_EQ(deformed.size(), 8u);
  const auto at = [&](double t) {
    for (const auto& row : deformed) {
      if (std::abs(row[0] - t) < 1e-12) return row;
    }
    return std::vector<double>{};
  };
  ASSERT_EQ(at(1.0 / 3.0).size(), 3u);
  EXPECT_NEAR(at(1.0 / 3.0)[1], 1.0, 1e-12);
  EXPECT_NEAR(at(1.0 / 3.0)[2], 0.01, 1e-12);
  ASSERT_EQ(at(5.0 / 6.0).size(), 3u);
  EXPECT_NEAR(at(5.0 / 6.0)[1], 2.0, 1e-12);
  EXPECT_NEAR(at(5.0 / 6.0)[2], 0.52, 1e-12);
  ASSERT_EQ(at(0.25).size(), 3u);
  EXPECT_NEAR(at(0.25)[2], 0.0075, 1e-12);  // between the nodes the polyline of deflected nodes
  const auto summary = nlohmann::json::parse(test::read_text(dir / "out" / "summary.json"));
  EXPECT_EQ(summary["frame"], "xy");
  EXPECT_TRUE(summary["cad"].is_null());
}

/// Runs `hotmesh curve ARGUMENTS -o DIR/out` and checks it wrote every output.
void expect_curve_written(const test::TempDir& dir, const std::string& arguments) {
  const auto r = hotmesh("-q curve " + arguments + " -o " + shell_quote((dir / "out").string()) + " --force");
  ASSERT_EQ(r.exit_code, 0) << arguments << "\n" << r.output;
  for (const char* f : {"undeformed.csv", "deformed.csv", "curves.step", "curves.igs", "plot.svg", "summary.json"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << arguments << ": " << f;
  }
  const auto summary = nlohmann::json::parse(test::read_text(dir / "out" / "summary.json"));
  EXPECT_LT(summary["max_node_residual"].get<double>(), 1e-9) << arguments;
}

// Issue 18, item 1: an FEM node on a CAD knot to rounding (a face end, the junction of two
// faces) ended in "critical internal error: bezier_pieces: ..." (exit 3). The sample's own
// tables and the real CAD files showed it.
TEST(CurveCli, NodesOnCadKnotsAndFaceEnds) {
  test::TempDir dir;
  const std::filesystem::path sample = std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples" / "stator_well";
  const std::string step = shell_quote((sample / "stator_well.step").string());
  const std::string about_z = " --form displacement --axis 0,0,0,0,0,1";
  for (const auto& [faces, table] : {std::pair{"40,41,42", "disc_down.csv"}, std::pair{"32,33,34", "disc_up_upper.csv"},
                                     std::pair{"13,14,15,16,17,18,19,20,21,22,23,24,25", "fins.csv"}}) {
    expect_curve_written(dir, "--cad " + step + " --faces " + faces + " --fem " +
                                  shell_quote((sample / table).string()) + about_z);
  }
  // The CATIA bolt: head, shoulder and shank, nodes at their corners (z = 3 mm).
  test::write_text(dir / "bolt.csv", "r,z,dr,dz\n7.5,0,0.01,0\n7.5,1.5,0.01,0\n7.5,3,0.01,0.01\n6.25,3,0,0.01\n"
                                     "5,3,0.01,0.01\n5,20,0.01,0.02\n5,37,0.01,0.03\n");
  expect_curve_written(dir, "--cad " + cad("bug3883_xr2-ct-214_bolt.stp") +
                                " --unit mm --faces 2,1,4 --fem " + shell_quote((dir / "bolt.csv").string()) + about_z);
  // The I-DEAS cylinder (a B-spline face about y), nodes at both ends.
  test::write_text(dir / "cylinder.csv", "r,z,dr,dz\n25,-75,0.1,0\n25,0,0.2,0\n25,75,0.1,0.1\n");
  expect_curve_written(dir, "--cad " + cad("OCC8842_cylinder_Ideas.igs") +
                                " --unit mm --faces 1 --fem " + shell_quote((dir / "cylinder.csv").string()) +
                                " --form displacement --axis 0,0,0,0,1,0");
}

// Issue 18, item 2: degrees 3 and 5 without CAD gave the same internal error.
TEST(CurveCli, OddDegreesWithoutCad) {
  test::TempDir dir;
  const std::string ramp = shell_quote((std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples" / "ramp2d" / "ramp.csv").string());
  for (const char* degree : {"2", "3", "5"}) expect_curve_written(dir, "--fem " + ramp + " --degree " + degree);
}

TEST(CurveCli, RefusesBadOptionsAndFoldersHoldingInputs) {
  test::TempDir dir;
  test::write_text(dir / "nodes.csv", cone_nodes(5));
  const std::string nodes = shell_quote((dir / "nodes.csv").string());
  const std::string base = "curve --cad " + cad("OCC8842_cone_CATIA.igs") + " --unit mm --fem " + nodes;
  const auto in_place = hotmesh(base + " --faces 1 -o " + shell_quote(dir.path().string()));
  EXPECT_EQ(in_place.exit_code, 2);
  EXPECT_THAT(in_place.output, HasSubstr("nodes.csv"));
  EXPECT_EQ(hotmesh(base + " --faces 1 --degree 7 -o " + shell_quote((dir / "x").string())).exit_code, 2);
  const auto no_faces = hotmesh(base + " -o " + shell_quote((dir / "y").string()));
  EXPECT_EQ(no_faces.exit_code, 2);
  EXPECT_THAT(no_faces.output, HasSubstr("--cad needs --faces"));
  const auto bad_axis = hotmesh(base + " --faces 1 --axis 0,0,0,0,0 -o " + shell_quote((dir / "z").string()));
  EXPECT_EQ(bad_axis.exit_code, 2);
  EXPECT_THAT(bad_axis.output, HasSubstr("--axis needs six numbers"));
  const auto wrong_face = hotmesh(base + " --faces 3 --axis 1,0,0,0,1,0 -o " + shell_quote((dir / "w").string()));
  EXPECT_EQ(wrong_face.exit_code, 2);
  EXPECT_THAT(wrong_face.output, HasSubstr("face 3 (plane) is not a surface of revolution about the axis"));
  // Nothing was written next to the inputs.
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) names.push_back(e.path().filename().string());
  EXPECT_THAT(names, ::testing::UnorderedElementsAre("nodes.csv"));
}

}  // namespace
}  // namespace hotmesh::app
