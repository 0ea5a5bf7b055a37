// Tests of hotmesh::io::parse_gmsh on broken and unusual input: every kind of damage gives an
// InputError naming the file, the line (ASCII) or byte offset (binary) and the problem; cut and
// corrupted files never crash; harmless variations (CRLF, extra sections, sparse tags, elements
// repeated per physical group in 2.2) read as they should.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <string_view>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using mesh::ElementType;
using mesh::Mesh;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Two quads side by side: nodes 1-2-3 at y = 0, 4-5-6 at y = 1; the inlet edge x = 0, a wall
// edge at the bottom, both cells in group "fluid".
constexpr std::string_view kTiny22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
3
1 1 "inlet"
1 2 "wall"
2 10 "fluid"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
$EndNodes
$Elements
4
1 1 2 1 1 4 1
2 1 2 2 2 1 2
3 3 2 10 1 1 2 5 4
4 3 2 10 1 2 3 6 5
$EndElements
)";

// The same mesh in format 4.1, with the wall edge left out.
constexpr std::string_view kTiny41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "inlet"
2 10 "fluid"
$EndPhysicalNames
$Entities
0 1 1 0
1 0 0 0 0 1 0 1 1 0
1 0 0 0 2 1 0 1 10 0
$EndEntities
$Nodes
1 6 1 6
2 1 0 6
1
2
3
4
5
6
0 0 0
1 0 0
2 0 0
0 1 0
1 1 0
2 1 0
$EndNodes
$Elements
2 3 1 3
1 1 1 1
1 4 1
2 1 3 2
2 1 2 5 4
3 2 3 6 5
$EndElements
)";

/// `text` with the first `from` replaced by `to` (which must be there).
std::string replaced(std::string_view text, std::string_view from, std::string_view to) {
  std::string result(text);
  const auto at = result.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture lacks '" << from << "'";
  if (at != std::string::npos) result.replace(at, from.size(), to);
  return result;
}

/// "<source>:<line>:" for the line of `text` holding `needle`.
std::string line_of(std::string_view text, std::string_view needle, std::string_view source = "tiny.msh") {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
  return std::string(source) + ":" + std::to_string(line) + ":";
}

std::string error_of(std::string_view content, std::string_view source = "tiny.msh") {
  try {
    parse_gmsh(content, source);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(GmshReaderInput, TinyFilesAreValid) {
  const Mesh v2 = parse_gmsh(kTiny22, "tiny.msh");
  EXPECT_EQ(v2.dimension, 2);
  EXPECT_EQ(v2.node_count(), 6u);
  EXPECT_EQ(v2.cells.type(1), ElementType::quad4);
  EXPECT_THAT(std::vector<mesh::NodeId>(v2.cells.nodes(1).begin(), v2.cells.nodes(1).end()),
              ::testing::ElementsAre(1, 2, 5, 4));
  EXPECT_EQ(v2.cell_ids, (std::vector<std::int64_t>{3, 4}));
  ASSERT_EQ(v2.patches.size(), 2u);
  EXPECT_EQ(v2.patches[1].name, "wall");
  EXPECT_EQ(v2.patches[1].nodes, (std::vector<mesh::NodeId>{0, 1}));
  ASSERT_EQ(v2.cell_groups.size(), 1u);
  EXPECT_EQ(v2.cell_groups[0].cells, (std::vector<mesh::CellId>{0, 1}));

  Mesh v4 = parse_gmsh(kTiny41, "tiny41.msh");
  EXPECT_EQ(v4.cell_ids, (std::vector<std::int64_t>{2, 3}));
  v4.cell_ids = v2.cell_ids;
  Mesh v2_without_wall = v2;
  v2_without_wall.patches.pop_back();
  EXPECT_EQ(v4, v2_without_wall);
}

// ---- cut, corrupt and malformed files ---------------------------------------------------

TEST(GmshReaderInput, CutFileNamesTheLineWhereItEnds) {
  const std::string cut(kTiny22.substr(0, kTiny22.find("4 3 2 10")));
  EXPECT_THAT(error_of(cut),
              StartsWith("tiny.msh:24: the file ends where element tag was expected (the file is cut short)"));
  // Cut so early that the node count cannot fit: reported at the count, before allocating.
  const std::string early(kTiny22.substr(0, kTiny22.find("4 0 1 0")));
  EXPECT_THAT(error_of(early), StartsWith("tiny.msh:11: number of nodes 6 is more than the rest of the file can hold "
                                          "(a corrupt count, or the file is cut short)"));
  EXPECT_THAT(error_of(""), HasSubstr("tiny.msh: the file is empty"));
  EXPECT_THAT(error_of(kTiny22.substr(0, kTiny22.find("$Elements"))), HasSubstr("the file has no $Elements section"));
}

TEST(GmshReaderInput, EveryPrefixOfARealFileIsRejected) {
  // Files written by gmsh in all four formats, and by us: cut after any byte, they must give an
  // InputError (never a crash or a read past the end). Only the final line end may go.
  test::TempDir dir;
  std::vector<std::pair<std::string, std::string>> files;
  for (const char* flavour : {"msh22", "msh22 -bin", "msh41", "msh41 -bin"}) {
    const auto path = dir / "tiny.msh";
    std::string command = "gmsh -2 -nt 1 '";
    command += test::data_path("gmsh/quad_channel.geo").string();
    command += "' -format ";
    command += flavour;
    command += " -o '" + path.string() + "' > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "gmsh is a required test dependency: " << command;
    files.emplace_back(flavour, test::read_text(path));
  }
  for (bool binary : {false, true}) {
    std::ostringstream ours;
    write_gmsh(ours, test::unit_cube(2), {.binary = binary});
    files.emplace_back(binary ? "ours binary" : "ours ASCII", ours.str());
  }
  for (const auto& [label, content] : files) {
    ASSERT_GT(content.size(), 100u);
    EXPECT_NO_THROW(parse_gmsh(content.substr(0, content.size() - 1), label)) << label;
    for (std::size_t size = 0; size + 1 < content.size(); ++size) {
      const std::string error = error_of(std::string_view(content).substr(0, size), label);
      ASSERT_THAT(error, StartsWith(label + ":")) << label << " cut to " << size << " bytes";
    }
  }
}

TEST(GmshReaderInput, CorruptBinaryBytesNeverCrash) {
  std::ostringstream out;
  Mesh mesh = test::unit_cube(2);
  mesh.cell_groups.push_back({"all", 3, {0, 1, 2, 3, 4, 5, 6, 7}});
  write_gmsh(out, mesh, {.binary = true});
  const std::string original = out.str();
  std::mt19937 random(12345);
  std::size_t rejected = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string content = original;
    for (int k = 0; k < 1 + trial % 4; ++k) {
      const auto at = std::uniform_int_distribution<std::size_t>(0, content.size() - 1)(random);
      content[at] = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(random));
    }
    try {
      parse_gmsh(content, "fuzz.msh");
    } catch (const InputError& e) {
      ++rejected;
      EXPECT_THAT(e.what(), StartsWith("fuzz.msh:"));
    }
  }
  EXPECT_GT(rejected, 100u);
}

TEST(GmshReaderInput, CountsThatDoNotMatchTheData) {
  const std::string more = replaced(kTiny22, "$Nodes\n6\n", "$Nodes\n7\n");
  EXPECT_THAT(error_of(more), StartsWith(line_of(more, "$EndNodes") +
                                         " found '$EndNodes' where node tag was expected: the section holds "
                                         "fewer entries than its counts say"));
  const std::string fewer = replaced(kTiny22, "$Elements\n4\n", "$Elements\n3\n");
  EXPECT_THAT(error_of(fewer),
              StartsWith(line_of(fewer, "4 3 2 10") + " expected $EndElements, found '4 3 2 10 1 2 3 6 5'"));
  const std::string total = replaced(kTiny41, "1 6 1 6\n", "1 7 1 7\n");
  EXPECT_THAT(error_of(total, "tiny41.msh"), HasSubstr("the $Nodes header announces 7 nodes, its blocks hold 6"));
  const std::string block = replaced(kTiny41, "2 3 1 3\n", "2 2 1 3\n");
  EXPECT_THAT(error_of(block, "tiny41.msh"),
              StartsWith(line_of(block, "2 1 3 2", "tiny41.msh") +
                         " element block of 2 elements, but the section header announces 2 elements in all and "
                         "1 came before"));
  const std::string huge = replaced(kTiny22, "$Nodes\n6\n", "$Nodes\n99999999999\n");
  EXPECT_THAT(error_of(huge), StartsWith(line_of(huge, "99999999999") +
                                         " number of nodes 99999999999 is more than the rest of the file can hold"));
}

TEST(GmshReaderInput, NonFiniteCoordinates) {
  const std::string nan = replaced(kTiny22, "3 2 0 0", "3 2 nan 0");
  EXPECT_THAT(error_of(nan),
              StartsWith(line_of(nan, "3 2 nan") + " node 3 has a coordinate that is not a finite number (2, nan, 0)"));
  const std::string inf = replaced(kTiny41, "0 1 0\n1 1 0\n", "0 1 0\n1 1 -inf\n");
  EXPECT_THAT(error_of(inf, "tiny41.msh"), StartsWith(line_of(inf, "1 1 -inf", "tiny41.msh") + " node 5 has"));

  Mesh mesh = test::unit_square(1, 1);
  mesh.points[2].x = std::numeric_limits<double>::quiet_NaN();
  std::ostringstream binary;
  write_gmsh(binary, mesh, {.binary = true});
  EXPECT_THAT(error_of(binary.str(), "nan.msh"),
              ::testing::MatchesRegex("nan\\.msh: byte [0-9]+ in \\$Nodes: node 3 has a coordinate that is not a "
                                      "finite number \\(nan, 1, 0\\)"));
}

TEST(GmshReaderInput, NonNumericToken) {
  const std::string text = replaced(kTiny22, "2 1 0 0", "2 1x 0 0");
  EXPECT_THAT(error_of(text), StartsWith(line_of(text, "2 1x") + " expected x coordinate, found '1x'"));
}

TEST(GmshReaderInput, UnknownAndUnsupportedElementTypes) {
  const std::string unknown = replaced(kTiny22, "3 3 2 10", "3 99 2 10");
  EXPECT_THAT(error_of(unknown), StartsWith(line_of(unknown, "3 99 2") + " unknown element type 99"));
  const std::string hex27 = replaced(kTiny22, "3 3 2 10", "3 12 2 10");
  EXPECT_THAT(error_of(hex27), StartsWith(line_of(hex27, "3 12 2") +
                                          " second-order hexahedron (type 12) is not supported: hotmesh needs "
                                          "linear elements (mesh with Mesh.ElementOrder = 1)"));
  const std::string quad9 = replaced(kTiny41, "2 1 3 2\n", "2 1 10 2\n");
  EXPECT_THAT(error_of(quad9, "tiny41.msh"), StartsWith(line_of(quad9, "2 1 10 2", "tiny41.msh") +
                                                        " second-order quadrangle (type 10) is not supported"));
}

TEST(GmshReaderInput, ElementWithTheWrongNumberOfNodes) {
  const std::string few = replaced(kTiny22, "3 3 2 10 1 1 2 5 4", "3 3 2 10 1 1 2 5");
  EXPECT_THAT(error_of(few),
              StartsWith(line_of(few, "3 3 2 10") + " element 3 of type 3 (quad4) has 3 node tags, needs 4"));
  const std::string many = replaced(kTiny41, "3 2 3 6 5", "3 2 3 6 5 1");
  EXPECT_THAT(error_of(many, "tiny41.msh"), StartsWith(line_of(many, "3 2 3 6 5 1", "tiny41.msh") +
                                                       " element 3 of type 3 (quad4) has more than 4 node tags"));
}

/// What spdlog's default logger writes while `read` runs.
template <typename Read>
std::string warnings_of(Read read) {
  std::ostringstream captured;
  const auto previous = spdlog::default_logger();
  auto logger = std::make_shared<spdlog::logger>("capture", std::make_shared<spdlog::sinks::ostream_sink_st>(captured));
  spdlog::set_default_logger(logger);
  try {
    read();
  } catch (...) {
    spdlog::set_default_logger(previous);
    throw;
  }
  spdlog::set_default_logger(previous);
  return captured.str();
}

TEST(GmshReaderInput, UnnamedGroupsAreNamedByTheirTag) {
  const std::string patch = replaced(replaced(kTiny22, "1 2 \"wall\"\n", ""), "$PhysicalNames\n3", "$PhysicalNames\n2");
  Mesh v2;
  EXPECT_THAT(warnings_of([&] { v2 = parse_gmsh(patch, "tiny.msh"); }),
              HasSubstr("tiny.msh: physical group 2 (dimension 1) has no name in $PhysicalNames: its patch is named "
                        "'2'"));
  ASSERT_EQ(v2.patches.size(), 2u);
  EXPECT_EQ(v2.patches[1].name, "2");
  EXPECT_EQ(v2.patches[1].tag, 2);
  EXPECT_EQ(v2.patches[1].faces.size(), 1u);

  const std::string cells =
      replaced(replaced(kTiny41, "2 10 \"fluid\"\n", ""), "$PhysicalNames\n2", "$PhysicalNames\n1");
  Mesh v4;
  EXPECT_THAT(warnings_of([&] { v4 = parse_gmsh(cells, "tiny41.msh"); }),
              HasSubstr("physical group 10 (dimension 2) has no name in $PhysicalNames: its cell group is named '10'"));
  ASSERT_EQ(v4.cell_groups.size(), 1u);
  EXPECT_EQ(v4.cell_groups[0].name, "10");
  EXPECT_EQ(v4.cell_groups[0].cells.size(), 2u);

  // gmsh writes "" for a group named with an empty string: a role still needs a name
  const std::string empty = replaced(kTiny22, "1 2 \"wall\"", "1 2 \"\"");
  EXPECT_THAT(warnings_of([&] { v2 = parse_gmsh(empty, "tiny.msh"); }),
              HasSubstr("physical group 2 (dimension 1) has an empty name in $PhysicalNames: its patch is named '2'"));
  EXPECT_EQ(v2.patches[1].name, "2");
}

TEST(GmshReaderInput, AGroupNamedByItsTagMayNotTakeAnotherGroupsName) {
  const std::string text =
      replaced(replaced(kTiny22, "1 2 \"wall\"\n", ""), "1 1 \"inlet\"", "1 1 \"2\"");
  const std::string fixed = replaced(text, "$PhysicalNames\n3", "$PhysicalNames\n2");
  EXPECT_THAT(error_of(fixed), StartsWith(line_of(fixed, "1 1 \"2\"") +
                                          " physical groups 1 and 2 (dimension 1) are both named '2'; patch "
                                          "names must be unique"));
}

TEST(GmshReaderInput, NegativePhysicalTagsAreTheirGroups) {
  // gmsh 4.1 writes -t for an entity in group t with the opposite orientation, and reads it as t
  const std::string text = replaced(kTiny41, "1 0 0 0 0 1 0 1 1 0", "1 0 0 0 0 1 0 1 -1 0");
  const Mesh mesh = parse_gmsh(text, "tiny41.msh");
  ASSERT_EQ(mesh.patches.size(), 1u);
  EXPECT_EQ(mesh.patches[0].name, "inlet");
  EXPECT_EQ(mesh.patches[0].tag, 1);
  EXPECT_EQ(mesh.patches[0].faces.size(), 1u);
  const std::string zero = replaced(kTiny41, "1 0 0 0 0 1 0 1 1 0", "1 0 0 0 0 1 0 1 0 0");
  EXPECT_THAT(error_of(zero, "tiny41.msh"),
              StartsWith(line_of(zero, "1 0 0 0 0 1 0 1 0 0", "tiny41.msh") +
                         " physical tag 0 is out of range (1 to 2147483647, or its negative)"));
}

TEST(GmshReaderInput, TwoPatchesWithOneName) {
  const std::string text = replaced(kTiny22, "1 2 \"wall\"", "1 2 \"inlet\"");
  EXPECT_THAT(error_of(text), StartsWith(line_of(text, "1 2 \"inlet\"") +
                                         " physical groups 1 and 2 (dimension 1) are both named 'inlet'; patch "
                                         "names must be unique"));
}

TEST(GmshReaderInput, UndefinedAndDuplicateNodeTags) {
  const std::string undefined = replaced(kTiny22, "4 3 2 10 1 2 3 6 5", "4 3 2 10 1 2 3 9 5");
  EXPECT_THAT(error_of(undefined),
              StartsWith(line_of(undefined, "4 3 2 10") + " element refers to node 9, which $Nodes does not define"));
  const std::string twice = replaced(kTiny22, "5 1 1 0", "3 1 1 0");
  EXPECT_THAT(error_of(twice), StartsWith(line_of(twice, "3 1 1 0") + " node tag 3 is defined twice"));
  const std::string twice41 = replaced(kTiny41, "\n5\n", "\n2\n");
  EXPECT_THAT(error_of(twice41, "tiny41.msh"), HasSubstr(":21: node tag 2 is defined twice"));
  EXPECT_THAT(error_of(replaced(kTiny22, "1 0 0 0", "0 0 0 0")), HasSubstr("tiny.msh:12: node tag 0 is not positive"));
}

TEST(GmshReaderInput, UnsupportedVersionsAndNonMeshFiles) {
  EXPECT_THAT(error_of(replaced(kTiny22, "2.2 0 8", "3.0 0 8")),
              StartsWith("tiny.msh:2: format 3.0 is not supported; save as 4.1 or 2.2"));
  EXPECT_THAT(error_of(replaced(kTiny41, "4.1 0 8", "4 0 8")), HasSubstr("format 4 is not supported"));
  EXPECT_THAT(error_of("solid cube\nfacet normal 0 0 1\n"),
              StartsWith("tiny.msh:1: not a Gmsh .msh file: it does not start with $MeshFormat"));
  EXPECT_THAT(error_of("$NOD\n1\n1 0 0 0\n$ENDNOD\n"), HasSubstr("format 1.0 is not supported"));
}

TEST(GmshReaderInput, PartitionedFile) {
  const std::string text =
      replaced(kTiny41, "$Nodes\n", "$PartitionedEntities\n2\n0\n$EndPartitionedEntities\n$Nodes\n");
  EXPECT_THAT(error_of(text, "tiny41.msh"), StartsWith(line_of(text, "$PartitionedEntities", "tiny41.msh") +
                                                       " partitioned meshes are not supported"));
}

TEST(GmshReaderInput, BinaryByteOrderAndDataSize) {
  std::ostringstream out;
  write_gmsh(out, test::unit_square(1, 1), {.binary = true});
  std::string swapped = out.str();
  const auto marker = swapped.find("4.1 1 8\n") + 8;
  swapped[marker] = 0;
  swapped[marker + 3] = 1;
  EXPECT_THAT(error_of(swapped, "be.msh"),
              HasSubstr("be.msh: byte 20 in $MeshFormat: the binary file has the other byte order"));
  EXPECT_THAT(error_of(replaced(out.str(), "4.1 1 8", "4.1 1 4"), "x.msh"),
              HasSubstr("binary files must have data size 8"));
}

TEST(GmshReaderInput, ElementBlockOnUndefinedEntity) {
  const std::string text = replaced(kTiny41, "2 1 3 2\n", "2 7 3 2\n");
  EXPECT_THAT(error_of(text, "tiny41.msh"),
              StartsWith(line_of(text, "2 7 3 2", "tiny41.msh") +
                         " element block on entity 7 of dimension 2, which $Entities does not define"));
}

TEST(GmshReaderInput, FileWithoutCells) {
  const std::string lines =
      replaced(replaced(replaced(kTiny22, "3 3 2 10 1 1 2 5 4\n", ""), "4 3 2 10 1 2 3 6 5\n", ""), "$Elements\n4",
               "$Elements\n2");
  EXPECT_THAT(error_of(lines),
              HasSubstr("tiny.msh: the file holds only lines and points: hotmesh needs 2D or 3D cells"));
}

// ---- variations that must be accepted ---------------------------------------------------

TEST(GmshReaderInput, CrlfLineEndsAndExtraSectionsAreAccepted) {
  const Mesh expected = parse_gmsh(kTiny22, "tiny.msh");
  std::string crlf;
  for (char c : kTiny22) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  EXPECT_EQ(parse_gmsh(crlf, "crlf.msh"), expected);
  const std::string extra =
      replaced(kTiny22, "$Nodes\n",
               "$Comments\nnot $EndNodes: a remark\n$EndComments\n"
               "$Periodic\n0\n$EndPeriodic\n\n$Nodes\n") +
      "$NodeData\n1\n\"T\"\n1\n0.0\n3\n0\n1\n6\n1 300\n2 300\n3 300\n4 300\n5 300\n6 300\n$EndNodeData\n";
  EXPECT_EQ(parse_gmsh(extra, "extra.msh"), expected);
  EXPECT_THAT(error_of(replaced(kTiny22, "$Nodes\n", "$Comments\n$Nodes\n")),
              HasSubstr("section $Comments has no $EndComments"));
}

TEST(GmshReaderInput, Format22ElementRepeatedPerGroupIsOneCell) {
  // gmsh writes an element of two physical groups twice, with new tags: one cell, two groups.
  // The same nodes under another elementary entity are a second cell (not merged).
  std::string text = replaced(kTiny22, "2 10 \"fluid\"\n", "2 10 \"fluid\"\n2 11 \"hot\"\n1 3 \"bottom\"\n");
  text = replaced(text, "$PhysicalNames\n3", "$PhysicalNames\n5");
  text = replaced(text, "$Elements\n4\n", "$Elements\n8\n");
  text = replaced(text, "2 1 2 2 2 1 2\n", "2 1 2 2 2 1 2\n12 1 2 3 2 1 2\n");
  text = replaced(text, "3 3 2 10 1 1 2 5 4\n", "3 3 2 10 1 1 2 5 4\n13 3 2 11 1 1 2 5 4\n");
  text = replaced(text, "4 3 2 10 1 2 3 6 5\n", "4 3 2 10 1 2 3 6 5\n14 3 2 11 1 2 3 6 5\n15 3 2 11 9 2 3 6 5\n");
  const Mesh mesh = parse_gmsh(text, "groups.msh");
  EXPECT_EQ(mesh.cell_count(), 3u);
  EXPECT_EQ(mesh.cell_ids, (std::vector<std::int64_t>{3, 4, 15}));
  ASSERT_EQ(mesh.cell_groups.size(), 2u);
  EXPECT_EQ(mesh.cell_groups[0].cells, (std::vector<mesh::CellId>{0, 1}));
  EXPECT_EQ(mesh.cell_groups[1].name, "hot");
  EXPECT_EQ(mesh.cell_groups[1].cells, (std::vector<mesh::CellId>{0, 1, 2}));
  ASSERT_EQ(mesh.patches.size(), 3u);
  EXPECT_EQ(mesh.patches[1].faces, mesh.patches[2].faces);  // the edge is in "wall" and "bottom"
  EXPECT_EQ(mesh.patches[2].name, "bottom");
}

TEST(GmshReaderInput, NodesKeepFileOrderWithSparseTags) {
  std::string text = std::string(kTiny22);
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{{"\n1 0 0 0", "\n900000000000 0 0 0"},
                                                                                 {"4 1\n", "4 900000000000\n"},
                                                                                 {"1 1 2 5 4", "1 900000000000 2 5 4"},
                                                                                 {"\n2 1 0 0", "\n77 1 0 0"},
                                                                                 {"2 2 2 1 2", "2 2 2 900000000000 77"},
                                                                                 {"2 5 4", "77 5 4"},
                                                                                 {"1 2 3 6 5", "1 77 3 6 5"}}) {
    text = replaced(text, from, to);
  }
  const Mesh sparse = parse_gmsh(text, "sparse.msh");
  const Mesh dense = parse_gmsh(kTiny22, "tiny.msh");
  EXPECT_EQ(sparse.node_ids, (std::vector<std::int64_t>{900000000000, 77, 3, 4, 5, 6}));
  EXPECT_EQ(sparse.points, dense.points);
  EXPECT_EQ(sparse.cells, dense.cells);
  EXPECT_EQ(sparse.patches, dense.patches);
}

TEST(GmshReaderInput, Format41WithoutEntitiesHasNoGroups) {
  std::string text = replaced(
      kTiny41, kTiny41.substr(kTiny41.find("$Entities"), kTiny41.find("$Nodes") - kTiny41.find("$Entities")), "");
  text = replaced(text, "2 10 \"fluid\"\n", "");
  text = replaced(text, "1 1 \"inlet\"\n", "");
  text = replaced(text, "$PhysicalNames\n2", "$PhysicalNames\n0");
  const Mesh mesh = parse_gmsh(text, "bare.msh");
  EXPECT_EQ(mesh.cell_count(), 2u);
  EXPECT_TRUE(mesh.patches.empty());
  EXPECT_TRUE(mesh.cell_groups.empty());
}

// A mesh the gmsh fuzz target made from a sample (docs/fuzzing.md): one node moved some 10^12
// away makes the duplicate tolerance (a fraction of the bounding box) larger than the rest of
// the mesh, so its 1 525 nodes make 1.2 million duplicate pairs; counting each one took the
// target 10 s, and a million-node mesh would have kept the validation busy for days. The count
// stops at 100 000 pairs.
TEST(GmshReaderInput, NodesCrowdedByOneFarAwayStopTheDuplicateCount) {
  const auto file = test::data_path("fuzz/gmsh-nodes-crowded-by-one-far-away.msh");
  try {
    read_mesh(file);
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string() + ": "));
    EXPECT_THAT(e.what(), HasSubstr(" or more pairs of nodes are duplicates"));
    EXPECT_THAT(e.what(), HasSubstr("node 1 at (0, 0, 0) and node 1525"));
  }
}

}  // namespace
}  // namespace hotmesh::io
