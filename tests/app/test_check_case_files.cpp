// Tests of `hotmesh check --case`: the case file gives the walls a mesh is checked against, as
// in the coupled loop (the ramp2d sliding case deformed by hotmesh deform and then checked; the
// stator-well case's own mesh on its CAD; a 2D wall on CAD edges before and after deformation),
// and the options and meshes a case refuses.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "channel_step.hpp"
#include "occt_fixtures.hpp"
#include "run_command.hpp"
#include "test_support.hpp"
#include "check_command_support.hpp"

namespace hotmesh::app {
namespace {

using namespace check_test;  // NOLINT: the helpers of these tests
using ::testing::HasSubstr;

/// The node of `patch` nearest to `point` that is on no other patch of `mesh`.
mesh::NodeId nearest_own_node(const mesh::Mesh& mesh, const std::string& patch, const geometry::Vec3& point) {
  std::vector<mesh::NodeId> own;
  for (const mesh::NodeId n : mesh.find_patch(patch)->nodes) {
    const bool shared = std::any_of(mesh.patches.begin(), mesh.patches.end(), [&](const mesh::Patch& other) {
      return other.name != patch && std::binary_search(other.nodes.begin(), other.nodes.end(), n);
    });
    if (!shared) own.push_back(n);
  }
  return *std::min_element(own.begin(), own.end(), [&](mesh::NodeId a, mesh::NodeId b) {
    return distance(mesh.points[static_cast<std::size_t>(a)], point) < distance(mesh.points[static_cast<std::size_t>(b)], point);
  });
}

// The coupled-loop workflow on the ramp2d sliding sample: `hotmesh deform case.yaml -o out`,
// then `hotmesh check out/deformed.msh --case case.yaml`, the case giving every patch's wall.
TEST(CheckCommand, CaseFileGivesTheWallsADeformedMeshIsCheckedAgainst) {
  test::TempDir dir;
  // The paper's sliding (features off), which cuts corner A.
  const std::filesystem::path case_file = kSamples / "ramp2d/ramp2d-sliding-nofeatures.yaml";
  const auto deformed = hotmesh("-q deform " + q(case_file) + " -o " + q(dir / "out"));
  ASSERT_EQ(deformed.exit_code, 0) << deformed.output;

  const auto [hot_code, hot] = check_json(q(dir / "out/deformed.msh") + " --case " + q(case_file));
  ASSERT_EQ(hot_code, 0) << hot.dump(2);
  EXPECT_EQ(hot["case"], case_file.string());
  ASSERT_EQ(hot["patches"].size(), 2u);  // the sliding patches, in the order of the case file
  EXPECT_EQ(hot["patches"][0]["patch"], "top");
  EXPECT_EQ(hot["patches"][1]["patch"], "bottom");
  for (const Json& patch : hot["patches"]) {
    EXPECT_EQ(patch["nodes"], 58);
    EXPECT_LT(patch["max_distance"].get<double>(), 1e-12) << patch["patch"];
    EXPECT_EQ(patch["wall"]["passed"], true) << patch["patch"];  // no --wall-tol: reported only
    EXPECT_THAT(patch["reference"].get<std::string>(), HasSubstr("the deflected wall of the case (sliding)"));
  }
  EXPECT_THAT(hot["patches"][1]["reference"].get<std::string>(),
              HasSubstr("the curve through the FEM nodes of ramp.csv, deflected by them (eq. 21, curve form, degree 1)"));
  // The upper wall slid along its straight self; the lower one's nodes gathered on the ramp,
  // leaving corner A, at the ramp's foot, to one long edge.
  EXPECT_LT(hot["patches"][0]["wall"]["hausdorff"].get<double>(), 1e-12);
  EXPECT_GT(hot["patches"][1]["wall"]["hausdorff"].get<double>(), 0.02);
  EXPECT_NEAR(hot["patches"][1]["wall"]["worst_point"][0].get<double>(), 0.975, 1e-9);

  // A node of the flat part of the deflected wall 10 um up (the cells there are thin: the
  // sliding nodes gathered on the ramp): found.
  mesh::Mesh mesh = io::read_gmsh(dir / "out/deformed.msh");
  const mesh::NodeId moved = nearest_own_node(mesh, "bottom", {0.3, 0.0, 0.0});
  mesh.points[static_cast<std::size_t>(moved)].y += 1e-5;
  io::write_gmsh(dir / "perturbed.msh", mesh);
  const auto [fail_code, fail] = check_json(q(dir / "perturbed.msh") + " --case " + q(case_file));
  ASSERT_EQ(fail_code, 1) << fail.dump(2);
  EXPECT_EQ(fail["patches"][0]["passed"], true);
  EXPECT_EQ(fail["patches"][1]["worst_node"]["id"], mesh.node_id(moved));
  EXPECT_NEAR(fail["patches"][1]["max_distance"].get<double>(), 1e-5, 1e-12);

  // Without a mesh, the case's own mesh against its undeformed walls.
  const auto [cold_code, cold] = check_json("--case " + q(case_file));
  ASSERT_EQ(cold_code, 0) << cold.dump(2);
  EXPECT_EQ(cold["mesh"], (kSamples / "ramp2d/ramp2d.msh").string());
  EXPECT_THAT(cold["patches"][1]["reference"].get<std::string>(),
              HasSubstr("the undeformed wall of the case (sliding): the curve through the FEM nodes of ramp.csv in the"));
  // Any other mesh is taken as deformed: a copy of the undeformed one is as far from the
  // deflected ramp as the ramp's height.
  std::filesystem::copy_file(kSamples / "ramp2d/ramp2d.msh", dir / "copy.msh");
  const auto [copy_code, copy] = check_json(q(dir / "copy.msh") + " --case " + q(case_file));
  EXPECT_EQ(copy_code, 1);
  EXPECT_GT(copy["patches"][1]["max_distance"].get<double>(), 0.1);
}

// The stator-well sample's case on its own mesh: the ten walls that follow the FEM tables,
// prescribed and sliding, lie on their CAD faces (taken with the case's axis and unit).
TEST(CheckCommand, CaseFileOfTheStatorWellSampleChecksItsTenWallsOnTheCad) {
  const auto [code, report] = check_json("--case " + q(kSamples / "stator_well/case_small.yaml"));
  ASSERT_EQ(code, 0) << report.dump(2);
  EXPECT_EQ(report["cad"], (kSamples / "stator_well/stator_well.step").string());
  std::vector<std::string> patches;
  for (const Json& patch : report["patches"]) {
    patches.push_back(patch["patch"]);
    EXPECT_LT(patch["max_distance"].get<double>(), 1e-12) << patch["patch"];
    EXPECT_THAT(patch["reference"].get<std::string>(), HasSubstr("the undeformed wall of the case"));
    EXPECT_THAT(patch["reference"].get<std::string>(), HasSubstr("of stator_well.step about the axis (0, 0, 0) along (0, 0, 1)"));
  }
  EXPECT_EQ(patches, (std::vector<std::string>{"stator_front", "fins", "stator_rear", "rim_up", "disc_up_upper", "joint",
                                               "disc_up_lower", "disc_base", "disc_down", "rim_down"}));
  EXPECT_THAT(report["patches"][8]["reference"].get<std::string>(),
              HasSubstr("the undeformed wall of the case (sliding): CAD faces 40, 41, 42 of stator_well.step"));
}

TEST(CheckCommand, CaseFileRefusesTheOptionsItGivesAndMeshesOfOtherCases) {
  test::TempDir dir;
  const std::string ramp = " --case " + q(kSamples / "ramp2d/ramp2d-sliding.yaml");
  auto expect = [](const test::CommandResult& r, const std::string& text) {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr(text));
  };
  expect(hotmesh("check" + ramp + " --map bottom=1 --unit mm"), "--map, --unit: not with --case, which gives");
  expect(hotmesh("check" + ramp + " --mode surface"), "--mode: not with --case");
  expect(hotmesh("check" + ramp + " --deflection bottom=" + q(kSamples / "ramp2d/ramp.csv")), "--deflection: not with --case");
  expect(hotmesh("check " + q(kSamples / "shear2d/shear2d.msh") + ramp), "give a mesh the case was deformed into");
  // A case whose patches follow no boundary has nothing to check.
  test::write_text(dir / "fixed.yaml", fmt::format("mesh: {}\npatches:\n  left: {{role: fixed}}\n  right: {{role: slip}}\n"
                                                   "  top: {{role: fixed}}\n  bottom: {{role: fixed}}\n",
                                                   (kSamples / "ramp2d/ramp2d.msh").string()));
  expect(hotmesh("check --case " + q(dir / "fixed.yaml")), "no patch follows a boundary (role prescribed or sliding)");
  // The case's own errors, with its file and line.
  test::write_text(dir / "typo.yaml", "mesh: ramp2d.msh\n");
  expect(hotmesh("check --case " + q(dir / "typo.yaml")), "typo.yaml:1: mesh:");
}

// With --case, the walls hotmesh deform builds: the case's own mesh on the wall the CAD edges
// give, the mesh it deforms into on the wall the FEM table deflects (displacement form).
TEST(CheckCommand, CaseWithAWallOnCadEdgesChecksItsMeshBeforeAndAfterDeformation) {
  const test::ChannelStep channel;
  channel.write_table("bottom.csv", {0.0, 0.03});
  const std::string case_file = channel.write_case(fmt::format(
      "{{role: sliding, deflection: {{file: bottom.csv, edges: [{}], form: displacement}}}}", channel.wall_edge_list()));
  const auto [own_code, own] = check_json("--case " + case_file);
  ASSERT_EQ(own_code, 0) << own.dump(2);
  EXPECT_LT(own["patches"][0]["max_distance"].get<double>(), 1e-9);
  EXPECT_THAT(own["patches"][0]["reference"].get<std::string>(), HasSubstr("CAD edges"));
  const auto deformed = hotmesh("-q deform " + case_file + " -o " + q(channel.path("out")));
  ASSERT_EQ(deformed.exit_code, 0) << deformed.output;
  const auto [code, report] = check_json(q(channel.path("out/deformed.msh")) + " --case " + case_file);
  ASSERT_EQ(code, 0) << report.dump(2);
  EXPECT_LT(report["patches"][0]["max_distance"].get<double>(), 1e-9);
}

}  // namespace
}  // namespace hotmesh::app
