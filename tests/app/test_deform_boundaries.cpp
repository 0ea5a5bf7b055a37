// Tests of `hotmesh deform` on boundary roles that meet: a channel between sliding walls with
// slip ends runs without a fixed patch (with either linear solver); a passive inlet and outlet
// on a sliding floor keep their planes and meet the deflected floor; a sector between coaxial
// sliding cylinders with periodic sides, free to turn about its axis, is refused at the case's
// `patches:` with exit code 2.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include <fmt/format.h>

#include "deform_cases.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using test::hotmesh;
using test::read_json;
using test::shell_quote;

std::string run(const test::TempDir& dir, const std::string& yaml, test::CommandResult& result) {
  test::write_text(dir / "case.yaml", yaml);
  const auto out = dir / "out";
  result = hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " + shell_quote(out.string()));
  return out.string();
}

/// 1-based line of `key` at the start of a line of `text`.
std::size_t line_of(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  std::string line;
  for (std::size_t n = 1; std::getline(lines, line); ++n) {
    if (line.starts_with(key)) return n;
  }
  return 0;
}

class SlidingChannelWithSlipEnds : public ::testing::TestWithParam<const char*> {};

TEST_P(SlidingChannelWithSlipEnds, RunsWithoutAFixedPatch) {
  // The coarse ramp channel, its inlet and outlet slip instead of fixed: they hold the channel
  // along itself, the sliding walls across it.
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  const std::string yaml = fmt::format(
      "mesh: ramp.msh\nsolver: {{increments: 4, linear: {}}}\n"
      "patches:\n  left: {{role: slip}}\n  right: {{role: slip}}\n  top: {{role: sliding}}\n"
      "  bottom: {{role: sliding, deflection: {{file: full.csv}}}}\n",
      GetParam());
  test::CommandResult r;
  const std::filesystem::path out = run(dir, yaml, r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto report = read_json(out / "report.json");
  EXPECT_EQ(report["status"], "success");
  EXPECT_EQ(report["inverted_cells"], 0);
  for (const auto& increment : report["increments"]) {  // an attempt that stalls is split, as on the fixed-inlet ramp
    if (increment["accepted"].get<bool>()) {
      EXPECT_TRUE(increment["converged"].get<bool>());
    }
  }
  const mesh::Mesh moved = io::read_gmsh(out / "deformed.msh");
  for (mesh::NodeId n : moved.find_patch("bottom")->nodes) {
    const auto& p = moved.points[static_cast<std::size_t>(n)];
    const double ramp = p.x <= 0.975 ? 0.0 : p.x >= 1.025 ? 0.5 : 0.5 * (p.x - 0.975) / 0.05;
    EXPECT_NEAR(p.y, ramp, 1e-9) << "x = " << p.x;
  }
  for (mesh::NodeId n : moved.find_patch("left")->nodes) EXPECT_NEAR(moved.points[static_cast<std::size_t>(n)].x, 0.0, 1e-12);
  for (mesh::NodeId n : moved.find_patch("right")->nodes) EXPECT_NEAR(moved.points[static_cast<std::size_t>(n)].x, 2.0, 1e-12);
  EXPECT_EQ(mesh::summarize_quality(mesh::scaled_jacobians(moved.cells, moved.points)).inverted_cells, 0u);
}

INSTANTIATE_TEST_SUITE_P(LinearSolvers, SlidingChannelWithSlipEnds, ::testing::Values("jacobi-pcg", "amg"));

TEST(DeformBoundaries, PassiveInletAndOutletOnASlidingFloorKeepTheirPlanes) {
  // A channel whose floor, in the FEM table, moves 0.1 downstream and rises by 0.1 + 0.05 x
  // (the table reaches past both ends): the deflected floor is y = 0.095 + 0.05 x. Its corners
  // with the passive inlet and outlet end where it crosses x = 0 and x = 2.
  test::TempDir dir;
  io::write_gmsh(dir / "channel.msh", mesh::structured_quads(mesh::uniform_line(0.0, 2.0, 20), mesh::uniform_line(0.0, 1.0, 10),
                                                               {"inlet", "outlet", "floor", "ceiling"}));
  std::string table = "x,y,dx,dy\n";
  for (int j = 0; j <= 6; ++j) {
    const double x = -0.5 + 0.5 * j;
    table += fmt::format("{},0,0.1,{}\n", x, 0.1 + 0.05 * x);
  }
  test::write_text(dir / "floor.csv", table);
  const std::string yaml =
      "mesh: channel.msh\nsolver: {increments: 4}\npatches:\n  inlet: {role: passive}\n  outlet: {role: passive}\n"
      "  floor: {role: sliding, deflection: {file: floor.csv}}\n  ceiling: {role: sliding}\n";
  test::CommandResult r;
  const std::filesystem::path out = run(dir, yaml, r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const mesh::Mesh moved = io::read_gmsh(out / "deformed.msh");
  const auto& floor = moved.find_patch("floor")->nodes;
  for (const auto& [name, x] : {std::pair{"inlet", 0.0}, std::pair{"outlet", 2.0}}) {
    std::size_t corners = 0;
    for (mesh::NodeId n : moved.find_patch(name)->nodes) {
      const auto& p = moved.points[static_cast<std::size_t>(n)];
      EXPECT_NEAR(p.x, x, 1e-12) << name;  // on the inlet's (outlet's) plane
      if (!std::binary_search(floor.begin(), floor.end(), n)) continue;
      ++corners;
      EXPECT_NEAR(p.y, 0.095 + 0.05 * x, 1e-9) << name;  // and on the deflected floor
    }
    EXPECT_EQ(corners, 1u) << name;
  }
  for (mesh::NodeId n : floor) {
    const auto& p = moved.points[static_cast<std::size_t>(n)];
    EXPECT_NEAR(p.y, 0.095 + 0.05 * p.x, 1e-9);
  }
  EXPECT_EQ(mesh::summarize_quality(mesh::scaled_jacobians(moved.cells, moved.points)).inverted_cells, 0u);
}

TEST(DeformBoundaries, SectorFreeToTurnAboutItsAxisIsRefusedAtPatches) {
  // Coaxial sliding cylinders, slip floor and ceiling, periodic sides: nothing stops the sector
  // turning about the axis.
  test::TempDir dir;
  io::write_gmsh(dir / "sector.msh", test::annular_sector(3, 2, 2, 1.0, 2.0, 0.0, 1.0, 10.0));
  const std::string yaml =
      "mesh: sector.msh\naxis: {origin: [0, 0, 0], direction: [0, 0, 1]}\npatches:\n"
      "  inner: {role: sliding}\n  outer: {role: sliding}\n  bottom: {role: slip}\n  top: {role: slip}\n"
      "  per_lo: {role: periodic, partner: per_hi, angle_deg: 10}\n  per_hi: {role: periodic}\n";
  test::CommandResult r;
  const std::filesystem::path out = run(dir, yaml, r);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(fmt::format("{}:{}: patches: the patch roles leave the mesh free to move as a rigid "
                                              "body: it can rotate about the axis through (0, 0, 0.5) along (0, 0, 1).",
                                              (dir / "case.yaml").string(), line_of(yaml, "patches:"))));
  EXPECT_FALSE(std::filesystem::exists(out / "deformed.msh"));
  EXPECT_FALSE(std::filesystem::exists(out / "report.json"));
}

}  // namespace
}  // namespace hotmesh::app
