// Tests of CGNS through the command line: convert the ramp sample to CGNS and back, info on
// it, deform from the CGNS file (the same points as from the .msh, and deformed.cgns passes
// cgnscheck), and exit code 2 for files that are not CGNS meshes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hotmesh/io/mesh_files.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using test::run_command;
using test::shell_quote;

const std::filesystem::path kRampFolder = std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples/ramp2d";

test::CommandResult hotmesh(const std::string& arguments) { return run_command(std::string(HOTMESH_EXE) + " " + arguments); }

test::CommandResult cgnscheck(const std::filesystem::path& file) {
  return run_command(std::string(HOTMESH_CGNSCHECK) + " " + shell_quote(file.string()));
}

/// The ramp sample's prescribed case, with `mesh` as its mesh, in `folder`.
void write_ramp_case(const std::filesystem::path& folder, const std::string& mesh) {
  std::filesystem::copy_file(kRampFolder / "ramp.csv", folder / "ramp.csv", std::filesystem::copy_options::skip_existing);
  test::write_text(folder / (mesh + ".yaml"), "mesh: " + mesh +
                                                  "\nsolver:\n  increments: 4\npatches:\n  left: {role: fixed}\n"
                                                  "  right: {role: slip}\n  top: {role: fixed}\n"
                                                  "  bottom: {role: prescribed, deflection: {file: ramp.csv, degree: 1}}\n");
}

TEST(CgnsCommands, ConvertInfoAndBackToGmsh) {
  test::TempDir dir;
  const auto to_cgns = hotmesh("convert " + shell_quote((kRampFolder / "ramp2d.msh").string()) + " " +
                               shell_quote((dir / "ramp.cgns").string()));
  ASSERT_EQ(to_cgns.exit_code, 0) << to_cgns.output;
  const auto check = cgnscheck(dir / "ramp.cgns");
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, ::testing::Not(HasSubstr("ERROR")));
  const auto info = hotmesh("info " + shell_quote((dir / "ramp.cgns").string()));
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_THAT(info.output, HasSubstr("zone Zone (Unstructured, size 2378 2280 0)"));
  EXPECT_THAT(info.output, HasSubstr("section bottom"));
  const auto back = hotmesh("convert " + shell_quote((dir / "ramp.cgns").string()) + " " +
                            shell_quote((dir / "back.msh").string()));
  ASSERT_EQ(back.exit_code, 0) << back.output;
  const auto original = io::read_mesh(kRampFolder / "ramp2d.msh").mesh;
  const auto round_trip = io::read_mesh(dir / "back.msh").mesh;
  EXPECT_EQ(round_trip.points, original.points);
  EXPECT_EQ(round_trip.cells, original.cells);
  ASSERT_EQ(round_trip.patches.size(), original.patches.size());
  for (std::size_t p = 0; p < original.patches.size(); ++p) {
    EXPECT_EQ(round_trip.patches[p].name, original.patches[p].name);
    EXPECT_EQ(round_trip.patches[p].faces, original.patches[p].faces);
  }
}

TEST(CgnsCommands, DeformFromCgnsMovesLikeGmshAndWritesDeformedCgns) {
  test::TempDir dir;
  ASSERT_EQ(hotmesh("convert " + shell_quote((kRampFolder / "ramp2d.msh").string()) + " " +
                    shell_quote((dir / "ramp.cgns").string()))
                .exit_code,
            0);
  std::filesystem::copy_file(kRampFolder / "ramp2d.msh", dir / "ramp.msh");
  write_ramp_case(dir.path(), "ramp.msh");
  write_ramp_case(dir.path(), "ramp.cgns");
  const auto gmsh_run = hotmesh("deform " + shell_quote((dir / "ramp.msh.yaml").string()) + " -o " +
                                shell_quote((dir / "out_msh").string()));
  ASSERT_EQ(gmsh_run.exit_code, 0) << gmsh_run.output;
  const auto cgns_run = hotmesh("deform " + shell_quote((dir / "ramp.cgns.yaml").string()) + " -o " +
                                shell_quote((dir / "out_cgns").string()));
  ASSERT_EQ(cgns_run.exit_code, 0) << cgns_run.output;
  const auto by_gmsh = io::read_mesh(dir / "out_msh" / "deformed.msh").mesh;
  const auto by_cgns = io::read_mesh(dir / "out_cgns" / "deformed.msh").mesh;
  const auto written_back = io::read_mesh(dir / "out_cgns" / "deformed.cgns").mesh;
  ASSERT_EQ(by_cgns.node_count(), by_gmsh.node_count());
  ASSERT_EQ(written_back.node_count(), by_gmsh.node_count());
  for (std::size_t n = 0; n < by_gmsh.node_count(); ++n) {
    EXPECT_LE(norm(by_cgns.points[n] - by_gmsh.points[n]), 1e-12) << "node " << n + 1;
    EXPECT_LE(norm(written_back.points[n] - by_gmsh.points[n]), 1e-12) << "node " << n + 1;
  }
  const auto check = cgnscheck(dir / "out_cgns" / "deformed.cgns");
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, ::testing::Not(HasSubstr("ERROR")));
}

TEST(CgnsCommands, FilesThatAreNotCgnsMeshesExitWithCodeTwo) {
  test::TempDir dir;
  test::write_text(dir / "text.cgns", "not a CGNS file\n");
  const auto text = hotmesh("info " + shell_quote((dir / "text.cgns").string()));
  EXPECT_EQ(text.exit_code, 2);
  EXPECT_THAT(text.output, HasSubstr((dir / "text.cgns").string() + ": not a CGNS file"));
  write_ramp_case(dir.path(), "missing.cgns");
  const auto missing = hotmesh("deform " + shell_quote((dir / "missing.cgns.yaml").string()) + " -o " +
                               shell_quote((dir / "out").string()));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.output, HasSubstr("missing.cgns"));
}

}  // namespace
}  // namespace hotmesh::app
