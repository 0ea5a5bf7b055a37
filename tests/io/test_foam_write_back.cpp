// Tests of the OpenFOAM write-back (hotmesh/io/foam.hpp): moved points written in the input's
// form (header kept, ASCII or binary, gzipped again), the other polyMesh files copied byte for
// byte, and --foam-time's time folder in the case.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "foam_fixtures.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using test::foam::block_2x1x1;
using test::foam::Layout;
using test::foam::write_poly_mesh;
using ::testing::HasSubstr;

std::vector<geometry::Vec3> moved(const mesh::Mesh& m) {
  std::vector<geometry::Vec3> points = m.points;
  for (auto& p : points) p = p + geometry::Vec3{0.1 * p.y * p.z, 1.0 / 3.0, -0.25 * p.x};
  return points;
}

TEST(FoamWriteBack, WritesMovedPointsInTheInputsFormAndCopiesTheRest) {
  for (const Layout& layout : {Layout{}, Layout{.binary = true}, Layout{.binary = true, .gzip = true},
                               Layout{.gzip = true, .compact_faces = true}}) {
    test::TempDir dir;
    write_poly_mesh(dir / "in", block_2x1x1(), layout);
    const LoadedMesh loaded = read_mesh(dir / "in");
    const auto points = moved(loaded.mesh);
    const auto written = loaded.write_back->write(dir / "out", points, {});
    EXPECT_EQ(written.size(), 5u);
    const std::string gz = layout.gzip ? ".gz" : "";
    // Read back: the moved points exactly (shortest round-trip text, or raw doubles).
    const LoadedMesh again = read_mesh(dir / "out" / "polyMesh");
    EXPECT_EQ(again.mesh.points, points) << "binary " << layout.binary << " gzip " << layout.gzip;
    EXPECT_EQ(again.mesh.cells, loaded.mesh.cells);
    for (const char* name : {"faces", "owner", "neighbour", "boundary"}) {
      EXPECT_EQ(test::read_text(dir / "out" / "polyMesh" / (name + gz)), test::read_text(dir / "in" / (name + gz)))
          << name;
    }
    // The input is untouched.
    EXPECT_EQ(read_mesh(dir / "in").mesh.points, loaded.mesh.points);
  }
}

TEST(FoamWriteBack, SinglePrecisionPointsAreWrittenAsFloats) {
  test::TempDir dir;
  write_poly_mesh(dir / "in", block_2x1x1(), {.binary = true, .scalar_bits = 32});
  const LoadedMesh loaded = read_mesh(dir / "in");
  const auto points = moved(loaded.mesh);
  loaded.write_back->write(dir / "out", points, {});
  const std::string in = test::read_text(dir / "in" / "points"), out = test::read_text(dir / "out" / "polyMesh" / "points");
  EXPECT_EQ(out.size(), in.size());  // 12 x 3 floats, as the input
  const auto again = read_mesh(dir / "out" / "polyMesh").mesh.points;
  ASSERT_EQ(again.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(again[i].y, static_cast<double>(static_cast<float>(points[i].y)));
  }
}

TEST(FoamWriteBack, UnmovedPointsGiveTheSameFileAndTheHeaderIsKept) {
  test::TempDir dir;
  for (const Layout& layout : {Layout{}, Layout{.binary = true}}) {
    write_poly_mesh(dir / "in", block_2x1x1(), layout);
    const LoadedMesh loaded = read_mesh(dir / "in");
    loaded.write_back->write(dir / "out", loaded.mesh.points, {});
    EXPECT_EQ(test::read_text(dir / "out" / "polyMesh" / "points"), test::read_text(dir / "in" / "points"));
  }
}

TEST(FoamWriteBack, FoamTimeWritesThePointsIntoTheCasesTimeFolder) {
  test::TempDir dir;
  const auto polymesh = dir / "case" / "constant" / "polyMesh";
  write_poly_mesh(polymesh, block_2x1x1());
  const LoadedMesh loaded = read_mesh(dir / "case");
  const auto points = moved(loaded.mesh);
  WriteBackOptions options;
  options.foam_time = "0.5";
  const auto written = loaded.write_back->write(dir / "out", points, options);
  EXPECT_EQ(written.back(), std::filesystem::weakly_canonical(dir / "case") / "0.5" / "polyMesh" / "points");
  const std::string text = test::read_text(dir / "case" / "0.5" / "polyMesh" / "points");
  EXPECT_THAT(text, HasSubstr("location    \"0.5/polyMesh\";"));
  const std::string in_output = test::read_text(dir / "out" / "polyMesh" / "points");
  EXPECT_EQ(in_output.substr(in_output.find("object")), text.substr(text.find("object")));  // the same but its location
  EXPECT_FALSE(std::filesystem::exists(dir / "case" / "0.5" / "polyMesh" / "faces"));
  EXPECT_EQ(foam_time_folder(polymesh, "1e-05"),
            std::filesystem::weakly_canonical(dir / "case") / "1e-05" / "polyMesh");
}

TEST(FoamWriteBack, FoamTimeRefusesNamesThatAreNoTimesAndMeshesOutsideACase) {
  test::TempDir dir;
  write_poly_mesh(dir / "case" / "constant" / "polyMesh", block_2x1x1());
  for (const char* time : {"constant", "../constant", "system", "", "-1", "1/polyMesh", "nan"}) {
    EXPECT_THROW(foam_time_folder(dir / "case", time), InputError) << time;
  }
  write_poly_mesh(dir / "loose" / "polyMesh", block_2x1x1());
  try {
    foam_time_folder(dir / "loose" / "polyMesh", "1");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is not a case's constant/polyMesh"));
  }
}

}  // namespace
}  // namespace hotmesh::io
