// Tests of wall_deviation, the two-sided distance between a discrete wall and its curve: the
// sagitta of chords inscribed in an arc, a corner cut by a chord (both sides known in closed
// form, the wall's maximum between samples), a wall lying on a piecewise linear curve, a wall
// covering part of its curve, a ring of quads about an axis measured in the meridional plane,
// and a wall of many edges against brute force (the grid search).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "curve_fixtures.hpp"
#include "hotmesh/geometry/wall_deviation.hpp"

namespace hotmesh::geometry {
namespace {

CurveProjector polyline_curve(const std::vector<Vec2>& points) {
  std::vector<double> t;
  for (std::size_t i = 0; i < points.size(); ++i) t.push_back(static_cast<double>(i));
  return CurveProjector(DeflectedCurve(BSplineCurve2d::polyline(t, points)));
}

/// The wall through `nodes` in order, as 2-node faces (a 2D patch's edges).
WallFaces chain(std::size_t nodes) {
  WallFaces faces;
  for (std::size_t i = 0; i + 1 < nodes; ++i) {
    const std::int32_t edge[2] = {static_cast<std::int32_t>(i), static_cast<std::int32_t>(i + 1)};
    faces.add(edge);
  }
  return faces;
}

std::vector<Vec3> points_of(const std::vector<Vec2>& xy) {
  std::vector<Vec3> points;
  for (const Vec2& p : xy) points.push_back({p.x, p.y, 0.0});
  return points;
}

TEST(WallDeviation, ChordsInscribedInAnArcAreASagittaOffBothWays) {
  const double radius = 2.0, step = std::numbers::pi / 2.0 / 6.0;  // six chords of 15 degrees
  const CurveProjector arc{DeflectedCurve(test::quarter_circle(radius))};
  std::vector<Vec3> points;
  for (int k = 0; k <= 6; ++k) points.push_back({radius * std::cos(k * step), radius * std::sin(k * step), 0.0});
  const WallDeviation w = wall_deviation(arc, points, chain(points.size()));
  const double sagitta = radius * (1.0 - std::cos(step / 2.0));
  EXPECT_EQ(w.edges, 6u);
  EXPECT_NEAR(w.mesh_to_shape.distance, sagitta, 1e-10);
  EXPECT_NEAR(w.shape_to_mesh.distance, sagitta, 1e-10);
  EXPECT_NEAR(w.hausdorff, sagitta, 1e-10);
  // Reached at a chord's middle, whose nearest curve point is the arc's middle above it.
  EXPECT_NEAR(norm(w.mesh_to_shape.point), radius * std::cos(step / 2.0), 1e-10);
  EXPECT_NEAR(norm(w.mesh_to_shape.nearest), radius, 1e-12);
  EXPECT_EQ(w.mesh_to_shape.edge[1], w.mesh_to_shape.edge[0] + 1);
  EXPECT_NEAR(w.first_parameter, 0.0, 1e-12);
  EXPECT_NEAR(w.last_parameter, 1.0, 1e-12);
  // The node distance this replaces: zero.
  for (const Vec3& p : points) EXPECT_LT(arc.project({p.x, p.y}, 1.0).distance, 1e-12);
}

TEST(WallDeviation, ACornerWithoutANodeIsCutByAChord) {
  // The curve turns by 90 degrees at the origin; the wall's chord joins (0, a) to (b, 0).
  const double a = 0.3, b = 0.13;
  const CurveProjector corner = polyline_curve({{0, 1}, {0, 0}, {1, 0}});
  const std::vector<Vec3> points = points_of({{0, 1}, {0, a}, {b, 0}, {1, 0}});
  const WallDeviation w = wall_deviation(corner, points, chain(points.size()));
  // The corner is the curve's farthest point from the chord: a b / sqrt(a^2 + b^2).
  EXPECT_NEAR(w.shape_to_mesh.distance, a * b / std::hypot(a, b), 1e-12);
  EXPECT_NEAR(distance(w.shape_to_mesh.point, Vec3{0, 0, 0}), 0.0, 1e-12);
  EXPECT_NEAR(w.shape_to_mesh.parameter, 1.0, 1e-12);
  EXPECT_EQ(w.shape_to_mesh.edge, (std::array<std::int32_t, 2>{1, 2}));
  // On the chord (s b, (1 - s) a) the distance is min(x, y): largest, a b / (a + b), where the
  // two are equal, at s = a / (a + b) = 0.698, between two samples (a kink: refined).
  EXPECT_NEAR(w.mesh_to_shape.distance, a * b / (a + b), 1e-8);
  EXPECT_NEAR(w.mesh_to_shape.point.x, a * b / (a + b), 1e-7);
  EXPECT_NEAR(w.mesh_to_shape.point.y, a * b / (a + b), 1e-7);
  EXPECT_EQ(w.worst, WallDirection::shape_to_mesh);
  EXPECT_DOUBLE_EQ(w.hausdorff, w.shape_to_mesh.distance);
  EXPECT_STREQ(to_string(w.worst), "shape_to_mesh");
}

TEST(WallDeviation, AWallOnAPiecewiseLinearCurveIsOnIt) {
  const std::vector<Vec2> kinks{{0, 0}, {1, 0}, {1.5, 0.8}, {2.5, 0.8}, {3, 0}};
  const CurveProjector curve = polyline_curve(kinks);
  // A node on every kink and two more on each side between them.
  std::vector<Vec2> nodes;
  for (std::size_t i = 0; i + 1 < kinks.size(); ++i) {
    for (const double s : {0.0, 0.3, 0.65}) nodes.push_back(kinks[i] + s * (kinks[i + 1] - kinks[i]));
  }
  nodes.push_back(kinks.back());
  const WallDeviation w = wall_deviation(curve, points_of(nodes), chain(nodes.size()));
  EXPECT_EQ(w.edges, nodes.size() - 1);
  EXPECT_LT(w.hausdorff, 1e-14);
  EXPECT_NEAR(w.first_parameter, 0.0, 1e-12);
  EXPECT_NEAR(w.last_parameter, 4.0, 1e-12);
  EXPECT_GT(w.shape_samples, 4u * 8u);  // at least every kink and eight per edge

  // Without the node on the kink (1.5, 0.8) the wall cuts it.
  std::vector<Vec2> cut = nodes;
  cut.erase(cut.begin() + 6);
  const WallDeviation c = wall_deviation(curve, points_of(cut), chain(cut.size()));
  EXPECT_GT(c.shape_to_mesh.distance, 0.05);
  EXPECT_NEAR(distance(c.shape_to_mesh.point, Vec3{1.5, 0.8, 0}), 0.0, 1e-12);
}

TEST(WallDeviation, OnlyThePartOfTheCurveTheWallCoversCounts) {
  // The curve goes on beyond the wall's last node and turns up there: not the wall's business.
  const CurveProjector curve = polyline_curve({{0, 0}, {1, 0}, {2, 0}, {2, 1}});
  const std::vector<Vec3> points = points_of({{0, 0}, {0.5, 0}, {1, 0}, {1.5, 0}});
  const WallDeviation w = wall_deviation(curve, points, chain(points.size()));
  EXPECT_LT(w.hausdorff, 1e-15);
  EXPECT_NEAR(w.first_parameter, 0.0, 1e-12);
  EXPECT_NEAR(w.last_parameter, 1.5, 1e-12);
  // The same wall on a curve that stays on its line up to x = 1.5 but turns away at x = 1:
  // counted, from the corner to the wall's end.
  const CurveProjector bent = polyline_curve({{0, 0}, {1, 0}, {1.5, 0.5}, {2, 1}});
  const WallDeviation b = wall_deviation(bent, points, chain(points.size()));
  EXPECT_GT(b.shape_to_mesh.distance, 0.1);
}

TEST(WallDeviation, ARingOfQuadsIsMeasuredInTheMeridionalPlane) {
  // An annular floor (z = 0, 0.5 < r < 1) meeting a cylinder (r = 1, 0 < z < 1) at a right
  // angle, about a tilted axis off the origin; the wall has no node on the corner (1, 0): its
  // meridional chord from (0.8, 0) to (1, 0.2) cuts it. A 30-degree sector, quads 10 degrees
  // wide, whose chords across theta lie inside the cylinder (not counted).
  const Axis axis({1, 2, 3}, {0, 1, 1});
  const CurveProjector meridian = polyline_curve({{0.5, 0}, {1, 0}, {1, 1}});
  const std::vector<Vec2> rz{{0.5, 0}, {0.8, 0}, {1, 0.2}, {1, 0.6}, {1, 1}};
  const int sectors = 3;
  std::vector<Vec3> points;
  for (int k = 0; k <= sectors; ++k) {
    for (const Vec2& q : rz) points.push_back(axis.to_cartesian({q.x, k * std::numbers::pi / 18.0, q.y}));
  }
  const auto node = [&](int k, std::size_t m) { return static_cast<std::int32_t>(static_cast<std::size_t>(k) * rz.size() + m); };
  WallFaces faces;
  for (int k = 0; k < sectors; ++k) {
    for (std::size_t m = 0; m + 1 < rz.size(); ++m) {
      const std::int32_t quad[4] = {node(k, m), node(k, m + 1), node(k + 1, m + 1), node(k + 1, m)};
      faces.add(quad);
    }
  }
  const WallDeviation w = wall_deviation(meridian, points, faces, {.axis = axis});
  // Distinct edges: 4 meridional per theta line (4 lines), 5 across theta per strip (3 strips).
  EXPECT_EQ(w.edges, 4u * 4u + 5u * 3u);
  EXPECT_NEAR(w.shape_to_mesh.distance, 0.2 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(w.mesh_to_shape.distance, 0.1, 1e-8);
  const Cylindrical corner = axis.to_cylindrical(w.shape_to_mesh.point);
  EXPECT_NEAR(corner.r, 1.0, 1e-12);
  EXPECT_NEAR(corner.z, 0.0, 1e-12);
  EXPECT_GE(corner.theta, -1e-12);
  EXPECT_LE(corner.theta, std::numbers::pi / 6.0 + 1e-12);
  const Cylindrical chord = axis.to_cylindrical(w.shape_to_mesh.nearest);
  EXPECT_NEAR(chord.r, 0.9, 1e-12);
  EXPECT_NEAR(chord.z, 0.1, 1e-12);
  EXPECT_NEAR(chord.theta, corner.theta, 1e-12);  // in the same meridional plane
}

TEST(WallDeviation, ManyEdgesAgreeWithBruteForce) {
  // 1000 chords of a circle of radius 1 whose nodes are pushed off it by up to 1e-3 (a fixed
  // pseudo-random pattern): the grid search must find what trying every edge finds.
  const int n = 1000;
  std::vector<Vec2> circle;  // closed polyline curve through 4000 points of the circle
  for (int k = 0; k <= 4000; ++k) {
    circle.push_back({std::cos(2.0 * std::numbers::pi * k / 4000), std::sin(2.0 * std::numbers::pi * k / 4000)});
  }
  const CurveProjector curve = polyline_curve(circle);
  std::vector<Vec3> points;
  unsigned state = 12345u;
  for (int k = 0; k <= n; ++k) {
    state = state * 1103515245u + 12345u;
    const double r = 1.0 + 1e-3 * (static_cast<double>((state >> 8) % 2001) / 1000.0 - 1.0);
    const double angle = 2.0 * std::numbers::pi * (k % n) / n;
    points.push_back({r * std::cos(angle), r * std::sin(angle), 0.0});
  }
  const WallDeviation w = wall_deviation(curve, points, chain(points.size()));

  double wall_to_curve = 0.0, curve_to_wall = 0.0;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j <= 64; ++j) {
      const Vec3 p = points[static_cast<std::size_t>(k)] + (j / 64.0) * (points[static_cast<std::size_t>(k) + 1] - points[static_cast<std::size_t>(k)]);
      wall_to_curve = std::max(wall_to_curve, curve.project({p.x, p.y}, 1.0).distance);
    }
  }
  std::vector<Vec2> dense;  // the curve: 16 points per piece (the distance peaks between vertices too)
  for (std::size_t i = 0; i + 1 < circle.size(); ++i) {
    for (int j = 0; j < 16; ++j) dense.push_back(circle[i] + (j / 16.0) * (circle[i + 1] - circle[i]));
  }
  for (const Vec2& c : dense) {
    double nearest = 1e300;
    for (int k = 0; k < n; ++k) {
      const Vec3& a = points[static_cast<std::size_t>(k)];
      const Vec3& b = points[static_cast<std::size_t>(k) + 1];
      const Vec2 d{b.x - a.x, b.y - a.y}, pa{c.x - a.x, c.y - a.y};
      const double s = std::clamp(dot(pa, d) / dot(d, d), 0.0, 1.0);
      nearest = std::min(nearest, norm(pa - s * d));
    }
    curve_to_wall = std::max(curve_to_wall, nearest);
  }
  // The brute force samples: the true maxima are at most half its spacing above its values
  // (distances are 1-Lipschitz), and never below them.
  const double chord = 2.0 * std::numbers::pi / n, piece = 2.0 * std::numbers::pi / 4000;
  EXPECT_GE(w.mesh_to_shape.distance, wall_to_curve - 1e-12);
  EXPECT_LE(w.mesh_to_shape.distance, wall_to_curve + 0.5 * chord / 64);
  EXPECT_GE(w.shape_to_mesh.distance, curve_to_wall - 1e-12);
  EXPECT_LE(w.shape_to_mesh.distance, curve_to_wall + 0.5 * piece / 16);
  EXPECT_GT(w.hausdorff, 5e-4);  // about the largest push
}

TEST(WallDeviation, NoFacesNothingMeasuredAndBadCornersRefused) {
  const CurveProjector curve = polyline_curve({{0, 0}, {1, 0}});
  const WallDeviation none = wall_deviation(curve, {}, WallFaces{});
  EXPECT_EQ(none.edges, 0u);
  EXPECT_EQ(none.hausdorff, 0.0);
  WallFaces faces;
  const std::int32_t edge[2] = {0, 5};
  faces.add(edge);
  const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(wall_deviation(curve, points, faces), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::geometry
