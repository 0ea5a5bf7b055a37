// Tests of hotmesh::io::write_vtu: the file is read back by VTK's own XML reader (the one
// ParaView uses, through tests/io/check_vtu.py) and by a minimal parser of the appended
// section, and both must give back exactly the mesh and arrays written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/io/vtu.hpp"
#include "test_support.hpp"
#include "vtk_reader.hpp"

namespace hotmesh::io {
namespace {

using mesh::Mesh;
using geometry::Vec3;

using test::read_with_vtk;

/// A sheared and displaced copy of the points, so coordinates are not trivially the grid.
std::vector<Vec3> moved_points(const Mesh& mesh) {
  std::vector<Vec3> p = mesh.points;
  for (auto& x : p) x = {x.x + 0.25 * x.y + 1e-3, x.y + 1.0 / 3.0, x.z * 2.0};
  return p;
}

VtuFields example_fields(const Mesh& mesh, const std::vector<Vec3>& points) {
  VtuFields f = quality_fields(mesh, points);
  std::vector<double> displacement;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = points[i] - mesh.points[i];
    displacement.insert(displacement.end(), {d.x, d.y, d.z});
  }
  f.point_data.push_back({"displacement", 3, displacement});
  std::vector<std::int32_t> role(points.size());
  for (std::size_t i = 0; i < role.size(); ++i) role[i] = static_cast<std::int32_t>(i % 4);
  f.point_data.push_back({"node_role", 1, role});
  return f;
}

void expect_same_as_vtk_sees(const Mesh& mesh, const std::vector<Vec3>& points, const VtuFields& fields,
                             int vtk_type) {
  test::TempDir dir;
  write_vtu(dir / "m.vtu", mesh, points, fields);
  const nlohmann::json seen = read_with_vtk(dir / "m.vtu");
  ASSERT_FALSE(seen.contains("error"));
  const auto coords = seen["points"].get<std::vector<double>>();
  ASSERT_EQ(coords.size(), 3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(coords[3 * i], points[i].x);
    EXPECT_EQ(coords[3 * i + 1], points[i].y);
    EXPECT_EQ(coords[3 * i + 2], points[i].z);
  }
  ASSERT_EQ(seen["cells"].size(), mesh.cell_count());
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    EXPECT_EQ(seen["cell_types"][c].get<int>(), vtk_type);
    const auto nodes = mesh.cells.nodes(c);
    EXPECT_EQ(seen["cells"][c].get<std::vector<int>>(), std::vector<int>(nodes.begin(), nodes.end()));
  }
  auto check = [](const std::vector<VtuArray>& written, const nlohmann::json& read) {
    ASSERT_EQ(read.size(), written.size());
    for (const VtuArray& a : written) {
      ASSERT_TRUE(read.contains(a.name)) << a.name;
      EXPECT_EQ(read[a.name]["components"].get<int>(), a.components);
      std::visit(
          [&](const auto& v) {
            using T = typename std::decay_t<decltype(v)>::value_type;
            EXPECT_EQ(read[a.name]["values"].get<std::vector<T>>(), v) << a.name;
          },
          a.values);
    }
  };
  check(fields.point_data, seen["point_data"]);
  check(fields.cell_data, seen["cell_data"]);
}

TEST(WriteVtu, VtkReadsBackQuadMeshExactly) {
  const Mesh mesh = test::unit_square(5, 3);
  const auto points = moved_points(mesh);
  expect_same_as_vtk_sees(mesh, points, example_fields(mesh, points), 9);
}

TEST(WriteVtu, VtkReadsBackHexMeshExactly) {
  const Mesh mesh = test::unit_cube(3);
  const auto points = moved_points(mesh);
  expect_same_as_vtk_sees(mesh, points, example_fields(mesh, points), 12);
}

TEST(WriteVtu, QualityFieldsMarkInvertedCellsAndPatchNodes) {
  Mesh mesh = test::unit_square(2, 1);
  std::vector<Vec3> points = mesh.points;
  points[1].x = 1.5;  // node (1,0) pushed beyond node (2,0): the left cell folds
  const VtuFields f = quality_fields(mesh, points);
  const auto& q = std::get<std::vector<double>>(f.cell_data[0].values);
  const auto& inverted = std::get<std::vector<std::uint8_t>>(f.cell_data[1].values);
  EXPECT_GT(q[0], 0.0);
  EXPECT_LT(q[1], 0.0);
  EXPECT_EQ(inverted, (std::vector<std::uint8_t>{0, 1}));
  const auto& patch = std::get<std::vector<std::int32_t>>(f.point_data[0].values);
  EXPECT_EQ(patch[0], 1);  // xmin wins over ymin: first patch listed
  EXPECT_EQ(patch[1], 3);  // ymin
}

TEST(WriteVtu, AppendedSectionHoldsCountedRawBlocks) {
  const Mesh mesh = test::unit_square(1, 1);
  std::ostringstream out;
  write_vtu(out, mesh, mesh.points, {});
  const std::string text = out.str();
  EXPECT_THAT(text, ::testing::HasSubstr(R"(header_type="UInt64")"));
  const auto start = text.find('_', text.find("<AppendedData")) + 1;
  // First block: 4 points x 3 Float64.
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, text.data() + start, sizeof bytes);
  EXPECT_EQ(bytes, 4u * 3u * sizeof(double));
  double x2 = 0;
  std::memcpy(&x2, text.data() + start + 8 + 3 * sizeof(double), sizeof x2);
  EXPECT_EQ(x2, 1.0);
}

TEST(WriteVtu, RejectsArrayOfWrongLength) {
  const Mesh mesh = test::unit_square(2, 2);
  VtuFields f;
  f.point_data.push_back({"displacement", 3, std::vector<double>(5)});
  std::ostringstream out;
  EXPECT_THROW(write_vtu(out, mesh, mesh.points, f), std::invalid_argument);
}

TEST(WriteVtu, WritesAtomicallyLeavingNoTemporaryFile) {
  test::TempDir dir;
  const Mesh mesh = test::unit_square(2, 2);
  write_vtu(dir / "a.vtu", mesh, mesh.points, {});
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename(), "a.vtu");
    ++files;
  }
  EXPECT_EQ(files, 1u);
}

TEST(WriteVtp, VtkReadsBackPolylinesAndPolygonsExactly) {
  PolyData data;
  data.points = {{0, 0, 0}, {1, 0.25, 0}, {2, 1.0 / 3.0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1.5}};
  data.lines = {{0, 1, 2}, {2, 1}};
  data.polygons = {{3, 4, 5, 6}, {3, 4, 5}};
  data.cell_data.push_back({"patch", 1, std::vector<std::int32_t>{7, 8, 9, 10}});
  test::TempDir dir;
  write_vtp(dir / "w.vtp", data);
  const nlohmann::json seen = read_with_vtk(dir / "w.vtp");
  ASSERT_FALSE(seen.contains("error")) << seen.dump();
  const auto coords = seen["points"].get<std::vector<double>>();
  ASSERT_EQ(coords.size(), 3 * data.points.size());
  for (std::size_t i = 0; i < data.points.size(); ++i) {
    EXPECT_EQ(coords[3 * i], data.points[i].x);
    EXPECT_EQ(coords[3 * i + 1], data.points[i].y);
    EXPECT_EQ(coords[3 * i + 2], data.points[i].z);
  }
  // VTK lists a poly data's lines before its polygons, and names each by its point count:
  // VTK_POLY_LINE 4, VTK_LINE 3, VTK_QUAD 9, VTK_TRIANGLE 5.
  EXPECT_EQ(seen["cells"], nlohmann::json::parse("[[0, 1, 2], [2, 1], [3, 4, 5, 6], [3, 4, 5]]"));
  EXPECT_EQ(seen["cell_types"], nlohmann::json::parse("[4, 3, 9, 5]"));
  EXPECT_EQ(seen["cell_data"]["patch"]["values"], nlohmann::json::parse("[7, 8, 9, 10]"));
}

TEST(WriteVtp, RejectsIndexOutOfRangeAndArrayOfWrongLength) {
  PolyData data;
  data.points = {{0, 0, 0}, {1, 0, 0}};
  data.lines = {{0, 2}};
  std::ostringstream out;
  EXPECT_THROW(write_vtp(out, data), std::invalid_argument);
  data.lines = {{0, 1}};
  data.cell_data.push_back({"patch", 1, std::vector<std::int32_t>{1, 2}});
  EXPECT_THROW(write_vtp(out, data), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::io
