// Tests of `hotmesh deform`'s ParaView time series (`output: {series: true}` or --series):
// deformed.pvd and walls.pvd list a step per increment, the start and the corner pass, each
// read by VTK's own readers; the meshes are the motion's (the start the input, the last one
// deformed.vtu) and the walls the deflected curve at each stage; a resumed run keeps the steps
// of the interrupted one and ends with the same series as a straight run.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "deform_cases.hpp"
#include "faults.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "test_support.hpp"
#include "vtk_reader.hpp"

namespace hotmesh::app {
namespace {

using test::hotmesh;
using test::read_with_vtk;
using test::shell_quote;

constexpr int kIncrements = 6;  // none is halved

/// The coarse sliding ramp (corners at (0.975, 0) and (1.025, 0.5) once deflected).
struct SeriesRamp {
  test::TempDir dir;
  explicit SeriesRamp(const std::string& extra = "") {
    test::write_coarse_ramp(dir.path());
    test::write_text(dir / "case.yaml", test::ramp_case("full.csv", kIncrements, extra));
  }
  std::string deform(const std::string& out, const std::string& options = "") const {
    return fmt::format("-q deform {} -o {} {}", shell_quote((dir / "case.yaml").string()),
                       shell_quote((dir / out).string()), options);
  }
};

std::vector<double> times_of(const nlohmann::json& series) {
  std::vector<double> times;
  for (const auto& step : series["steps"]) times.push_back(step["time"]);
  return times;
}

/// Whether the polylines of `walls` pass through (x, y).
bool passes_through(const nlohmann::json& walls, double x, double y) {
  const auto p = walls["points"].get<std::vector<double>>();
  for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
    if (std::abs(p[i] - x) < 1e-12 && std::abs(p[i + 1] - y) < 1e-12) return true;
  }
  return false;
}

TEST(DeformSeries, StepsAreTheStartEveryIncrementAndTheCornerPass) {
  SeriesRamp ramp("output: {series: true}\n");
  const auto run = hotmesh(ramp.deform("out"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json meshes = read_with_vtk(ramp.dir / "out" / "deformed.pvd");
  const nlohmann::json walls = read_with_vtk(ramp.dir / "out" / "walls.pvd");
  ASSERT_FALSE(meshes.contains("error") || walls.contains("error")) << meshes.dump().substr(0, 300);
  const std::vector<double> times{0, 1, 2, 3, 4, 5, 6, 7};  // start, 6 increments, corner pass
  EXPECT_EQ(times_of(meshes), times);
  EXPECT_EQ(times_of(walls), times);
  for (const auto& step : meshes["steps"]) ASSERT_FALSE(step.contains("error")) << step["file"];

  // The first mesh is the input, the last the deformed mesh; each carries its displacement.
  const mesh::Mesh input = io::read_gmsh(ramp.dir / "ramp.msh");
  const auto start = meshes["steps"].front()["points"].get<std::vector<double>>();
  ASSERT_EQ(start.size(), 3 * input.node_count());
  for (std::size_t i = 0; i < input.node_count(); ++i) {
    EXPECT_EQ(start[3 * i], input.points[i].x);
    EXPECT_EQ(start[3 * i + 1], input.points[i].y);
  }
  EXPECT_TRUE(meshes["steps"].back()["points"] == read_with_vtk(ramp.dir / "out" / "deformed.vtu")["points"]);
  const auto middle = meshes["steps"][3]["points"].get<std::vector<double>>();
  const auto displacement = meshes["steps"][3]["point_data"]["displacement"]["values"].get<std::vector<double>>();
  ASSERT_EQ(displacement.size(), start.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) {
    EXPECT_NEAR(displacement[i], middle[i] - start[i], 1e-15);
    largest = std::max(largest, std::abs(displacement[i]));
  }
  EXPECT_GT(largest, 0.1) << "the mesh moved by increment 3";
  EXPECT_THAT(meshes["steps"][3]["cell_data"]["scaled_jacobian"]["values"], ::testing::Not(::testing::IsEmpty()));

  // The walls: flat at the start; half the ramp after 3 of 6 increments; the ramp at the end.
  EXPECT_TRUE(passes_through(walls["steps"][0], 1.025, 0.0));
  EXPECT_TRUE(passes_through(walls["steps"][3], 1.025, 0.25));
  EXPECT_TRUE(passes_through(walls["steps"][6], 0.975, 0.0));
  EXPECT_TRUE(passes_through(walls["steps"][6], 1.025, 0.5));
  EXPECT_TRUE(walls["steps"][7]["points"] == walls["steps"][6]["points"]) << "the corner pass moves no wall";
}

TEST(DeformSeries, ResumedRunKeepsTheInterruptedStepsAndEndsAsAStraightRun) {
  SeriesRamp ramp;
  ASSERT_EQ(hotmesh(ramp.deform("straight", "--series")).exit_code, 0);
  const auto killed = hotmesh(ramp.deform("out", "--series"), test::Faults{.kill_after_checkpoint = 2});
  ASSERT_NE(killed.exit_code, 0);
  const nlohmann::json before = read_with_vtk(ramp.dir / "out" / "deformed.pvd");
  EXPECT_EQ(times_of(before), (std::vector<double>{0, 1, 2}));
  const std::string step_1 = test::read_text(ramp.dir / "out" / "series" / "mesh_0001.vtu");

  const auto resumed = hotmesh(ramp.deform("out", "--series --resume"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(test::read_text(ramp.dir / "out" / "series" / "mesh_0001.vtu"), step_1) << "written again";
  const nlohmann::json straight = read_with_vtk(ramp.dir / "straight" / "deformed.pvd");
  const nlohmann::json after = read_with_vtk(ramp.dir / "out" / "deformed.pvd");
  EXPECT_EQ(times_of(after), times_of(straight));
  ASSERT_EQ(after["steps"].size(), straight["steps"].size());
  for (std::size_t i = 0; i < after["steps"].size(); ++i) {
    EXPECT_EQ(after["steps"][i]["points"], straight["steps"][i]["points"]) << "step " << i;
  }
}

}  // namespace
}  // namespace hotmesh::app
