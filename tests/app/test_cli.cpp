// Tests of the hotmesh command line: help, exit codes, messages for bad input, and the
// promise that inputs are never overwritten. They run the built executable.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using test::run_command;
using test::shell_quote;

const std::string kRamp = std::string(HOTMESH_SOURCE_DIR) + "/samples/ramp2d/ramp2d.msh";

test::CommandResult hotmesh(const std::string& arguments) { return run_command(std::string(HOTMESH_EXE) + " " + arguments); }

TEST(Cli, EveryCommandHasHelp) {
  for (const std::string command : {"", "info ", "convert ", "deform "}) {
    const auto r = hotmesh(command + "--help");
    EXPECT_EQ(r.exit_code, 0) << command;
    EXPECT_THAT(r.output, HasSubstr("Usage:")) << command;
  }
  EXPECT_EQ(hotmesh("--version").exit_code, 0);
}

TEST(Cli, BadCommandLinesExitWithCodeTwo) {
  EXPECT_EQ(hotmesh("").exit_code, 2);
  EXPECT_EQ(hotmesh("frobnicate").exit_code, 2);
  EXPECT_EQ(hotmesh("info").exit_code, 2);
  const auto missing = hotmesh("info /nonexistent/mesh.msh");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.output, HasSubstr("/nonexistent/mesh.msh"));
}

TEST(Cli, InfoSummarisesTheRampSample) {
  const auto text = hotmesh("info " + shell_quote(kRamp));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_THAT(text.output, HasSubstr("2280 (2280 quad4)"));
  const auto json = hotmesh("-q info --json " + shell_quote(kRamp));
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto j = nlohmann::json::parse(json.output);
  EXPECT_EQ(j["dimension"], 2);
  EXPECT_EQ(j["cells"], 2280);
  EXPECT_EQ(j["nodes"], 58 * 41);
  EXPECT_EQ(j["patches"].size(), 4u);
  EXPECT_EQ(j["patches"][2]["name"], "bottom");
  EXPECT_EQ(j["quality"]["inverted_cells"], 0);
  EXPECT_DOUBLE_EQ(j["quality"]["min_scaled_jacobian"].get<double>(), 1.0);
}

// Global options are taken anywhere on the line, as users type them after the command: -q
// silences the run's log, -v adds its debug lines; an option nobody knows is still refused.
TEST(Cli, GlobalOptionsAreTakenAfterTheCommandToo) {
  const std::string shear = shell_quote(std::string(HOTMESH_SOURCE_DIR) + "/samples/shear2d/shear2d.yaml");
  test::TempDir dir;
  const auto run = [&](const std::string& folder, const std::string& option) {
    return hotmesh("deform " + shear + " -o " + shell_quote((dir / folder).string()) + " " + option);
  };
  const auto normal = run("normal", "");
  ASSERT_EQ(normal.exit_code, 0) << normal.output;
  EXPECT_THAT(normal.output, HasSubstr("info "));
  const auto quiet = run("quiet", "-q");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
  const auto verbose = run("verbose", "--verbose");
  ASSERT_EQ(verbose.exit_code, 0) << verbose.output;
  EXPECT_THAT(verbose.output, HasSubstr("debug "));
  EXPECT_THAT(normal.output, Not(HasSubstr("debug ")));
  const auto unknown = hotmesh("info " + shell_quote(kRamp) + " --frobnicate");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.output, HasSubstr("--frobnicate"));
}

TEST(Cli, MalformedMeshIsAUserErrorNamingFileAndLine) {
  test::TempDir dir;
  test::write_text(dir / "bad.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n2 1 0 2\n1\n2\n0 0 0\nnan 1 0\n$EndNodes\n");
  const auto r = hotmesh("info " + shell_quote((dir / "bad.msh").string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr((dir / "bad.msh").string() + ":10"));
}

TEST(Cli, ConvertWritesVtuAndNeverOverwritesItsInput) {
  test::TempDir dir;
  const auto input = dir / "ramp.msh";
  std::filesystem::copy_file(kRamp, input);
  const std::string before = test::read_text(input);
  const auto same = hotmesh("convert " + shell_quote(input.string()) + " " + shell_quote((dir / "." / "ramp.msh").string()));
  EXPECT_EQ(same.exit_code, 2);
  EXPECT_THAT(same.output, HasSubstr("never overwrites its inputs"));
  EXPECT_EQ(test::read_text(input), before);

  const auto vtu = hotmesh("convert " + shell_quote(input.string()) + " " + shell_quote((dir / "ramp.vtu").string()));
  ASSERT_EQ(vtu.exit_code, 0) << vtu.output;
  EXPECT_THAT(test::read_text(dir / "ramp.vtu"), HasSubstr("NumberOfCells=\"2280\""));
  const auto msh = hotmesh("convert --binary " + shell_quote(input.string()) + " " + shell_quote((dir / "copy.msh").string()));
  ASSERT_EQ(msh.exit_code, 0) << msh.output;
  EXPECT_EQ(hotmesh("info " + shell_quote((dir / "copy.msh").string())).exit_code, 0);
  const auto bad = hotmesh("convert " + shell_quote(input.string()) + " " + shell_quote((dir / "ramp.stl").string()));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.output, HasSubstr("unknown mesh format '.stl'"));
  // Only the files asked for, no temporaries left behind.
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) names.push_back(e.path().filename().string());
  EXPECT_THAT(names, ::testing::UnorderedElementsAre("ramp.msh", "ramp.vtu", "copy.msh"));
}

}  // namespace
}  // namespace hotmesh::app
