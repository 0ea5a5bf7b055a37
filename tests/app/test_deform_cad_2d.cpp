// End-to-end tests of `hotmesh deform` on 2D walls from CAD (issue 45, item 2), on files made
// as users make them, with gmsh's OpenCASCADE kernel:
//  - a planar case: the 2D channel with a forward-facing step of channel_step.hpp, its lower wall
//    named by its CAD edges (`edges:`), deflected by a rigid shift given at FEM nodes at most
//    0.8 mm apart; the deflected wall is then the CAD wall shifted, fillet included, which the
//    nodes are measured against;
//  - the next coupling iteration, restarted on the same edges with a new shift;
//  - an axisymmetric case: a 2D mesh in the (z, r) half plane of a hub (a cylinder, then a cone)
//    whose revolved solid is the CAD, the wall named by the hub's faces, the axis given;
//  - the inputs a 2D case refuses: edges out of the mesh's plane, edges that do not chain, CAD
//    faces without an axis.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "channel_step.hpp"
#include "deform_cases.hpp"
#include "hotmesh/io/gmsh.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using geometry::Vec2;
using test::ChannelStep;
using test::hotmesh;
using test::shell_quote;
using test::StepWall;

/// The rigid shift of the lower wall, mm: up by the 0.03 mm.
const Vec2 kShift{0.0, 0.03};

struct WallMotion {
  test::CommandResult result;
  std::vector<Vec2> before;  ///< the wall patch's nodes, undeformed
  std::vector<Vec2> after;   ///< the same nodes, deformed
};

/// `hotmesh deform` of the case in `folder` into `folder`/`out`, and where the nodes of patch
/// `wall` of its mesh `mesh_name` went.
WallMotion deform(const std::filesystem::path& folder, const std::string& mesh_name, const std::string& wall,
                  const std::string& out = "out") {
  WallMotion m;
  m.result = hotmesh("-q deform " + shell_quote((folder / "case.yaml").string()) + " -o " +
                     shell_quote((folder / out).string()));
  if (m.result.exit_code != 0) return m;
  const mesh::Mesh before = io::read_gmsh(folder / mesh_name);
  const mesh::Mesh after = io::read_gmsh(folder / out / "deformed.msh");
  for (const mesh::NodeId n : before.find_patch(wall)->nodes) {
    const auto& p = before.points[static_cast<std::size_t>(n)];
    const auto& q = after.points[static_cast<std::size_t>(n)];
    m.before.push_back({p.x, p.y});
    m.after.push_back({q.x, q.y});
  }
  return m;
}

/// The lower wall deflected by kShift as the FEM table gives it, in the form asked for.
WallMotion shifted_channel(const ChannelStep& channel, const std::string& form) {
  channel.write_table("bottom.csv", kShift);
  channel.write_case(fmt::format("{{role: sliding, deflection: {{file: bottom.csv, edges: [{}]{}}}}}",
                                 channel.wall_edge_list(), form.empty() ? "" : ", form: " + form));
  return deform(channel.dir(), "channel.msh", "bottom");
}

/// The largest distance from the fillet's circle moved by `shift` of the deformed nodes within
/// its arc (seen from its centre: up and to the left; nodes slide, so a node that started at an
/// end of the arc may end on the line next to it), and how many there are.
std::pair<double, int> fillet_miss(const WallMotion& m, const Vec2& shift = kShift) {
  double worst = 0.0;
  int count = 0;
  for (const Vec2& q : m.after) {
    const Vec2 r = q - (StepWall::centre() + shift);
    if (r.x > 0.0 || r.y < 0.0) continue;
    ++count;
    worst = std::max(worst, StepWall::off_fillet(q, shift));
  }
  return {worst, count};
}

TEST(DeformCad2d, WallOnCadEdgesInDisplacementFormIsTheShiftedCadWallFilletIncluded) {
  const ChannelStep channel;
  ASSERT_EQ(channel.wall_edges().size(), 4u);
  const WallMotion m = shifted_channel(channel, "displacement");
  ASSERT_EQ(m.result.exit_code, 0) << m.result.output;
  double worst = 0.0;
  for (const Vec2& q : m.after) worst = std::max(worst, StepWall::off_wall(q, kShift));
  EXPECT_LT(worst, 1e-9);
  const auto [fillet, count] = fillet_miss(m);
  EXPECT_GE(count, 3);
  EXPECT_LT(fillet, 1e-9 * StepWall::kRadius);
  // The sharp foot, a CAD vertex and a mesh node, is a corner of the wall its node holds.
  const auto foot = std::find_if(m.before.begin(), m.before.end(), [](const Vec2& p) { return distance(p, {10, 0}) < 1e-12; });
  ASSERT_NE(foot, m.before.end());
  EXPECT_LT(distance(m.after[static_cast<std::size_t>(foot - m.before.begin())], Vec2{10, 0} + kShift), 1e-9);
}

// The complaint: the curve through the deflected FEM nodes (form curve, degree 1) cuts
// the fillet between them, by up to R (1 - cos(pi / 16)) = 0.038 mm, more than the deflection.
TEST(DeformCad2d, CurveFormThroughTheFemNodesCutsTheFilletBetweenThem) {
  const ChannelStep channel;
  const WallMotion m = shifted_channel(channel, "");
  ASSERT_EQ(m.result.exit_code, 0) << m.result.output;
  const auto [fillet, count] = fillet_miss(m);
  EXPECT_GE(count, 3);
  EXPECT_GT(fillet, 1e-3);
}

// The next coupling iteration (section 4.3, eq. 22): restarted from the first run's state with a
// new table, the wall goes from the first deflected wall to the new one, both on the CAD's
// edges: the restart keeps them, and the fillet is the CAD's circle moved by the new shift.
TEST(DeformCad2d, RestartGoesOnOnTheCadEdgesToTheNewDeflection) {
  const ChannelStep channel;
  ASSERT_EQ(shifted_channel(channel, "displacement").result.exit_code, 0);
  const Vec2 next{0.0, 0.05};
  channel.write_table("bottom.csv", next);
  channel.write_case(fmt::format("{{role: sliding, deflection: {{file: bottom.csv, edges: [{}], form: displacement}}}}",
                                 channel.wall_edge_list()),
                     "cad: channel.step\nrestart: out/restart.hmr\n");
  const WallMotion m = deform(channel.dir(), "channel.msh", "bottom", "second");
  ASSERT_EQ(m.result.exit_code, 0) << m.result.output;
  const auto [fillet, count] = fillet_miss(m, next);
  EXPECT_GE(count, 3);
  EXPECT_LT(fillet, 1e-9 * StepWall::kRadius);
  double worst = 0.0;
  for (const Vec2& q : m.after) worst = std::max(worst, StepWall::off_wall(q, next));
  EXPECT_LT(worst, 1e-9);
}

TEST(DeformCad2d, EdgesOutOfTheMeshPlaneAreRefusedNamingTheEdgeAndItsDistance) {
  const ChannelStep channel;
  channel.write_lifted_cad("lifted.step");
  const std::vector<int> lifted = channel.edges_along_wall("lifted.step");
  ASSERT_EQ(lifted.size(), 4u);
  channel.write_table("bottom.csv", kShift);
  channel.write_case(fmt::format("{{role: sliding, deflection: {{file: bottom.csv, edges: [{}]}}}}", fmt::join(lifted, ", ")),
                     "cad: lifted.step\n");
  const auto r = hotmesh("-q deform " + shell_quote(channel.path("case.yaml")) + " -o " + shell_quote(channel.path("out")));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("patches.bottom: deflection.edges: " + channel.path("lifted.step") + ": edge "));
  EXPECT_THAT(r.output, HasSubstr("is not in the mesh's plane z = 0: it reaches 0.5 from it"));
}

TEST(DeformCad2d, EdgesThatDoNotFormOneChainAreRefused) {
  const ChannelStep channel;
  std::vector<int> without_fillet = channel.wall_edges();
  without_fillet.erase(without_fillet.begin() + 2);  // the listing keeps the wall's order: the arc is third
  channel.write_table("bottom.csv", kShift);
  channel.write_case(
      fmt::format("{{role: sliding, deflection: {{file: bottom.csv, edges: [{}]}}}}", fmt::join(without_fillet, ", ")));
  const auto r = hotmesh("-q deform " + shell_quote(channel.path("case.yaml")) + " -o " + shell_quote(channel.path("out")));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("patches.bottom: deflection.edges: "));
  EXPECT_THAT(r.output, HasSubstr("do not form one chain"));
}

TEST(DeformCad2d, CadFacesInA2DCaseWithoutAxisAreRefused) {
  const ChannelStep channel;
  channel.write_table("bottom.csv", kShift);
  channel.write_case("{role: sliding, deflection: {file: bottom.csv, faces: [1]}}");
  const auto r = hotmesh("-q deform " + shell_quote(channel.path("case.yaml")) + " -o " + shell_quote(channel.path("out")));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("patches.bottom.deflection.faces: CAD faces are surfaces: a 2D case takes them only "
                                  "when it is axisymmetric"));
}

/// The hub's radius at axial position z (hub_axisymmetric.geo): 1 up to z = 4, then the cone
/// down to 0.5 at z = 7.
double hub_radius(double z) { return z <= 4.0 ? 1.0 : 1.0 - (z - 4.0) / 6.0; }

// An axisymmetric 2D case: the mesh drawn in the (z, r) half plane of the x axis, the wall given
// as the revolved CAD's cylinder and cone faces with the case's axis; the FEM table in (r, z)
// grows the hub's radius by 0.02 mm, which the displacement form makes the profile moved out by
// 0.02 exactly.
TEST(DeformCad2d, AxisymmetricCaseTakesItsWallFromTheRevolvedFaces) {
  test::TempDir dir;
  const std::string geo = shell_quote(test::data_path("gmsh/hub_axisymmetric.geo").string());
  ASSERT_EQ(test::run_command("gmsh -2 -nt 1 " + geo + " -format msh41 -o " + shell_quote((dir / "hub.msh").string())).exit_code, 0);
  ASSERT_EQ(test::run_command("gmsh -0 -setnumber part 3 " + geo + " -o " + shell_quote((dir / "hub.step").string())).exit_code, 0);
  const auto listing = hotmesh("-q cad --json --unit mm " + shell_quote((dir / "hub.step").string()));
  ASSERT_EQ(listing.exit_code, 0) << listing.output;
  const nlohmann::json model = nlohmann::json::parse(listing.output);
  std::vector<int> faces;
  for (const auto& face : model["faces"]) {
    if (face["kind"] == "cylinder" || face["kind"] == "cone") faces.push_back(face["id"].get<int>());
  }
  ASSERT_EQ(faces.size(), 2u) << listing.output;
  std::string table = "r,z,dr,dz\n";
  for (int j = 0; j <= 28; ++j) table += fmt::format("{:.17g},{:.17g},0.02,0\n", hub_radius(0.25 * j), 0.25 * j);
  test::write_text(dir / "hub.csv", table);
  test::write_text(dir / "case.yaml",
                   fmt::format("mesh: hub.msh\ncad: hub.step\nlength_unit: mm\n"
                               "axis: {{origin: [0, 0, 0], direction: [1, 0, 0]}}\npatches:\n"
                               "  hub: {{role: sliding, deflection: {{file: hub.csv, faces: [{}], form: displacement}}}}\n"
                               "  casing: {{role: fixed}}\n  inlet: {{role: slip}}\n  outlet: {{role: slip}}\n",
                               fmt::join(faces, ", ")));
  const WallMotion m = deform(dir.path(), "hub.msh", "hub");
  ASSERT_EQ(m.result.exit_code, 0) << m.result.output;
  double worst = 0.0;
  for (const Vec2& q : m.after) worst = std::max(worst, std::abs(q.y - (hub_radius(q.x) + 0.02)));
  EXPECT_LT(worst, 1e-9);
  EXPECT_EQ(m.after.size(), m.before.size());
}

}  // namespace
}  // namespace hotmesh::app
