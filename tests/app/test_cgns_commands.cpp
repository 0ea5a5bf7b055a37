// Tests of CGNS through the command line: convert the ramp sample to CGNS and back, info on
// it, deform from the CGNS file (the same points as from the .msh, and deformed.cgns passes
// cgnscheck), and exit code 2 for files that are not CGNS meshes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include "cgns_files.hpp"
#include "faults.hpp"
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
  const auto json = hotmesh("info --json " + shell_quote((dir / "ramp.cgns").string()));
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const auto summary = nlohmann::json::parse(json.output);
  EXPECT_EQ(summary["cgns"]["bases"][0]["zones"][0]["bcs"].size(), 4u);
  EXPECT_EQ(summary["cgns"]["bases"][0]["zones"][0]["sections"][0]["type"], "QUAD_4");
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

TEST(CgnsCommands, StructuredZonesMoveAsOneAndTheirInterfaceStaysShared) {
  test::TempDir dir;
  test::write_structured_2d(dir / "s2.cgns");
  std::string table = "x,y,dx,dy\n";
  for (int i = 0; i <= 20; ++i) {
    const double x = 0.1 * i;
    table += fmt::format("{},0,0,{}\n", x, 0.05 * std::sin(M_PI * x / 2.0));
  }
  test::write_text(dir / "bump.csv", table);
  test::write_text(dir / "case.yaml", "mesh: s2.cgns\nsolver:\n  increments: 2\npatches:\n  inlet: {role: fixed}\n"
                                      "  outlet: {role: fixed}\n  top: {role: fixed}\n"
                                      "  Walls: {role: prescribed, deflection: {file: bump.csv, degree: 1}}\n");
  const auto run = hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " + shell_quote((dir / "out").string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto zones = test::read_zone_coordinates(dir / "out" / "deformed.cgns");
  ASSERT_EQ(zones.size(), 2u);
  // A's nodes (4, j) are B's nodes (j, 1): the same values, moved.
  for (std::size_t j = 0; j < 3; ++j) {
    const std::size_t a = 3 + 4 * j, b = j;
    EXPECT_EQ(zones[0].xyz[3 * a], zones[1].xyz[3 * b]) << j;
    EXPECT_EQ(zones[0].xyz[3 * a + 1], zones[1].xyz[3 * b + 1]) << j;
  }
  EXPECT_GT(zones[0].xyz[3 * 3 + 1], 0.04);  // the wall node at x = 1 rose with the bump
  const auto check = cgnscheck(dir / "out" / "deformed.cgns");
  EXPECT_EQ(check.exit_code, 0) << check.output;
}

TEST(CgnsCommands, UnsupportedCellsAndBcsWithoutFacesExitWithCodeTwo) {
  test::TempDir dir;
  test::write_with_quadratic_triangles(dir / "tri.cgns");
  const auto tri = hotmesh("info " + shell_quote((dir / "tri.cgns").string()));
  EXPECT_EQ(tri.exit_code, 2);
  EXPECT_THAT(tri.output, HasSubstr((dir / "tri.cgns").string() + ": zone 'Fluid' section 'Tris' holds 2 TRI_6"));
  test::write_bc_without_faces(dir / "lonely.cgns");
  const auto lonely = hotmesh("info " + shell_quote((dir / "lonely.cgns").string()));
  EXPECT_EQ(lonely.exit_code, 2);
  EXPECT_THAT(lonely.output, HasSubstr("zone 'Fluid' BC 'lonely' names 1 nodes"));
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

// Issue 46: libhdf5 aborted inside cg_open on a CGNS file with one byte of a link name
// changed, and hotmesh died with it (SIGABRT). hotmesh reads a CGNS file in a child process
// first: a fault of the library there is an error naming the file, exit 2, for every command
// that reads it. The fault is the test library's (HOTMESH_TEST_ABORT_IN_HDF5_OPEN), the file
// a valid one: the damaged files this libhdf5 (1.10) aborts on are its own bugs, which a later
// version may not have (test_cgns_damage.cpp has the damaged files hotmesh itself refuses).
TEST(CgnsCommands, AFaultOfTheCgnsLibraryExitsWithCodeTwoNamingTheFile) {
  test::TempDir dir;
  const auto file = dir / "u2.cgns";
  test::write_unstructured_2d(file);
  test::Faults faults;
  faults.abort_in_hdf5_open = true;
  const std::string aborting = test::fault_variables(faults);
  for (const std::string& command : {"info " + shell_quote(file.string()),
                                     "convert " + shell_quote(file.string()) + " " + shell_quote((dir / "u2.msh").string())}) {
    const auto result = run_command(aborting + HOTMESH_EXE + " " + command);
    EXPECT_EQ(result.exit_code, 2) << command << "\n" << result.output;
    EXPECT_THAT(result.output, HasSubstr(file.string() + ": the CGNS library (or HDF5 beneath it) crashed reading it "
                                                         "(signal 6, Aborted)"))
        << command;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "u2.msh"));
  EXPECT_EQ(hotmesh("info " + shell_quote(file.string())).exit_code, 0);  // the same file, without the fault
}

// Found by fuzz_cgns: an ADF file (the tests' structured 2D file of two zones, converted by
// hdf2adf) with bytes of its grid coordinates' node changed, on which the CGNS
// library's ADF reader copies from a wild address inside cg_open (AddressSanitizer: SEGV in
// ADFI_read_data_chunk; without it the library refuses the file, having read who knows what).
// In the child the fault is an error naming the file; either way, exit 2.
TEST(CgnsCommands, AnAdfFileOnWhichTheCgnsLibraryReadsAWildAddressExitsWithCodeTwo) {
  const auto file = test::data_path("fuzz/cgns-adf-wild-read.cgns");
  const auto result = hotmesh("info " + shell_quote(file.string()));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_THAT(result.output, HasSubstr("error " + file.string() + ": "));
}

}  // namespace
}  // namespace hotmesh::app
