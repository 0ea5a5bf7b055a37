// Tests of wall_deviation against walls on CAD faces (SurfaceShape), the two-sided distance
// between a mesh patch's faces (quads as bilinear patches, triangles) and a stage of the faces:
// walls that sample a bilinear or planar face exactly, chords of a cylinder (the sagitta both
// ways, refined between samples), a wall raised off its face, a wall covering an L-shaped part
// of its face (the rest not counted), a raised node and a bump of the deflected face (their
// heights and where), and many faces against brute force (the box tree).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "hotmesh/geometry/surface_shape.hpp"
#include "hotmesh/geometry/wall_deviation.hpp"

namespace hotmesh::geometry {
namespace {

/// A face of degree 1 x 1 over [0, 4] x [0, 1] through four corner poles (u-major).
BSplineSurface bilinear_face(const Vec3& p00, const Vec3& p01, const Vec3& p10, const Vec3& p11) {
  return BSplineSurface(1, 1, {0, 0, 4, 4}, {0, 0, 1, 1}, {p00, p01, p10, p11});
}

SurfaceShape shape_of(const BSplineSurface& face, const BSplineSurface& field) {
  return SurfaceShape({{1, face}}, {field});
}

/// A structured wall: nodes at place(i, j) for 0 <= i <= nx, 0 <= j <= ny; quads (or each
/// quad split into two triangles) over the cells that `keep(i, j)` accepts.
struct Wall {
  std::vector<Vec3> points;
  WallFaces faces;
  int nx = 0, ny = 0;
  std::int32_t node(int i, int j) const { return static_cast<std::int32_t>(i * (ny + 1) + j); }
};

Wall grid_wall(int nx, int ny, const std::function<Vec3(int, int)>& place, bool triangles = false,
               const std::function<bool(int, int)>& keep = {}) {
  Wall w;
  w.nx = nx;
  w.ny = ny;
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) w.points.push_back(place(i, j));
  }
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      if (keep && !keep(i, j)) continue;
      const std::int32_t a = w.node(i, j), b = w.node(i + 1, j), c = w.node(i + 1, j + 1), d = w.node(i, j + 1);
      if (triangles) {
        const std::int32_t t1[3] = {a, b, c}, t2[3] = {a, c, d};
        w.faces.add(t1);
        w.faces.add(t2);
      } else {
        const std::int32_t quad[4] = {a, b, c, d};
        w.faces.add(quad);
      }
    }
  }
  return w;
}

// A twisted bilinear face S(x, y) = (x, y, 0.2 x y) deflected by a bilinear field: stage 0.5 is
// bilinear too, so quads through its points on a parameter grid are exactly on it, both ways.
// Triangles on a planar face likewise.
TEST(SurfaceWallDeviation, AWallSamplingItsFaceExactlyIsOnItBothWays) {
  const BSplineSurface face = bilinear_face({0, 0, 0}, {0, 1, 0}, {4, 0, 0}, {4, 1, 0.8});
  const BSplineSurface field(1, 1, {0, 0, 4, 4}, {0, 0, 1, 1}, {{0.1, 0, 0.05}, {0, 0.02, -0.1}, {0, 0, 0.2}, {-0.1, 0, 0}});
  const SurfaceShape shape = shape_of(face, field);
  const double lambda = 0.5;
  const Wall quads = grid_wall(16, 4, [&](int i, int j) {
    const double x = 0.25 * i, y = 0.25 * j;
    return face.point(x, y) + lambda * field.point(x, y);
  });
  const WallDeviation w = wall_deviation(shape, quads.points, quads.faces, {.lambda = lambda});
  EXPECT_EQ(w.faces, 64u);
  EXPECT_EQ(w.edges, 0u);
  EXPECT_LT(w.mesh_to_shape.distance, 1e-10);
  EXPECT_LT(w.shape_to_mesh.distance, 1e-10);
  EXPECT_LT(w.hausdorff, 1e-10);
  EXPECT_GE(w.shape_samples, 16u * 64u);  // about 1/0.25^2 per face
  // The same wall against the undeformed stage is off it.
  EXPECT_GT(wall_deviation(shape, quads.points, quads.faces, {.lambda = 0.0}).hausdorff, 0.05);

  const BSplineSurface plane = bilinear_face({0, 0, 0}, {0, 1, 0.5}, {4, 0, 1}, {4, 1, 1.5});
  const auto undeformed = undeformed_surface_shape({{1, plane}});
  const SurfaceShape& flat = *undeformed;
  const Wall triangles = grid_wall(
      10, 3, [&](int i, int j) { return plane.point(0.4 * i, j / 3.0); }, true);
  const WallDeviation t = wall_deviation(flat, triangles.points, triangles.faces);
  EXPECT_EQ(t.faces, 60u);
  EXPECT_LT(t.hausdorff, 1e-10);
}

/// A quarter of the cylinder x^2 + z^2 = R^2, 0 <= y <= 1: rational quadratic in u (the arc from
/// (R, 0, 0) to (0, 0, R)), linear in v.
BSplineSurface quarter_cylinder(double radius) {
  const double w = std::sqrt(0.5);
  return BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1},
                        {{radius, 0, 0}, {radius, 1, 0}, {radius, 0, radius}, {radius, 1, radius}, {0, 0, radius},
                         {0, 1, radius}},
                        {1, 1, w, w, 1, 1});
}

// Flat quads whose nodes lie on a cylinder: each chord across the angle is off the cylinder by
// the sagitta R (1 - cos(step / 2)) at its middle, both ways. Sampled at a third of each face
// (face_samples 3), the middle is between samples: the refinement finds it.
TEST(SurfaceWallDeviation, ChordsOfACylinderAreASagittaOffBothWays) {
  const double radius = 2.0, step = std::numbers::pi / 2.0 / 6.0;
  const BSplineSurface cylinder = quarter_cylinder(radius);
  const auto undeformed = undeformed_surface_shape({{1, cylinder}});
  const SurfaceShape& shape = *undeformed;
  const Wall wall = grid_wall(6, 3, [&](int i, int j) {
    return Vec3{radius * std::cos(i * step), j / 3.0, radius * std::sin(i * step)};
  });
  const WallDeviation w = wall_deviation(shape, wall.points, wall.faces, {.face_samples = 3});
  const double sagitta = radius * (1.0 - std::cos(step / 2.0));
  EXPECT_NEAR(w.mesh_to_shape.distance, sagitta, 1e-9);
  EXPECT_NEAR(w.shape_to_mesh.distance, sagitta, 1e-9);
  // Reached at the middle of a chord, whose nearest point is the arc's middle above it.
  EXPECT_NEAR(std::hypot(w.mesh_to_shape.point.x, w.mesh_to_shape.point.z), radius * std::cos(step / 2.0), 1e-9);
  EXPECT_NEAR(std::hypot(w.mesh_to_shape.nearest.x, w.mesh_to_shape.nearest.z), radius, 1e-9);
  EXPECT_EQ(w.mesh_to_shape.shape_face, 0);
  EXPECT_GE(w.mesh_to_shape.face, 0);
  EXPECT_LT(w.mesh_to_shape.face, 18);
  EXPECT_EQ(w.mesh_to_shape.edge, (std::array<std::int32_t, 2>{-1, -1}));
  EXPECT_NEAR(std::hypot(w.shape_to_mesh.point.x, w.shape_to_mesh.point.z), radius, 1e-9);
  // Far fewer refined than sampled would not show here; the values would: 1/3 of a chord off its
  // middle, the sagitta is 8/9 of its maximum.
}

// A wall raised by 0.01 along the normal of its planar face is 0.01 off it both ways.
TEST(SurfaceWallDeviation, AWallRaisedOffItsFaceIsOffByTheOffsetBothWays) {
  const BSplineSurface plane = bilinear_face({0, 0, 0}, {0, 1, 0.5}, {4, 0, 1}, {4, 1, 1.5});
  const auto undeformed = undeformed_surface_shape({{1, plane}});
  const SurfaceShape& shape = *undeformed;
  const Vec3 normal = cross(Vec3{4, 0, 1}, Vec3{0, 1, 0.5}) / norm(cross(Vec3{4, 0, 1}, Vec3{0, 1, 0.5}));
  const double offset = 0.01;
  for (const bool triangles : {false, true}) {
    const Wall wall = grid_wall(
        12, 5, [&](int i, int j) { return plane.point(i / 3.0, 0.2 * j) + offset * normal; }, triangles);
    const WallDeviation w = wall_deviation(shape, wall.points, wall.faces);
    EXPECT_NEAR(w.mesh_to_shape.distance, offset, 1e-12) << triangles;
    EXPECT_NEAR(w.shape_to_mesh.distance, offset, 1e-12) << triangles;
    EXPECT_NEAR(w.hausdorff, offset, 1e-12) << triangles;
  }
}

// The wall covers an L of the face [0, 4] x [0, 1] (all but x > 2, y > 0.5), the rectangle of
// its projections being the whole face: the face's uncovered quarter is left out (its samples'
// nearest points are on the wall's rim), so the wall is on the face both ways. Counted, that
// corner would be about 1.1 from the wall.
TEST(SurfaceWallDeviation, OnlyThePartOfTheFaceTheWallCoversCounts) {
  const BSplineSurface face = bilinear_face({0, 0, 0}, {0, 1, 0}, {4, 0, 0}, {4, 1, 0.8});
  const auto undeformed = undeformed_surface_shape({{1, face}});
  const SurfaceShape& shape = *undeformed;
  const Wall wall = grid_wall(
      16, 4, [&](int i, int j) { return face.point(0.25 * i, 0.25 * j); }, false,
      [](int i, int j) { return i < 8 || j < 2; });
  const WallDeviation w = wall_deviation(shape, wall.points, wall.faces);
  EXPECT_EQ(w.faces, 48u);
  EXPECT_LT(w.hausdorff, 1e-10);
  // Every sample of the quarter x > 2, y > 0.5, and those on the L's outline, left out.
  EXPECT_GT(w.uncovered_samples, w.shape_samples / 5);
  EXPECT_LT(w.uncovered_samples, w.shape_samples / 2);

  // A wall covering a strip in the middle of the face: the rectangle of its projections.
  const Wall strip = grid_wall(6, 2, [&](int i, int j) { return face.point(1.0 + 0.25 * i, 0.25 + 0.25 * j); });
  EXPECT_LT(wall_deviation(shape, strip.points, strip.faces).hausdorff, 1e-10);
}

// One node of a wall on a flat face raised by 0.03: the wall is 0.03 off the face there, at
// that node, in a face holding it; the face below it is nearer to the raised faces.
TEST(SurfaceWallDeviation, ARaisedNodeIsTheWallsLargestDistanceAndNamed) {
  const BSplineSurface face = bilinear_face({0, 0, 0}, {0, 1, 0}, {4, 0, 0}, {4, 1, 0});
  const auto undeformed = undeformed_surface_shape({{1, face}});
  const SurfaceShape& shape = *undeformed;
  Wall wall = grid_wall(16, 4, [&](int i, int j) { return Vec3{0.25 * i, 0.25 * j, 0.0}; });
  const std::int32_t raised = wall.node(7, 2);
  wall.points[static_cast<std::size_t>(raised)].z = 0.03;
  const WallDeviation w = wall_deviation(shape, wall.points, wall.faces);
  EXPECT_NEAR(w.mesh_to_shape.distance, 0.03, 1e-12);
  EXPECT_EQ(w.worst, WallDirection::mesh_to_shape);
  EXPECT_DOUBLE_EQ(w.hausdorff, w.mesh_to_shape.distance);
  EXPECT_LT(distance(w.mesh_to_shape.point, Vec3{1.75, 0.5, 0.03}), 1e-12);
  EXPECT_LT(distance(w.mesh_to_shape.nearest, Vec3{1.75, 0.5, 0.0}), 1e-9);
  EXPECT_NEAR(w.mesh_to_shape.parameter, 1.75, 1e-9);
  EXPECT_NEAR(w.mesh_to_shape.parameter_s, 0.5, 1e-9);
  const auto corners = wall.faces.corners(static_cast<std::size_t>(w.mesh_to_shape.face));
  EXPECT_NE(std::find(corners.begin(), corners.end(), raised), corners.end());
  EXPECT_GT(w.shape_to_mesh.distance, 0.01);
  EXPECT_LT(w.shape_to_mesh.distance, 0.03);
}

// The deflected face has a bump the flat wall does not follow: a quadratic B-spline field with
// one pole of height H lifts the face by 9/16 H at the middle of that pole's support, (1.65,
// 0.45), between the face's samples. The face is that far from the wall there.
TEST(SurfaceWallDeviation, ABumpOfTheFaceTheWallMissesIsFoundWhereItIs) {
  const BSplineSurface face = bilinear_face({0, 0, 0}, {0, 1, 0}, {4, 0, 0}, {4, 1, 0});
  const double pole = 0.04;
  std::vector<Vec3> poles(6 * 6, Vec3{0, 0, 0});
  poles[2 * 6 + 2] = {0, 0, pole};  // N_2(t) N_2(s): knots 0, 1.1, 2.2, 3.3 and 0, 0.3, 0.6, 0.9
  const BSplineSurface field(2, 2, {0, 0, 0, 1.1, 2.2, 3.3, 4, 4, 4}, {0, 0, 0, 0.3, 0.6, 0.9, 1, 1, 1}, poles);
  const SurfaceShape shape = shape_of(face, field);
  const Wall wall = grid_wall(16, 4, [&](int i, int j) { return Vec3{0.25 * i, 0.25 * j, 0.0}; });
  const WallDeviation w = wall_deviation(shape, wall.points, wall.faces);
  const double height = 9.0 / 16.0 * pole;
  EXPECT_NEAR(w.shape_to_mesh.distance, height, 1e-10);
  EXPECT_EQ(w.worst, WallDirection::shape_to_mesh);
  EXPECT_NEAR(w.shape_to_mesh.parameter, 1.65, 1e-4);
  EXPECT_NEAR(w.shape_to_mesh.parameter_s, 0.45, 1e-4);
  EXPECT_EQ(w.shape_to_mesh.shape_face, 0);
  EXPECT_LT(distance(w.shape_to_mesh.point, Vec3{1.65, 0.45, height}), 1e-4);
  EXPECT_LT(distance(w.shape_to_mesh.nearest, Vec3{1.65, 0.45, 0.0}), 1e-4);
  const auto corners = wall.faces.corners(static_cast<std::size_t>(w.shape_to_mesh.face));
  const Vec3& corner = wall.points[static_cast<std::size_t>(corners[0])];  // the face under (1.65, 0.45)
  EXPECT_DOUBLE_EQ(corner.x, 1.5);
  EXPECT_DOUBLE_EQ(corner.y, 0.25);
  EXPECT_LT(w.mesh_to_shape.distance, height);
  // At stage 0 the face is flat: the wall is on it.
  EXPECT_LT(wall_deviation(shape, wall.points, wall.faces, {.lambda = 0.0}).hausdorff, 1e-12);
}

// A wall of 30 x 30 quads on a wavy face, its nodes pushed off it by a fixed pseudo-random
// pattern of up to 0.01: the measure agrees with brute force, dense points of each quad (8 x 8)
// standing for the wall: each side's maximum is no lower than the brute force's (less its
// sampling), and the distance reported on the face side is that of its point to the wall.
TEST(SurfaceWallDeviation, ManyFacesAgreeWithBruteForce) {
  std::vector<Vec3> wave;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) wave.push_back({i / 5.0, j / 5.0, 0.1 * std::sin(1.3 * i + 0.7 * j)});
  }
  const BSplineSurface face(3, 3, {0, 0, 0, 0, 0.33, 0.67, 1, 1, 1, 1}, {0, 0, 0, 0, 0.33, 0.67, 1, 1, 1, 1}, wave);
  const auto undeformed = undeformed_surface_shape({{1, face}});
  const SurfaceShape& shape = *undeformed;
  const int n = 30;
  unsigned state = 12345u;
  const Wall wall = grid_wall(n, n, [&](int i, int j) {
    state = state * 1103515245u + 12345u;
    const double push = 1e-2 * (static_cast<double>((state >> 8) % 2001) / 1000.0 - 1.0);
    return face.point(static_cast<double>(i) / n, static_cast<double>(j) / n) + Vec3{0, 0, push};
  });
  const WallDeviation w = wall_deviation(shape, wall.points, wall.faces);

  std::vector<Vec3> dense;  // of the wall
  double spacing = 0.0;     // the largest distance between neighbouring dense points
  for (std::size_t f = 0; f < wall.faces.size(); ++f) {
    const auto c = wall.faces.corners(f);
    const auto p = [&](int k) { return wall.points[static_cast<std::size_t>(c[static_cast<std::size_t>(k)])]; };
    const auto at = [&](double a, double b) {
      return (1 - a) * (1 - b) * p(0) + a * (1 - b) * p(1) + a * b * p(2) + (1 - a) * b * p(3);
    };
    for (int i = 0; i <= 8; ++i) {
      for (int j = 0; j <= 8; ++j) {
        dense.push_back(at(i / 8.0, j / 8.0));
        if (i > 0 && j > 0) spacing = std::max(spacing, distance(at(i / 8.0, j / 8.0), at((i - 1) / 8.0, (j - 1) / 8.0)));
      }
    }
  }
  const auto to_wall = [&](const Vec3& x) {
    double nearest = 1e300;
    for (const Vec3& y : dense) nearest = std::min(nearest, distance(x, y));
    return nearest;
  };
  double wall_to_face = 0.0;
  for (const Vec3& x : dense) wall_to_face = std::max(wall_to_face, shape.project(x, 1.0).distance);
  double face_to_wall = 0.0;  // inside the wall's outline, away from its rim
  for (int i = 0; i <= 60; ++i) {
    for (int j = 0; j <= 60; ++j) face_to_wall = std::max(face_to_wall, to_wall(face.point(0.1 + 0.8 * i / 60, 0.1 + 0.8 * j / 60)));
  }
  EXPECT_GE(w.mesh_to_shape.distance, wall_to_face - 1e-9);
  EXPECT_LE(w.mesh_to_shape.distance, wall_to_face + spacing);
  EXPECT_GE(w.shape_to_mesh.distance, face_to_wall - spacing);
  const double at_point = to_wall(w.shape_to_mesh.point);
  EXPECT_GE(at_point, w.shape_to_mesh.distance - 1e-12);
  EXPECT_LE(at_point, w.shape_to_mesh.distance + spacing);
  EXPECT_LT(distance(w.shape_to_mesh.point, face.point(w.shape_to_mesh.parameter, w.shape_to_mesh.parameter_s)), 1e-12);
  EXPECT_GT(w.hausdorff, 5e-3);
}

TEST(SurfaceWallDeviation, NoFacesNothingMeasuredAndBadFacesRefused) {
  const BSplineSurface face = bilinear_face({0, 0, 0}, {0, 1, 0}, {4, 0, 0}, {4, 1, 0});
  const auto undeformed = undeformed_surface_shape({{1, face}});
  const SurfaceShape& shape = *undeformed;
  const WallDeviation none = wall_deviation(shape, {}, WallFaces{});
  EXPECT_EQ(none.faces, 0u);
  EXPECT_EQ(none.hausdorff, 0.0);
  const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  WallFaces edge;
  const std::int32_t two[2] = {0, 1};
  edge.add(two);
  EXPECT_THROW(wall_deviation(shape, points, edge), std::invalid_argument);
  WallFaces outside;
  const std::int32_t three[3] = {0, 1, 7};
  outside.add(three);
  EXPECT_THROW(wall_deviation(shape, points, outside), std::invalid_argument);
  WallFaces triangle;
  const std::int32_t good[3] = {0, 1, 2};
  triangle.add(good);
  EXPECT_THROW(wall_deviation(shape, points, triangle, {.face_samples = 0}), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::geometry
