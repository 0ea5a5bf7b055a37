// Tests of writing CGNS: the write-back of a moved mesh (deformed.cgns: the input with only its
// coordinates replaced, checked against the input node by node and array by array, and by
// cgnscheck) and new files from a mesh (hotmesh convert), read back.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cgns_files.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/cgns.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using geometry::Vec3;

/// A smooth motion; in 2D it keeps z (the plane).
Vec3 moved(const Vec3& p, int dimension) {
  return {p.x + 0.05 * std::sin(3.0 * p.y) + 0.01 * p.x * p.y, p.y + 0.03 * p.x * p.x,
          dimension == 3 ? p.z + 0.02 * p.x - 0.01 * p.y : p.z};
}

void expect_cgnscheck_accepts(const std::filesystem::path& file) {
  const auto result = test::run_command(std::string(HOTMESH_CGNSCHECK) + " " + test::shell_quote(file.string()));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_THAT(result.output, ::testing::Not(::testing::HasSubstr("ERROR"))) << result.output;
}

/// cgnsdiff (cgns-convert) compares every node of the two files, with its data: the lines it
/// prints for nodes that differ, each a path from the root.
std::vector<std::string> nodes_that_differ(const std::filesystem::path& a, const std::filesystem::path& b) {
  const auto result = test::run_command(std::string(HOTMESH_CGNSDIFF) + " -d " + test::shell_quote(a.string()) + " " +
                                        test::shell_quote(b.string()));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  std::vector<std::string> lines;
  std::istringstream text(result.output);
  for (std::string line; std::getline(text, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

/// Nothing of `output` differs from `input` but the data of the coordinate arrays.
void expect_only_coordinates_differ(const std::filesystem::path& input, const std::filesystem::path& output) {
  const std::vector<std::string> differ = nodes_that_differ(input, output);
  for (const std::string& line : differ) {
    EXPECT_THAT(line, ::testing::MatchesRegex("/[^/ ]+/[^/ ]+/GridCoordinates/Coordinate[XYZ] <> "
                                                  "/[^/ ]+/[^/ ]+/GridCoordinates/Coordinate[XYZ] : data values differ"))
        << "cgnsdiff " << input << " " << output;
  }
}

/// Everything of the summary but the coordinates is the same in both files.
void expect_same_structure(const CgnsSummary& a, const CgnsSummary& b) {
  ASSERT_EQ(a.bases.size(), b.bases.size());
  for (std::size_t i = 0; i < a.bases.size(); ++i) {
    EXPECT_EQ(a.bases[i].families, b.bases[i].families);
    EXPECT_EQ(a.bases[i].physical_dimension, b.bases[i].physical_dimension);
    ASSERT_EQ(a.bases[i].zones.size(), b.bases[i].zones.size());
    for (std::size_t z = 0; z < a.bases[i].zones.size(); ++z) {
      const auto &za = a.bases[i].zones[z], &zb = b.bases[i].zones[z];
      EXPECT_EQ(za.name, zb.name);
      EXPECT_EQ(za.size, zb.size);
      EXPECT_EQ(za.solutions, zb.solutions);
      EXPECT_EQ(za.sections.size(), zb.sections.size());
      EXPECT_EQ(za.connections.size(), zb.connections.size());
      ASSERT_EQ(za.bcs.size(), zb.bcs.size());
      for (std::size_t c = 0; c < za.bcs.size(); ++c) {
        EXPECT_EQ(za.bcs[c].name, zb.bcs[c].name);
        EXPECT_EQ(za.bcs[c].family, zb.bcs[c].family);
        EXPECT_EQ(za.bcs[c].points, zb.bcs[c].points);
      }
    }
  }
}

/// Moves the mesh of `input`, writes it back, and checks deformed.cgns.
void check_write_back(const std::filesystem::path& input, bool has_pressure) {
  const LoadedMesh loaded = read_mesh(input);
  const int dim = loaded.mesh.dimension;
  std::vector<Vec3> points;
  for (const Vec3& p : loaded.mesh.points) points.push_back(moved(p, dim));
  const auto folder = input.parent_path() / "out";
  std::filesystem::create_directories(folder);
  const auto written = loaded.write_back->write(folder, points, {});
  ASSERT_EQ(written, std::vector<std::filesystem::path>{folder / "deformed.cgns"});
  const auto output = written[0];

  const auto before = test::read_zone_coordinates(input);
  const auto after = test::read_zone_coordinates(output);
  ASSERT_EQ(before.size(), after.size());
  for (std::size_t z = 0; z < before.size(); ++z) {
    EXPECT_EQ(before[z].types, after[z].types);
    const bool single = before[z].types[0] == "RealSingle";
    for (std::size_t n = 0; n < before[z].xyz.size() / 3; ++n) {
      const Vec3 p = moved({before[z].xyz[3 * n], before[z].xyz[3 * n + 1], before[z].xyz[3 * n + 2]}, dim);
      const std::array<double, 3> want{p.x, p.y, before[z].types.size() == 3 ? p.z : 0.0};
      for (std::size_t a = 0; a < 3; ++a) {
        const double expected = single ? static_cast<double>(static_cast<float>(want[a])) : want[a];
        ASSERT_EQ(after[z].xyz[3 * n + a], expected) << "zone " << z + 1 << " node " << n + 1 << " axis " << a;
      }
    }
    if (has_pressure) {
      EXPECT_EQ(test::read_field(input, static_cast<int>(z) + 1, 1, "Pressure"),
                test::read_field(output, static_cast<int>(z) + 1, 1, "Pressure"));
    }
  }
  expect_same_structure(describe_cgns(input), describe_cgns(output));
  expect_only_coordinates_differ(input, output);
  expect_cgnscheck_accepts(output);
  const LoadedMesh again = read_mesh(output);
  EXPECT_EQ(again.mesh.cells, loaded.mesh.cells);
  EXPECT_EQ(again.mesh.patches, loaded.mesh.patches);
  ASSERT_EQ(again.mesh.node_count(), points.size());
  for (std::size_t n = 0; n < points.size(); ++n) EXPECT_NEAR(norm(again.mesh.points[n] - points[n]), 0.0, 1e-6);
}

TEST(CgnsWriteBack, Structured2dSinglePrecisionTwoZonesKeepsSolutionsAndConnectivity) {
  test::TempDir dir;
  test::write_structured_2d(dir / "s2.cgns");
  check_write_back(dir / "s2.cgns", true);
}

TEST(CgnsWriteBack, Unstructured2dWithPhysicalDimensionTwo) {
  test::TempDir dir;
  test::write_unstructured_2d(dir / "u2.cgns");
  check_write_back(dir / "u2.cgns", true);
}

TEST(CgnsWriteBack, Structured3dCoincidentZonesMoveAsOne) {
  test::TempDir dir;
  test::write_structured_3d(dir / "s3.cgns");
  check_write_back(dir / "s3.cgns", false);
}

TEST(CgnsWriteBack, Unstructured3dMixed) {
  test::TempDir dir;
  test::write_unstructured_3d(dir / "u3.cgns");
  check_write_back(dir / "u3.cgns", false);
}

// A file as CGNS before 3.4 writes it (SU2's mesh_bend_coarse.cgns): its MIXED sections have
// no ElementStartOffset. The library opened in modify mode would add one to every section and
// rewrite CGNSLibraryVersion as its own 3.4 on closing; the write-back changes only coordinates.
TEST(CgnsWriteBack, LegacyFileKeepsItsSectionsAndVersion) {
  test::TempDir dir;
  test::write_unstructured_3d(dir / "u3.cgns");
  test::make_legacy(dir / "u3.cgns");
  test::write_unstructured_2d(dir / "u2.cgns");
  test::make_legacy(dir / "u2.cgns");
  for (const char* name : {"u3.cgns", "u2.cgns"}) {
    const auto input = dir / name;
    ASSERT_THAT(nodes_that_differ(input, input), ::testing::IsEmpty());
    const auto converted = test::run_command(std::string(HOTMESH_HDF2ADF) + " " + test::shell_quote(input.string()) +
                                             " " + test::shell_quote(input.string() + ".adf"));
    ASSERT_EQ(converted.exit_code, 0) << converted.output;
    for (const std::filesystem::path& file : {input, std::filesystem::path(input.string() + ".adf")}) {
      check_write_back(file, std::string(name) == "u2.cgns");
      const auto output = file.parent_path() / "out" / "deformed.cgns";
      // the check above ran cgnsdiff; here that it saw the coordinates change, and nothing else
      const std::vector<std::string> differ = nodes_that_differ(file, output);
      EXPECT_EQ(differ.size(), std::string(name) == "u3.cgns" ? 3u : 2u) << ::testing::PrintToString(differ);
      const auto listed = test::run_command("cgnslist " + test::shell_quote(output.string()));
      EXPECT_THAT(listed.output, ::testing::HasSubstr("GridCoordinates"));
      EXPECT_THAT(listed.output, ::testing::Not(::testing::HasSubstr("ElementStartOffset")));
    }
  }
}

// Coordinates stored in another file through a link: writing them would change that file.
TEST(CgnsWriteBack, CoordinatesLinkedFromAnotherFileAreNotWrittenThere) {
  test::TempDir dir;
  test::write_unstructured_3d(dir / "grid.cgns");
  test::write_unstructured_3d(dir / "u3.cgns");
  test::link_node(dir / "u3.cgns", "/Base/Block/GridCoordinates/CoordinateY", dir / "grid.cgns");
  const std::string grid = test::read_text(dir / "grid.cgns");
  const LoadedMesh loaded = read_mesh(dir / "u3.cgns");
  std::vector<Vec3> points;
  for (const Vec3& p : loaded.mesh.points) points.push_back(moved(p, 3));
  try {
    loaded.write_back->write(dir.path(), points, {});
    ADD_FAILURE() << "wrote through the link";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith((dir / "u3.cgns").string() +
                                                ": /Base/Block/GridCoordinates/CoordinateY is a link into another file"));
  }
  EXPECT_EQ(test::read_text(dir / "grid.cgns"), grid);
  EXPECT_FALSE(std::filesystem::exists(dir / "deformed.cgns"));
}

TEST(CgnsWriteBack, UnstructuredZonesJoinedByConnectivity) {
  test::TempDir dir;
  test::write_unstructured_two_zones(dir / "u2z.cgns", true);
  check_write_back(dir / "u2z.cgns", false);
}

TEST(CgnsWriteBack, AdfFileStaysAdf) {
  test::TempDir dir;
  test::write_structured_2d(dir / "s2.cgns");
  const auto converted = test::run_command(std::string(HOTMESH_HDF2ADF) + " " + test::shell_quote((dir / "s2.cgns").string()) +
                                           " " + test::shell_quote((dir / "s2.adf").string()));
  ASSERT_EQ(converted.exit_code, 0) << converted.output;
  EXPECT_EQ(describe_cgns(dir / "s2.adf").file_type, "ADF");
  check_write_back(dir / "s2.adf", true);
  EXPECT_EQ(describe_cgns(dir / "out" / "deformed.cgns").file_type, "ADF");
}

TEST(CgnsWriteBack, LeavesNoTemporaryFileAndTheInputUntouched) {
  test::TempDir dir;
  test::write_structured_2d(dir / "s2.cgns");
  const std::string original = test::read_text(dir / "s2.cgns");
  const LoadedMesh loaded = read_mesh(dir / "s2.cgns");
  loaded.write_back->write(dir.path(), loaded.mesh.points, {});
  EXPECT_EQ(test::read_text(dir / "s2.cgns"), original);
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"deformed.cgns", "s2.cgns"}));
}

void check_round_trip(const mesh::Mesh& original, const std::filesystem::path& file) {
  write_mesh(file, original, original.points);
  expect_cgnscheck_accepts(file);
  const LoadedMesh back = read_mesh(file);
  EXPECT_EQ(back.mesh.dimension, original.dimension);
  EXPECT_EQ(back.mesh.points, original.points);
  EXPECT_EQ(back.mesh.cells, original.cells);
  ASSERT_EQ(back.mesh.patches.size(), original.patches.size());
  for (std::size_t p = 0; p < original.patches.size(); ++p) {
    EXPECT_EQ(back.mesh.patches[p].name, original.patches[p].name);
    EXPECT_EQ(back.mesh.patches[p].faces, original.patches[p].faces);
  }
}

TEST(CgnsConvert, QuadMeshRoundTripsThroughANewFile) {
  test::TempDir dir;
  check_round_trip(test::unit_square(4, 3), dir / "square.cgns");
  const CgnsSummary s = describe_cgns(dir / "square.cgns");
  ASSERT_EQ(s.bases.size(), 1u);
  EXPECT_EQ(s.bases[0].physical_dimension, 2);
  ASSERT_EQ(s.bases[0].zones.size(), 1u);
  EXPECT_EQ(s.bases[0].zones[0].sections.size(), 5u);  // cells + one per patch
  EXPECT_EQ(s.bases[0].zones[0].bcs.size(), 4u);
}

TEST(CgnsConvert, HexMeshRoundTripsThroughANewFile) {
  test::TempDir dir;
  check_round_trip(test::unit_cube(2), dir / "cube.cgns");
}

}  // namespace
}  // namespace hotmesh::io
