// Tests of Figure and mesh pictures: PNG files decode to the expected pixels, SVG files are
// SVG, and a mesh picture fills cells with their quality colour.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cairo.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <new>
#include <string>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/figure.hpp"
#include "hotmesh/io/mesh_picture.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

struct Pixel {
  int r, g, b;
};

/// Decodes a PNG with Cairo and returns the colour at (x, y).
Pixel pixel_at(const std::filesystem::path& png, int x, int y, int* width = nullptr, int* height = nullptr) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  if (width) *width = cairo_image_surface_get_width(s);
  if (height) *height = cairo_image_surface_get_height(s);
  cairo_surface_flush(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  std::uint32_t argb = 0;
  std::memcpy(&argb, data + y * stride + 4 * x, 4);
  cairo_surface_destroy(s);
  return {static_cast<int>((argb >> 16) & 0xff), static_cast<int>((argb >> 8) & 0xff), static_cast<int>(argb & 0xff)};
}

TEST(Figure, PngShowsFilledPolygonWhereItWasDrawn) {
  test::TempDir dir;
  Figure figure({.width = 400, .height = 300, .axes = false});
  const std::array<PlotPoint, 4> square{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  figure.polygon(square, colors::red);
  figure.set_view(-1, 2, -1, 2);  // the square takes the middle third
  figure.save(dir / "f.png");
  int w = 0, h = 0;
  const Pixel centre = pixel_at(dir / "f.png", 80 + (400 - 110) / 2, 50 + (300 - 110) / 2, &w, &h);
  EXPECT_EQ(w, 400);
  EXPECT_EQ(h, 300);
  EXPECT_GT(centre.r, 200);
  EXPECT_LT(centre.g, 60);
  const Pixel corner = pixel_at(dir / "f.png", 90, 60);  // inside the plot area, outside the square
  EXPECT_EQ(corner.r, 255);
  EXPECT_EQ(corner.g, 255);
}

TEST(Figure, SvgIsAnSvgDocumentWithTheTitle) {
  test::TempDir dir;
  Figure figure({.title = "deflected curve"});
  const std::array<PlotPoint, 2> line{{{0, 0}, {1, 2}}};
  figure.polyline(line, {colors::blue, 2.0});
  figure.legend("reconstructed", {colors::blue, 2.0});
  figure.save(dir / "f.svg");
  const std::string svg = test::read_text(dir / "f.svg");
  EXPECT_THAT(svg, ::testing::HasSubstr("<svg"));
  EXPECT_THAT(svg, ::testing::HasSubstr("</svg>"));
}

TEST(Figure, RejectsUnknownPictureFormat) {
  test::TempDir dir;
  EXPECT_THROW(Figure().save(dir / "f.jpg"), InputError);
}

/// The size of this process's address space (VmSize), in bytes.
std::uint64_t address_space_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmSize:", 0) == 0) return std::stoull(line.substr(7)) * 1024;
  }
  return 0;
}

TEST(Figure, OutOfMemoryForThePictureIsOutOfMemoryNotBadInput) {
  // Issue 18: `hotmesh deform` under a memory limit ended with "deformed.png: cannot render the
  // picture: out of memory" and exit code 2, which blames the input. In a child process with
  // 32 MB of address space to spare, a picture of 4000 x 4000 pixels (64 MB) cannot be drawn.
  if (test::under_sanitizers()) GTEST_SKIP() << "AddressSanitizer ends the process when malloc fails";
  test::TempDir dir;
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const rlimit limit{address_space_bytes() + (32u << 20), RLIM_INFINITY};
    ::setrlimit(RLIMIT_AS, &limit);
    int code = 1;
    try {
      Figure({.width = 4000, .height = 4000}).save(dir / "big.png");
      code = 0;
    } catch (const std::bad_alloc&) {
      code = 4;
    } catch (const InputError&) {
      code = 2;
    } catch (...) {
    }
    ::_exit(code);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 4) << "0: drawn, 2: InputError, 1: another exception";
  EXPECT_FALSE(std::filesystem::exists(dir / "big.png"));
}

TEST(Colormap, RunsFromBlueToRedAndClamps) {
  EXPECT_GT(colormap(0.0).b, colormap(0.0).r);
  EXPECT_GT(colormap(1.0).r, colormap(1.0).b);
  EXPECT_EQ(colormap(-3.0).b, colormap(0.0).b);
  EXPECT_EQ(colormap(7.0).r, colormap(1.0).r);
}

TEST(MeshPicture, InvertedCellIsDrawnDarkRed) {
  test::TempDir dir;
  const mesh::Mesh mesh = test::unit_square(2, 1);
  std::vector<geometry::Vec3> points = mesh.points;
  points[1].x = 1.5;  // the middle line moves past the right wall: the right cell is inverted
  points[4].x = 1.5;
  const auto quality = mesh::scaled_jacobians(mesh.cells, points);
  ASSERT_GT(quality[0], 0.0);
  ASSERT_LT(quality[1], 0.0);
  Figure figure({.width = 400, .height = 300, .axes = false});
  draw_mesh(figure, mesh, points, {.edges = {colors::black, 0.5}, .quality = quality});
  figure.set_view(0, 2, 0, 1);
  figure.save(dir / "m.png");
  // World to pixel: scale 145 px per unit, x = 1 at px 225, y = 0.5 at py 145.
  const Pixel inverted = pixel_at(dir / "m.png", 225 + 36, 145);  // x = 1.25: inside the inverted cell
  EXPECT_EQ(inverted.r, 115);
  EXPECT_EQ(inverted.g, 0);
  const Pixel valid = pixel_at(dir / "m.png", 225 - 109, 145);  // x = 0.25: only the valid cell
  EXPECT_NE(valid.r, 115);
  EXPECT_NE(valid.r, 255);  // filled, not background
}

}  // namespace
}  // namespace hotmesh::io
