// Tests of the BoundaryShape implementations: axisymmetric projection in the meridional plane
// through the point (Fig. 4), planar curves in the x-y plane, and planes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "curve_fixtures.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/interpolation.hpp"

namespace hotmesh::geometry {
namespace {

/// A cylinder of radius 2 about `axis` from z = 0 to z = 4, pushed out radially by 0.1 z / 4.
DeflectedCurve growing_cylinder() {
  const BSplineCurve2d r = BSplineCurve2d::polyline(std::vector<double>{0.0, 1.0}, std::vector<Vec2>{{2, 0}, {2, 4}});
  const std::vector<double> t{0.0, 0.5, 1.0};
  const std::vector<Vec2> d{{0.0, 0.0}, {0.05, 0.0}, {0.1, 0.0}};
  return DeflectedCurve(r, interpolate(t, d, 1), DeflectionForm::displacement);
}

TEST(RevolvedShape, ProjectsInTheMeridionalPlaneKeepingTheAngle) {
  const Axis axis({1, 1, 0}, {0, 0, 1});
  const RevolvedShape shape(growing_cylinder(), axis);
  const double theta = 2.0;
  const Vec3 p = axis.to_cartesian({3.0, theta, 2.0});
  // The deflected surface is a cone: its meridian runs from (2, 0) to (2.1, 4) in (r, z).
  for (const double lambda : {1.0, 0.5}) {
    const Vec2 a{2.0, 0.0};
    const Vec2 u = Vec2{0.1 * lambda, 4.0} / norm(Vec2{0.1 * lambda, 4.0});
    const Vec2 expected = a + dot(Vec2{3.0, 2.0} - a, u) * u;
    const ShapePoint q = shape.project(p, lambda);
    const Cylindrical c = axis.to_cylindrical(q.point);
    EXPECT_NEAR(c.r, expected.x, 1e-14);
    EXPECT_NEAR(c.z, expected.y, 1e-14);
    EXPECT_NEAR(c.theta, theta, 1e-14);
    EXPECT_NEAR(q.distance, distance(expected, Vec2{3.0, 2.0}), 1e-14);
    // The normal lies in the meridional plane, orthogonal to the meridian: left of +z, i.e.
    // towards the axis.
    EXPECT_NEAR(distance(q.normal, axis.meridional_vector(theta, -u.y, u.x)), 0.0, 1e-14);
  }
  // at() places the point at t in the meridional plane of the reference.
  const ShapePoint q = shape.at({.t = 0.5}, 1.0, p);
  EXPECT_NEAR(distance(q.point, axis.to_cartesian({2.05, theta, 2.0})), 0.0, 1e-14);
  EXPECT_EQ(q.parameter.t, 0.5);
}

TEST(RevolvedShape, NormalIsOrthogonalToTheSurfaceOfATorus) {
  // Meridional curve: a quarter circle of radius 0.5 about (r, z) = (3, 0): a torus patch.
  const Axis axis({0, 0, 0}, {1, 1, 1});
  const RevolvedShape shape(DeflectedCurve(test::quarter_circle(0.5, {3.0, 0.0})), axis);
  for (int i = 0; i < 20; ++i) {
    const Vec3 p = axis.to_cartesian({3.0 + 0.7 * std::cos(0.07 * i), 0.3 * i, 0.7 * std::sin(0.07 * i)});
    const ShapePoint q = shape.project(p, 0.0);
    // On a torus the normal passes through the tube's centre circle.
    const Cylindrical c = axis.to_cylindrical(q.point);
    const Vec3 centre = axis.to_cartesian({3.0, c.theta, 0.0});
    EXPECT_NEAR(norm(cross(q.normal, q.point - centre)), 0.0, 1e-12) << i;
    EXPECT_NEAR(distance(q.point, centre), 0.5, 1e-12) << i;
    EXPECT_NEAR(q.distance, 0.2, 1e-12) << i;
  }
}

TEST(PlanarCurveShape, ProjectsInTheXYPlane) {
  const PlanarCurveShape shape{DeflectedCurve(test::quarter_circle(1.0))};
  const ShapePoint q = shape.project({2.0, 2.0, 0.0}, 0.0);
  EXPECT_NEAR(q.point.x, std::sqrt(0.5), 1e-14);
  EXPECT_NEAR(q.point.y, std::sqrt(0.5), 1e-14);
  EXPECT_EQ(q.point.z, 0.0);
  EXPECT_NEAR(q.normal.x, -std::sqrt(0.5), 1e-14);  // left of increasing t (counter-clockwise)
  EXPECT_NEAR(q.parameter.t, 0.5, 1e-14);
  const std::unique_ptr<BoundaryShape> any = std::make_unique<PlanarCurveShape>(DeflectedCurve(test::s_curve()));
  EXPECT_NEAR(any->project({1.0, 1.0, 0.0}, 0.0).distance, test::brute_force_closest(DeflectedCurve(test::s_curve()), {1, 1}, 0.0).distance, 1e-10);
}

TEST(ShapeFactories, BuildDeflectedShapesFromFemSamples) {
  // A cylinder of radius 2 about the z axis through (1, 1, 0), from z = 0 to 4; cartesian FEM
  // nodes at 40 degrees pushed out radially by 0.1.
  const Axis axis({1, 1, 0}, {0, 0, 1});
  const BSplineCurve2d meridian =
      BSplineCurve2d::polyline(std::vector<double>{0.0, 1.0}, std::vector<Vec2>{{2, 0}, {2, 4}});
  DeflectionSamples samples;
  samples.frame = SampleFrame::cartesian;
  for (int j = 0; j <= 4; ++j) {
    samples.points.push_back(axis.to_cartesian({2.0, 0.7, static_cast<double>(j)}));
    samples.deflections.push_back(axis.meridional_vector(0.7, 0.1, 0.0));
  }
  const RevolvedShapeFit fit = make_revolved_shape(meridian, axis, samples);
  EXPECT_EQ(fit.report.used_nodes, 5u);
  const ShapePoint q = fit.shape.project(axis.to_cartesian({3.0, -2.0, 1.5}), 1.0);
  EXPECT_NEAR(axis.to_cylindrical(q.point).r, 2.1, 1e-14);
  EXPECT_NEAR(axis.to_cylindrical(q.point).theta, -2.0, 1e-14);

  DeflectionSamples planar;
  planar.frame = SampleFrame::planar;
  planar.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  planar.deflections = {{0, 0, 0}, {0, 0.1, 0}, {0, 0.2, 0}};
  // The deflected nodes lie on y = 0.1 x (y = 0.05 x half way): projections land on that line
  // and the offset is along its normal (-0.1, 1).
  const PlanarShapeFit from_nodes = make_planar_shape(planar);
  const ShapePoint a = from_nodes.shape.project({1.5, 1.0, 0.0}, 1.0);
  EXPECT_NEAR(a.point.y, 0.1 * a.point.x, 1e-14);
  EXPECT_NEAR(dot(Vec3{1.5, 1.0, 0.0} - a.point, Vec3{1.0, 0.1, 0.0}), 0.0, 1e-14);
  const PlanarShapeFit on_curve = make_planar_shape(
      BSplineCurve2d::polyline(std::vector<double>{0.0, 1.0}, std::vector<Vec2>{{-1, 0}, {3, 0}}), planar);
  const ShapePoint b = on_curve.shape.project({1.5, 1.0, 0.0}, 0.5);
  EXPECT_NEAR(b.point.y, 0.05 * b.point.x, 1e-14);
  EXPECT_NEAR(dot(Vec3{1.5, 1.0, 0.0} - b.point, Vec3{1.0, 0.05, 0.0}), 0.0, 1e-14);
  EXPECT_NEAR(on_curve.shape.project({-0.5, 1.0, 0.0}, 1.0).point.y, 0.0, 1e-14);  // before the nodes
  EXPECT_THROW(make_planar_shape(samples), InputError);                            // cartesian for 2D
}

TEST(PlaneShape, ProjectsOrthogonallyWhateverTheStage) {
  const PlaneShape plane({0, 0, 1}, {0, 0, 2});
  for (const double lambda : {0.0, 0.5, 1.0}) {
    const ShapePoint q = plane.project({3, 4, 5}, lambda);
    EXPECT_EQ(q.point, (Vec3{3, 4, 1}));
    EXPECT_EQ(q.normal, (Vec3{0, 0, 1}));
    EXPECT_EQ(q.distance, 4.0);
  }
  EXPECT_THROW(PlaneShape({0, 0, 0}, {0, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::geometry
