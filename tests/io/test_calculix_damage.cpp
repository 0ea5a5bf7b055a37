// hotmesh tests: CalculiX decks and results that crashed the readers, hung them or made them
// allocate gigabytes (issue 46; the files are in tests/data/calculix/): each is read, or
// refused with an InputError naming the file, the line and what is wrong, at once.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/calculix.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

/// The message read_inp refuses `file` with, "(read)" if it reads it.
std::string inp_error(const std::filesystem::path& file, const InpLimits& limits = {}) {
  try {
    read_inp(file, limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read)";
}

/// The message parse_frd refuses `text` with, "(read)" if it reads it.
std::string frd_error(const std::string& text, std::string_view source) {
  try {
    parse_frd(text, source);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read)";
}

std::string data_text(std::string_view name) { return test::read_text(test::data_path(name)); }

// An element redefined after a *SURFACE used one of its faces: the surface's nodes were taken
// from the new element, whose type has no such face (S4 of a CAX3) or no faces at all (a
// beam): a segmentation fault in `hotmesh fem --inp` and while `hotmesh deform` read its case.
// CalculiX refuses a deck that defines an element twice, and so does hotmesh.
TEST(CalculixDeckElements, ElementRedefinedAsATriangleAfterASurfaceUsedItsFourthFaceIsRefused) {
  const auto file = test::data_path("calculix/element-redefined-as-cax3.inp");
  EXPECT_THAT(inp_error(file), StartsWith(file.string() + ":11: element 1 is defined already, at " + file.string() +
                                          ":7; CalculiX refuses a deck that defines an element twice"));
}

TEST(CalculixDeckElements, ElementRedefinedAsABeamAfterASurfaceUsedItsFaceIsRefused) {
  const auto file = test::data_path("calculix/element-redefined-as-beam.inp");
  EXPECT_THAT(inp_error(file), StartsWith(file.string() + ":14: element 1 is defined already, at " + file.string() + ":9"));
}

// `9223372036854775806, 9223372036854775807`: the loop's n += 1 overflowed past the last
// number and never ended.
TEST(CalculixDeckLimits, GenerateRangeEndingAtTheLargestNumberHoldsItsTwoNumbers) {
  const InpDeck deck = read_inp(test::data_path("calculix/generate-at-int64-max.inp"));
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  EXPECT_EQ(deck.set_nodes("A"), (std::vector<std::int64_t>{kMax - 1, kMax}));
}

// The whole 64-bit range: last - first overflowed, and the range passed the old cap of 1e8.
TEST(CalculixDeckLimits, GenerateRangeOverAllSixtyFourBitsIsRefusedWithItsCount) {
  const auto file = test::data_path("calculix/generate-whole-int64-range.inp");
  EXPECT_THAT(inp_error(file), StartsWith(file.string() + ":4: a GENERATE range of 2^64 numbers: more than the "
                                          "30000000 numbers hotmesh holds in all sets of a deck"));
}

// Twelve ranges of 1e8 in one set: each passed the old cap of 1e8 a line, 9.6 GB in all.
TEST(CalculixDeckLimits, GenerateRangesLargerThanTheDecksLimitAreRefusedAtTheFirst) {
  const auto file = test::data_path("calculix/generate-twelve-ranges-of-1e8.inp");
  EXPECT_THAT(inp_error(file), StartsWith(file.string() + ":4: a GENERATE range of 100000000 numbers"));
}

TEST(CalculixDeckLimits, SetMembersAreCountedOverAllSetsOfTheDeck) {
  test::TempDir dir;
  test::write_text(dir / "deck.inp", "*NSET, NSET=A, GENERATE\n1, 100\n*ELSET, ELSET=B, GENERATE\n1, 100\n"
                                     "*NSET, NSET=C\nA\n");
  InpLimits limits;
  limits.set_members = 250;
  EXPECT_THAT(inp_error(dir / "deck.inp", limits),
              StartsWith((dir / "deck.inp").string() + ":6: this line adds 100 numbers to the deck's sets, which hold 200 "
                                                       "already: more than the 250 numbers hotmesh holds"));
  limits.set_members = 300;
  EXPECT_EQ(inp_error(dir / "deck.inp", limits), "(read)");
}

// 1.2 KB of deck, each set the one before twice over: 2^30 numbers, 8 GB.
TEST(CalculixDeckLimits, SetsDefinedAsThePreviousSetTwiceOverStopAtTheLimit) {
  const auto file = test::data_path("calculix/sets-doubled-thirty-times.inp");
  EXPECT_THAT(inp_error(file), StartsWith(file.string() + ":54: this line adds 8388608 numbers to the deck's sets, "
                                          "which hold 25165823 already"));
}

TEST(CalculixDeckLimits, SurfaceFacesCountTheirNodes) {
  test::TempDir dir;
  test::write_text(dir / "deck.inp", "*NODE\n1,1,0\n2,2,0\n3,2,1\n4,1,1\n5,1.5,0\n6,2,0.5\n7,1.5,1\n8,1,0.5\n"
                                     "*ELEMENT, TYPE=CAX8, ELSET=E\n1, 1,2,3,4,5,6,7,8\n"
                                     "*SURFACE, NAME=S\nE, S1\nE, S2\n");
  InpLimits limits;
  limits.set_members = 1 + 5;  // E, then the three nodes of S1; S2 would make it 7
  EXPECT_THAT(inp_error(dir / "deck.inp", limits), StartsWith((dir / "deck.inp").string() + ":14: this line adds 3"));
}

/// 31 files, each but the last including the next one twice: 2^31 reads of the last one.
void write_include_diamond(const std::filesystem::path& folder) {
  for (int i = 1; i <= 30; ++i) {
    test::write_text(folder / fmt::format("d{:02}.inp", i),
                     fmt::format("*INCLUDE, INPUT=d{0:02}.inp\n*INCLUDE, INPUT=d{0:02}.inp\n", i + 1));
  }
  test::write_text(folder / "d31.inp", "*NODE\n1, 1.0, 0.0\n");
}

// The depth limit of 32 files did not bound the reads: 4 GB of copies of d31.inp, then a hang.
TEST(CalculixDeckLimits, DiamondOfIncludesStopsAtTheIncludeLimit) {
  test::TempDir dir;
  write_include_diamond(dir.path());
  const std::string message = inp_error(dir / "d01.inp");
  EXPECT_THAT(message, ::testing::MatchesRegex(".*/d[0-9][0-9]\\.inp:[12]: more than 10000 \\*INCLUDE reads for one deck "
                                               "\\(a file included again counts again\\).*"));
}

// A file may be included more than once (the same loads in two steps): read once, listed once.
TEST(CalculixDeckLimits, FileIncludedTwiceIsListedOnceAndCountsTwiceAgainstTheLineLimit) {
  test::TempDir dir;
  test::write_text(dir / "nodes.inp", "1, 1.0, 0.0\n2, 2.0, 0.0\n");
  test::write_text(dir / "deck.inp", "*NODE, NSET=N\n*INCLUDE, INPUT=nodes.inp\n*NODE, NSET=M\n*INCLUDE, INPUT=nodes.inp\n");
  const InpDeck deck = read_inp(dir / "deck.inp");
  EXPECT_EQ(deck.files, (std::vector<std::filesystem::path>{dir / "deck.inp", dir / "nodes.inp"}));
  EXPECT_EQ(deck.set_nodes("M"), (std::vector<std::int64_t>{1, 2}));

  InpLimits limits;
  limits.lines = 5;
  EXPECT_THAT(inp_error(dir / "deck.inp", limits),
              StartsWith((dir / "nodes.inp").string() + ":2: the deck has more than 5 lines, its *INCLUDEs spliced in"));
}

// A node block with NaN coordinates passed the check that the results belong to the deck
// (every comparison with NaN is false), and `hotmesh fem` printed "largest |u| nan".
TEST(CalculixFrdValues, NanCoordinatesAreRefusedWithTheirLine) {
  EXPECT_EQ(frd_error(data_text("calculix/plate.frd"), "plate.frd"), "(read)");
  EXPECT_THAT(frd_error(data_text("calculix/plate-nan-coordinates.frd"), "nan.frd"),
              StartsWith("nan.frd:14: node 2 is at (nan, nan, nan): coordinates must be finite numbers"));
}

TEST(CalculixFrdValues, NanDisplacementIsRefusedWithItsLine) {
  EXPECT_THAT(frd_error(data_text("calculix/plate-nan-displacement.frd"), "nan.frd"),
              StartsWith("nan.frd:31: node 3 has the value nan in the DISP block: its values must be finite numbers"));
}

/// `text` with the bytes of `value` written `offset` bytes after the end of the first line
/// that starts with `line`.
template <class T>
std::string with_value_after(std::string text, std::string_view line, std::size_t offset, T value) {
  const std::size_t at = text.find(line);
  const std::size_t data = text.find('\n', at) + 1 + offset;
  std::memcpy(text.data() + data, &value, sizeof value);
  return text;
}

TEST(CalculixFrdValues, NonFiniteBinaryValuesAreRefused) {
  // ccx's binary node block holds doubles (format 3), its DISP block floats (format 2), each
  // record after a 4-byte node number.
  const std::string binary = data_text("calculix/plate-binary.frd");
  ASSERT_EQ(frd_error(binary, "plate.frd"), "(read)");
  const std::string node = with_value_after(binary, "    2C", 28 + 4, std::numeric_limits<double>::infinity());
  EXPECT_THAT(frd_error(node, "inf.frd"), StartsWith("inf.frd:12: node 2 (record 2 of the binary node block after this "
                                                     "line) is at (inf, 0, 1.22465e-16)"));
  const std::string disp = with_value_after(binary, " -5  ALL", 16 * 2 + 4 + 4, std::numeric_limits<float>::quiet_NaN());
  EXPECT_THAT(frd_error(disp, "nan.frd"), HasSubstr("node 3 (record 3 of the binary DISP block after this line) has "));
}

TEST(CalculixTable, NodesAtNanAreNotWhereTheDeckPutsThem) {
  // Made in code, as parse_frd refuses such a file: the check itself must not let NaN pass.
  FrdResults results = parse_frd(data_text("calculix/plate.frd"), "plate.frd");
  results.nodes.at(2) = {std::nan(""), 0.0, 0.0};
  const InpDeck deck = read_inp(test::data_path("calculix/plate.inp"));
  try {
    calculix_table(results, deck, {"plate.frd", deck.file, "RIM", {}});
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("plate.frd: node 2 is at (nan, 0.000000, 0.000000) here"));
  }
}

// The records of the .frd blocks that issue 49 reads: a continuation record whose node
// columns are not blank, an element with more nodes than its type, an unknown element type.
TEST(CalculixFrdRecords, DamagedContinuationAndElementRecordsAreRefusedWithTheirLine) {
  const std::string head = "    1C\n    2C                             1                                     1\n"
                           " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n -3\n";
  std::string components;
  for (int k = 1; k <= 7; ++k) components += fmt::format(" -5  SDV{}        1    1    0    0\n", k);
  const std::string values = " -1         1 1.00000E+00 2.00000E+00 3.00000E+00 4.00000E+00 5.00000E+00 6.00000E+00\n";
  const std::string sdv = "  100CL  101 1.000000000           1                     0    1           1\n -4  SDV         7    1\n" +
                          components + values;
  EXPECT_EQ(frd_error(head + sdv + " -2           7.00000E+00\n -3\n9999\n", "ok.frd"), "(read)");
  EXPECT_THAT(frd_error(head + sdv + " -2         1 7.00000E+00\n -3\n9999\n", "node.frd"),
              StartsWith("node.frd:15: a ' -2' continuation record has blank columns 4-13, got '         1'"));
  EXPECT_THAT(frd_error(head + sdv + " -3\n9999\n", "short.frd"),
              StartsWith("short.frd:15: node 1 of the SDV block has 6 values, the block 7"));

  const std::string elements = "    3C                             1                                     1\n";
  EXPECT_THAT(frd_error(head + elements + " -1         1   11    0    1\n -2         1         1         1\n -3\n9999\n", "be2.frd"),
              StartsWith("be2.frd:7: element 1 has 3 nodes, its type 2"));
  EXPECT_THAT(frd_error(head + elements + " -1         1   13    0    1\n -2         1\n -3\n9999\n", "type.frd"),
              StartsWith("type.frd:6: element 1 has the unknown element type 13; the .frd types are 1 to 12"));
}

}  // namespace
}  // namespace hotmesh::io
