// Tests of hotmesh::io::parse_deflection_csv / read_deflection_csv: the three column sets in
// any order, ids, comments, CRLF; every kind of malformed table gives an InputError naming
// the source, the line and (where there is one) the column.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using geometry::SampleFrame;
using geometry::Vec3;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string csv_error(std::string_view text) {
  try {
    parse_deflection_csv(text, "table.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DeflectionCsv, ReadsPlanarTable) {
  const auto s = parse_deflection_csv("x,y,dx,dy\n0,0,0.1,0.2\n1,0.5,-1e-3,+2\n", "ramp.csv");
  EXPECT_EQ(s.frame, SampleFrame::planar);
  EXPECT_THAT(s.points, ElementsAre(Vec3{0, 0, 0}, Vec3{1, 0.5, 0}));
  EXPECT_THAT(s.deflections, ElementsAre(Vec3{0.1, 0.2, 0}, Vec3{-1e-3, 2, 0}));
  EXPECT_THAT(s.lines, ElementsAre(2u, 3u));
  EXPECT_TRUE(s.ids.empty());
  EXPECT_EQ(s.source, "ramp.csv");
  EXPECT_EQ(s.size(), 2u);
}

TEST(DeflectionCsv, ReadsCartesianColumnsInAnyOrderAndCase) {
  const auto s = parse_deflection_csv(" dz , X,dy,z ,Y,DX\n6,1,5,3,2,4\n", "t.csv");
  EXPECT_EQ(s.frame, SampleFrame::cartesian);
  EXPECT_THAT(s.points, ElementsAre(Vec3{1, 2, 3}));
  EXPECT_THAT(s.deflections, ElementsAre(Vec3{4, 5, 6}));
}

TEST(DeflectionCsv, ReadsMeridionalTableAsRZ) {
  const auto s = parse_deflection_csv("z,dr,r,dz\n0.5,0.01,0.2,-0.02\n0.6,0,0,0\n", "t.csv");
  EXPECT_EQ(s.frame, SampleFrame::meridional);
  EXPECT_THAT(s.points, ElementsAre(Vec3{0.2, 0.5, 0}, Vec3{0, 0.6, 0}));
  EXPECT_THAT(s.deflections, ElementsAre(Vec3{0.01, -0.02, 0}, Vec3{0, 0, 0}));
}

TEST(DeflectionCsv, ReadsIdColumnAnywhere) {
  const auto s = parse_deflection_csv("x,id,y,dx,dy\n0,17,0,0,0\n1,+4,0,0,0\n2,-3,0,0,0\n", "t.csv");
  EXPECT_THAT(s.ids, ElementsAre(17, 4, -3));
  EXPECT_THAT(s.points, ElementsAre(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{2, 0, 0}));
}

TEST(DeflectionCsv, SkipsCommentsAndBlankLines) {
  const std::string text =
      "# exported by the FEM code\n"
      "\n"
      "   # header follows\n"
      "x, y, dx, dy   # columns\n"
      "  \t\n"
      "1, 2, 3, 4  # node A\n"
      "# between rows\n"
      "5,6,7,8\n";
  const auto s = parse_deflection_csv(text, "t.csv");
  EXPECT_THAT(s.points, ElementsAre(Vec3{1, 2, 0}, Vec3{5, 6, 0}));
  EXPECT_THAT(s.deflections, ElementsAre(Vec3{3, 4, 0}, Vec3{7, 8, 0}));
  EXPECT_THAT(s.lines, ElementsAre(6u, 8u));
}

TEST(DeflectionCsv, AcceptsCrlfLineEndingsAndByteOrderMark) {
  const auto s = parse_deflection_csv("\xEF\xBB\xBFr,z,dr,dz\r\n# c\r\n1,2,3,4\r\n5,6,7,8", "t.csv");
  EXPECT_EQ(s.frame, SampleFrame::meridional);
  EXPECT_THAT(s.points, ElementsAre(Vec3{1, 2, 0}, Vec3{5, 6, 0}));
  EXPECT_THAT(s.lines, ElementsAre(3u, 4u));
}

TEST(DeflectionCsv, ReadsNumberFormatsOfFemCodes) {
  const auto s = parse_deflection_csv("x,y,dx,dy\n1.5E+02,.25,-2.e-3,1e-400\n", "t.csv");
  EXPECT_THAT(s.points, ElementsAre(Vec3{150, 0.25, 0}));
  EXPECT_THAT(s.deflections, ElementsAre(Vec3{-2e-3, 0, 0}));  // 1e-400 underflows to 0
}

TEST(DeflectionCsv, RejectsEmptyOrCommentOnlyTable) {
  EXPECT_THAT(csv_error(""), StartsWith("table.csv: no header line"));
  EXPECT_THAT(csv_error("# nothing here\n\n"), StartsWith("table.csv: no header line"));
}

TEST(DeflectionCsv, RejectsHeaderWithoutRows) {
  EXPECT_EQ(csv_error("# c\nx,y,dx,dy\n# no rows\n"), "table.csv:2: the table has a header but no data rows");
}

TEST(DeflectionCsv, RejectsValuesWhereHeaderBelongs) {
  EXPECT_THAT(csv_error("0,0,1,1\n"), StartsWith("table.csv:1: the first line that is not a comment holds values"));
}

TEST(DeflectionCsv, RejectsUnknownColumn) {
  EXPECT_THAT(csv_error("#\nx,y,dx,Dq\n0,0,0,0\n"), StartsWith("table.csv:2: unknown column 'Dq'; expected x,y,dx,dy"));
}

TEST(DeflectionCsv, RejectsEmptyColumnName) {
  EXPECT_THAT(csv_error("x,y,,dx,dy\n"), StartsWith("table.csv:1: empty column name"));
}

TEST(DeflectionCsv, RejectsDuplicateColumn) {
  EXPECT_EQ(csv_error("x,y,X,dx,dy\n0,0,0,0,0\n"), "table.csv:1: column 'x' appears twice in the header");
}

TEST(DeflectionCsv, RejectsMissingColumnNamingTheSet) {
  EXPECT_EQ(csv_error("x,y,z,dx,dy\n"),
            "table.csv:1: missing column 'dz': a cartesian (x, y, z) table has columns x,y,z,dx,dy,dz "
            "(plus an optional id)");
  EXPECT_THAT(csv_error("id,r,z\n"), StartsWith("table.csv:1: missing columns 'dr,dz': a meridional (r, z) table"));
  EXPECT_THAT(csv_error("x,y,dx\n"), StartsWith("table.csv:1: missing column 'dy': a planar (x, y) table"));
  EXPECT_THAT(csv_error("id,z,dz\n"), StartsWith("table.csv:1: the header has no coordinate columns"));
}

TEST(DeflectionCsv, RejectsMixedColumnSets) {
  EXPECT_THAT(csv_error("x,y,dr,dz\n1,2,3,4\n"),
              StartsWith("table.csv:1: the header mixes column sets: 'dr' is meridional (r,z,dr,dz) but 'x' is not"));
  EXPECT_THAT(csv_error("r,z,dx,dz\n"), HasSubstr("'r' is meridional (r,z,dr,dz) but 'dx' is not"));
}

TEST(DeflectionCsv, RejectsWrongFieldCount) {
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,0,0,0\n1,2,3\n"), "table.csv:3: the row has 3 fields, the header 4 (x,y,dx,dy)");
  EXPECT_THAT(csv_error("x,y,dx,dy\n0,0,0,0,\n"), StartsWith("table.csv:2: the row has 5 fields"));
  // A decimal comma shows up as extra fields.
  EXPECT_THAT(csv_error("x,y,dx,dy\n0,5,0,0,0,1\n"), StartsWith("table.csv:2: the row has 6 fields"));
}

TEST(DeflectionCsv, RejectsNonNumericValueNamingColumn) {
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,0,0,abc\n"), "table.csv:2: 'abc' in column 'dy' is not a number");
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,1.5.2,0,0\n"), "table.csv:2: '1.5.2' in column 'y' is not a number");
  EXPECT_EQ(csv_error("x,y,dx,dy\n0x10,0,0,0\n"), "table.csv:2: '0x10' in column 'x' is not a number");
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,,0,0\n"), "table.csv:2: empty value in column 'y'");
}

TEST(DeflectionCsv, RejectsNanAndInfinity) {
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,0,nan,0\n"), "table.csv:2: 'nan' in column 'dx' is not a finite number");
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,0,0,-inf\n"), "table.csv:2: '-inf' in column 'dy' is not a finite number");
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,1e999,0,0\n"), "table.csv:2: '1e999' in column 'y' is not a finite number");
}

// Issue 18, item 8: values double precision cannot move a mesh with are named as such.
TEST(DeflectionCsv, RejectsValuesBeyondTheSupportedRange) {
  EXPECT_EQ(csv_error("x,y,dx,dy\n0,0,0,0\n1e155,0,0,0\n"),
            "table.csv:3: '1e155' in column 'x' is beyond 1e30, the largest coordinate hotmesh moves meshes at; is "
            "the table in another unit?");
}

TEST(DeflectionCsv, RejectsNegativeRadius) {
  EXPECT_EQ(csv_error("r,z,dr,dz\n0,0,0,0\n-0.5,1,0,0\n"),
            "table.csv:3: negative radius -0.5 in column 'r'; r is a distance from the axis, r >= 0");
  EXPECT_NO_THROW(parse_deflection_csv("r,z,dr,dz\n0,0,-0.5,0\n", "t.csv"));  // dr may be negative
}

TEST(DeflectionCsv, RejectsBadAndDuplicateIds) {
  EXPECT_EQ(csv_error("id,x,y,dx,dy\n7,0,0,0,0\n8,1,0,0,0\n7,2,0,0,0\n"), "table.csv:4: duplicate id 7 (first on line 2)");
  EXPECT_EQ(csv_error("id,x,y,dx,dy\n7.5,0,0,0,0\n"), "table.csv:2: '7.5' in column 'id' is not an integer node number");
}

TEST(DeflectionCsv, ReadFileNamesFileInSamplesAndErrors) {
  test::TempDir dir;
  const auto good = dir / "good.csv";
  test::write_text(good, "x,y,dx,dy\n0,0,1,1\n");
  EXPECT_EQ(read_deflection_csv(good).source, good.string());
  const auto bad = dir / "bad.csv";
  test::write_text(bad, "x,y,dx,dy\n0,0,1\n");
  try {
    read_deflection_csv(bad);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), StartsWith(bad.string() + ":2: the row has 3 fields"));
  }
  EXPECT_THROW(read_deflection_csv(dir / "missing.csv"), InputError);
}

}  // namespace
}  // namespace hotmesh::io
