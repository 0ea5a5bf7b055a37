// hotmesh tests: damaged CGNS files that overflowed the reader's buffers, made it throw the
// wrong exception or allocate gigabytes (issue 46). Each is written with the CGNS library and
// then has arrays edited in place (test::overwrite_integers), as the finder edited them;
// each must be refused with an InputError naming the file, the zone and section or BC, and the
// numbers that do not fit, before anything is sized from them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cgnslib.h>

#include <algorithm>
#include <climits>
#include <stdexcept>

#include "allocation_watch.hpp"
#include "cgns_files.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/cgns.hpp"
#include "read_error.hpp"
#include "run_command.hpp"
#include "hybrid_meshes.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using test_io::read_error;

/// The largest single allocation of read_mesh(file) (which must refuse it), or 0 where
/// operator new is not watched (under AddressSanitizer).
std::size_t largest_allocation_refusing(const std::filesystem::path& file) {
#if HOTMESH_WATCH_ALLOCATIONS
  ::test::allocations::arm();
  try {
    read_mesh(file);
    ADD_FAILURE() << file << " was read";
  } catch (const InputError&) {
  }
  ::test::allocations::armed = false;
  return ::test::allocations::largest;
#else
  (void)file;
  return 0;
#endif
}

constexpr std::size_t kMegabyte = std::size_t{1} << 20;

/// Opens `file` in modify mode for `edit(fn)` with the CGNS library's own writers.
template <class Edit>
void modify(const std::filesystem::path& file, Edit edit) {
  int fn = 0;
  if (cg_open(file.c_str(), CG_MODE_MODIFY, &fn) != CG_OK) throw std::runtime_error(cg_get_error());
  edit(fn);
  cg_close(fn);
}

// ---- MIXED sections: ElementRange against the stored ElementStartOffset -------------------

// write_unstructured_2d's section "Cells": MIXED, elements 1..6, 6 QUAD_4 (30 entries, 7
// offsets). The offsets buffer was sized from ElementRange, and cg_poly_elements_read wrote
// the whole stored ElementStartOffset into it: a heap overflow (SIGSEGV, "double free or
// corruption").
TEST(CgnsMixedSections, RangeOfFewerElementsThanTheStoredOffsetsIsRefused) {
  test::TempDir dir;
  const auto file = dir / "short-range.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/Cells/ElementRange", {1, 3});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' section 'Cells'"),
                                      HasSubstr("ElementRange 1..3 (3 elements)"),
                                      HasSubstr("the 7 offsets its ElementStartOffset stores")));
}

// The same in a MIXED section of boundary faces: the triangles and quads of the side of the
// hybrid box (gmsh), as hotmesh writes them.
TEST(CgnsMixedSections, FaceSectionRangeOfFewerElementsThanTheStoredOffsetsIsRefused) {
  test::TempDir dir;
  const auto file = dir / "short-face-range.cgns";
  const mesh::Mesh box = read_mesh(test::hybrid_msh("hybrid_box", 3, dir.path())).mesh;
  write_cgns(file, box, box.points);
  const CgnsSummary summary = describe_cgns(file);
  const auto& sections = summary.bases.at(0).zones.at(0).sections;
  const auto sides = std::find_if(sections.begin(), sections.end(), [](const auto& s) { return s.name == "sides"; });
  ASSERT_NE(sides, sections.end());
  ASSERT_EQ(sides->type, "MIXED");
  test::overwrite_integers(file, "/Base/Zone/sides/ElementRange",
                           {static_cast<int>(sides->first), static_cast<int>(sides->first + 1)});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Zone' section 'sides'"),
                                      HasSubstr("(2 elements) does not match the"),
                                      HasSubstr("offsets its ElementStartOffset stores")));
}

// One element more than stored: ElementStartOffset has 7 offsets, the range wants 8 (the
// connectivity ran out: vector::_M_range_check, exit 3).
TEST(CgnsMixedSections, RangeOneElementTooLongIsRefused) {
  test::TempDir dir;
  const auto file = dir / "long-range.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/Cells/ElementRange", {1, 7});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' section 'Cells'"),
                                      HasSubstr("ElementRange 1..7 (7 elements)"),
                                      HasSubstr("the 7 offsets its ElementStartOffset stores")));
}

// The connectivity cut short by two entries, the offsets left as they were: the last quad
// ends past the data.
TEST(CgnsMixedSections, ConnectivityShorterThanItsOffsetsIsRefused) {
  test::TempDir dir;
  const auto file = dir / "short-connectivity.cgns";
  test::write_unstructured_2d(file);
  std::vector<int> quads;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) quads.insert(quads.end(), {CGNS_ENUMV(QUAD_4), i + 4 * j + 1, i + 4 * j + 2, i + 4 * j + 6, i + 4 * j + 5});
  }
  quads.resize(quads.size() - 2);
  test::overwrite_integers(file, "/Base/Fluid/Cells/ElementConnectivity", quads);
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' section 'Cells'"),
                                      HasSubstr("ElementStartOffset starts at 0 and ends at 30"),
                                      HasSubstr("ElementConnectivity stores 28 values")));
}

// Offsets that disagree with the elements' types: the fifth quad's end moved one value back.
TEST(CgnsMixedSections, ElementWhoseSizeDisagreesWithItsOffsetsIsRefused) {
  test::TempDir dir;
  const auto file = dir / "offsets-disagree.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/Cells/ElementStartOffset", {0, 5, 10, 15, 20, 24, 30});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' MIXED section 'Cells'"),
                                      HasSubstr("element 5 (QUAD_4, 4 nodes) ends at value 25"),
                                      HasSubstr("ElementStartOffset says 24")));
}

// Found by fuzz_cgns: a type code that is no ElementType_t was made one before it was checked
// (undefined behaviour, UndefinedBehaviorSanitizer's report).
TEST(CgnsMixedSections, ElementTypeCodeBeyondTheLibrarysTypesIsRefused) {
  test::TempDir dir;
  const auto file = dir / "bad-type-code.cgns";
  test::write_unstructured_2d(file);
  std::vector<int> quads;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) quads.insert(quads.end(), {CGNS_ENUMV(QUAD_4), i + 4 * j + 1, i + 4 * j + 2, i + 4 * j + 6, i + 4 * j + 5});
  }
  quads[10] = 1000;  // the third quad's type
  test::overwrite_integers(file, "/Base/Fluid/Cells/ElementConnectivity", quads);
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' MIXED section 'Cells'"),
                                      HasSubstr("element 3 has type code 1000, which hotmesh does not read")));
}

TEST(CgnsMixedSections, ReversedRangeIsRefused) {
  test::TempDir dir;
  const auto file = dir / "reversed.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/Cells/ElementRange", {10, 1});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' section 'Cells'"),
                                      HasSubstr("ElementRange 10..1 is reversed")));
}

// 1..2^31-1: "cannot create std::vector larger than max_size()" (exit 3) from the offsets'
// size, end - start + 2, overflowing a 32-bit cgsize_t.
TEST(CgnsMixedSections, HugeRangeIsRefusedBeforeAllocating) {
  test::TempDir dir;
  const auto file = dir / "huge-range.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/Cells/ElementRange", {1, INT_MAX});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' section 'Cells'"),
                                      HasSubstr("ElementRange 1..2147483647 (2147483647 elements)"),
                                      HasSubstr("the 7 offsets its ElementStartOffset stores")));
  EXPECT_LT(largest_allocation_refusing(file), kMegabyte);
}

// A typed section whose range holds more elements than its connectivity stores.
TEST(CgnsTypedSections, RangeOfMoreElementsThanTheConnectivityStoresIsRefused) {
  test::TempDir dir;
  const auto file = dir / "typed-range.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/Bottom/ElementRange", {7, INT_MAX});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' section 'Bottom'"),
                                      HasSubstr("ElementRange 7..2147483647"),
                                      HasSubstr("ElementConnectivity stores 6 values")));
  EXPECT_LT(largest_allocation_refusing(file), kMegabyte);
}

// ---- point sets: checked against the zone before they are expanded ------------------------

// write_unstructured_2d's BC "bottom": PointRange 7..9 at EdgeCenter (its BAR_2 elements).
TEST(CgnsPointRanges, FaceRangeOfMoreElementsThanTheZoneHasIsRefusedBeforeExpanding) {
  test::TempDir dir;
  const auto file = dir / "huge-face-range.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/ZoneBC/bottom/PointRange", {1, INT_MAX}, {1, 2});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' BC 'bottom'"),
                                      HasSubstr("2147483647 elements")));
  EXPECT_LT(largest_allocation_refusing(file), kMegabyte);
}

// A vertex PointRange added to write_unstructured_2d's zone, then widened to 1..2^31-1.
TEST(CgnsPointRanges, VertexRangeBeyondTheZoneIsRefusedBeforeExpanding) {
  test::TempDir dir;
  const auto file = dir / "huge-vertex-range.cgns";
  test::write_unstructured_2d(file);
  modify(file, [](int fn) {
    const std::vector<cgsize_t> range{1, 4};
    int b = 0;
    cg_boco_write(fn, 1, 1, "band", CGNS_ENUMV(BCWall), CGNS_ENUMV(PointRange), 2, range.data(), &b);
  });
  ASSERT_EQ(read_error(file), "no error");
  test::overwrite_integers(file, "/Base/Fluid/ZoneBC/band/PointRange", {1, INT_MAX}, {1, 2});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' BC 'band'"),
                                      HasSubstr("PointRange 1..2147483647"), HasSubstr("the zone has 12 nodes")));
  EXPECT_LT(largest_allocation_refusing(file), kMegabyte);
}

// write_structured_3d's BC "xmin" of zone A (3 x 3 x 3 nodes), widened to 2e6 x 7 x 2e6
// points: 3.2 GB and seconds before its first point was checked.
TEST(CgnsPointRanges, StructuredBcRangeBeyondTheZoneIsRefusedBeforeExpanding) {
  test::TempDir dir;
  const auto file = dir / "huge-structured-bc.cgns";
  test::write_structured_3d(file);
  test::overwrite_integers(file, "/Base/A/ZoneBC/xmin/PointRange", {1, 1, 1, 2000000, 7, 2000000}, {3, 2});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'A' BC 'xmin'"),
                                      HasSubstr("2000000 along i"), HasSubstr("the zone has 3")));
  EXPECT_LT(largest_allocation_refusing(file), kMegabyte);
}

// A 1-to-1 connection added between write_structured_3d's zones at x = 1, then its range in
// zone A widened to 2e6 x 7 x 2e6.
TEST(CgnsPointRanges, OneToOneRangeBeyondTheZoneIsRefusedBeforeExpanding) {
  test::TempDir dir;
  const auto file = dir / "huge-one-to-one.cgns";
  test::write_structured_3d(file);
  modify(file, [](int fn) {
    const std::vector<cgsize_t> a{3, 1, 1, 3, 3, 3}, b{1, 1, 1, 1, 3, 3};
    const std::vector<int> transform{1, 2, 3};
    int c = 0;
    cg_1to1_write(fn, 1, 1, "A_to_B", "B", a.data(), b.data(), transform.data(), &c);
  });
  ASSERT_EQ(read_error(file), "no error");
  test::overwrite_integers(file, "/Base/A/ZoneGridConnectivity/A_to_B/PointRange", {1, 1, 1, 2000000, 7, 2000000},
                           {3, 2});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'A' connection 'A_to_B'"),
                                      HasSubstr("2000000 along i"), HasSubstr("the zone has 3")));
  EXPECT_LT(largest_allocation_refusing(file), kMegabyte);
}

// ---- point sets stored with more values per point than the zone's index dimension ---------

// The library reads a point set's whole stored array into a buffer of (index dimension x
// points) values: a PointRange of an unstructured zone stored as 3 x 2 values overflowed the
// BC's buffer of 2.
TEST(CgnsPointSets, BcPointRangeStoringThreeIndicesPerPointInAnUnstructuredZoneIsRefused) {
  test::TempDir dir;
  const auto file = dir / "wide-bc-range.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid/ZoneBC/bottom/PointRange", {7, 7, 7, 9, 9, 9}, {3, 2});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'Fluid' BC 'bottom'"),
                                      HasSubstr("PointRange stores 3 x 2 values"), HasSubstr("1 per point")));
}

// The same for a 1-to-1 connection's range, read into the reader's array of 6 (2 x 3).
TEST(CgnsPointSets, OneToOneRangeStoringMorePointsThanARangeIsRefused) {
  test::TempDir dir;
  const auto file = dir / "wide-one-to-one.cgns";
  test::write_structured_2d(file);
  std::vector<int> values(2 * 40, 1);
  test::overwrite_integers(file, "/Base/A/ZoneGridConnectivity/A_to_B/PointRange", values, {2, 40});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("zone 'A' connection 'A_to_B'"),
                                      HasSubstr("PointRange stores 2 x 40 values")));
}

// ---- coordinates against the zone's size ----------------------------------------------------

// The zone's node count sizes the arrays the coordinates are read into: a zone of 2^31 - 1
// nodes whose coordinates store 12 is refused (by the library, when it opens the file) before
// 16 GB are asked for.
TEST(CgnsZones, NodeCountBeyondTheStoredCoordinatesIsRefusedBeforeAllocating) {
  test::TempDir dir;
  const auto file = dir / "huge-zone.cgns";
  test::write_unstructured_2d(file);
  test::overwrite_integers(file, "/Base/Fluid", {INT_MAX, 6, 0}, {1, 3});
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("Invalid coordinates array dimension")));
  EXPECT_LT(largest_allocation_refusing(file), kMegabyte);
}

// ---- nodes declaring more data than the file holds ------------------------------------------

// Found by fuzz_cgns: one digit of the dimension of a BC's type string (BCWall, "00000006") in
// an ADF file changed, and cg_open allocated what it declared (512 MB there; here 2 GB) before
// it found the data missing. Refused before the library opens the file.
TEST(CgnsDeclaredSizes, AdfNodeDeclaringMoreDataThanTheFileHoldsIsRefusedBeforeOpening) {
  test::TempDir dir;
  test::write_unstructured_2d(dir / "u2.cgns");
  const auto file = dir / "u2-adf.cgns";
  const auto converted = test::run_command(std::string(HOTMESH_HDF2ADF) + " " + test::shell_quote((dir / "u2.cgns").string()) +
                                           " " + test::shell_quote(file.string()));
  ASSERT_EQ(converted.exit_code, 0) << converted.output;
  std::string bytes = test::read_text(file);
  // The BC node: "NoDe", its name and label (32 characters each), then the data's type (32)
  // and its dimension count and dimensions, in hexadecimal.
  const std::size_t node = bytes.find("NoDebottom ");
  ASSERT_NE(node, std::string::npos);
  const std::size_t type = bytes.find("C1 ", node);
  ASSERT_NE(type, std::string::npos);
  ASSERT_EQ(bytes.substr(type + 32, 10), "0100000006");
  bytes.replace(type + 34, 8, "7FFFFFFF");
  test::write_text(file, bytes);
  EXPECT_THAT(read_error(file), AllOf(HasSubstr(file.string()), HasSubstr("node /Base/Fluid/ZoneBC/bottom declares "
                                                                          "2147483647 values of type C1"),
                                      HasSubstr("the file is damaged")));
}

// Found by fuzz_cgns: a node's data type in an ADF file followed by other characters than
// spaces, which the CGNS library's node calls copy whole, unterminated, into a caller's buffer
// of 3 (an overflow of hotmesh's buffer while it checked the declared sizes above).
TEST(CgnsDeclaredSizes, AdfDataTypeFollowedByOtherCharactersIsReadSafely) {
  test::TempDir dir;
  test::write_unstructured_2d(dir / "u2.cgns");
  const auto file = dir / "u2-adf.cgns";
  const auto converted = test::run_command(std::string(HOTMESH_HDF2ADF) + " " + test::shell_quote((dir / "u2.cgns").string()) +
                                           " " + test::shell_quote(file.string()));
  ASSERT_EQ(converted.exit_code, 0) << converted.output;
  std::string bytes = test::read_text(file);
  const std::size_t node = bytes.find("NoDebottom ");
  ASSERT_NE(node, std::string::npos);
  const std::size_t type = bytes.find("C1 ", node);
  ASSERT_NE(type, std::string::npos);
  bytes.replace(type + 2, 30, std::string(30, 'X'));
  test::write_text(file, bytes);
  EXPECT_THAT(read_error(file), HasSubstr(file.string()));
}

// Found by fuzz_cgns: an ADF file (6 KB) whose node records make the CGNS library's ADF
// reader ask for 12.9 GB (malloc in ADFI_check_4_child_name, while cg_is_cgns looks for the
// version node), before hotmesh's own checks run. Without a sanitizer the allocation is only
// reserved (58 MB resident) and the file is refused by the declared sizes; under
// AddressSanitizer, whose allocator refuses sizes above 3 GB by ending the process, the child
// process that reads the file first dies and the file is refused all the same.
TEST(CgnsDeclaredSizes, AdfFileOnWhichTheLibraryAsksFor13GbIsRefused) {
  const auto file = test::data_path("fuzz/cgns-adf-children-13gb.cgns");
  EXPECT_THAT(read_error(file), HasSubstr(file.string() + ": "));
}

// Found by fuzz_cgns (seven inputs, one bug): ADF files whose sub-node tables make the CGNS
// library's ADF reader write past a buffer it allocated itself (ADFI_read_sub_node_table,
// from cg_is_cgns and cgio_get_node_id). Under AddressSanitizer the child process that
// reads the file first dies; without it the library may overwrite its heap unseen, or refuse
// the file: the child's refusal is the answer, and hotmesh's own process never runs the
// library on a file the child refused.
TEST(CgnsDeclaredSizes, AdfFileWhoseSubNodeTableOverflowsTheLibrarysBufferIsRefused) {
  const auto file = test::data_path("fuzz/cgns-adf-sub-node-table-overflow.cgns");
  EXPECT_THAT(read_error(file), HasSubstr(file.string() + ": "));
}

}  // namespace
}  // namespace hotmesh::io
