// Tests of SurfaceProjector: points land at the analytic closest point of planes, cylinders and
// spheres given as rational B-splines (OpenCASCADE conversions), at OpenCASCADE's projection on a
// wavy patch, on the rectangle's edge (and corner) when beyond it, on the right one of two
// patches that share an edge; warm starts agree with cold ones; a deformed patch S + d gives an
// orthogonal residual; poles are reported and get their limit normal.
#include <gtest/gtest.h>

#include <GeomAPI_ProjectPointOnSurf.hxx>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <thread>

#include "hotmesh/geometry/surface_projector.hpp"
#include "occt_surfaces.hpp"

namespace hotmesh::geometry {
namespace {

struct Frame {
  Vec3 origin, x, y, z;
};

Vec3 vec(const gp_XYZ& v) { return {v.X(), v.Y(), v.Z()}; }

Frame test_frame() {
  const gp_Ax3 a = test::test_frame();
  return {vec(a.Location().XYZ()), vec(a.XDirection().XYZ()), vec(a.YDirection().XYZ()), vec(a.Direction().XYZ())};
}

SurfaceProjector projector_of(const Handle(Geom_BSplineSurface)& s) {
  return SurfaceProjector({bspline_patch(test::from_occt(s))});
}

/// The smallest distance from p to the patches sampled on an n x n grid each: no projection
/// may be farther than that.
double sampled_distance(const SurfaceProjector& projector, const Vec3& p, int n = 150) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < projector.patch_count(); ++k) {
    const SurfacePatch& patch = projector.patch(k);
    const ParameterRectangle& r = patch.domain;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        const double u = r.u_first + (r.u_last - r.u_first) * i / n;
        const double v = r.v_first + (r.v_last - r.v_first) * j / n;
        best = std::min(best, distance(patch.evaluate(u, v).point, p));
      }
    }
  }
  return best;
}

/// The projection's point is the patch's point at its parameters, and its normal is a unit
/// vector orthogonal to S_u and S_v.
void expect_consistent(const SurfaceProjector& projector, const SurfaceProjection& q) {
  ASSERT_GE(q.where.patch, 0);
  const SurfaceDerivatives d = projector.patch(static_cast<std::size_t>(q.where.patch)).evaluate(q.where.u, q.where.v);
  EXPECT_LE(distance(q.point, d.point), 1e-14 * projector.length_scale());
  EXPECT_NEAR(norm(q.normal), 1.0, 1e-12);
  if (norm(cross(d.du, d.dv)) > 1e-6 * norm(d.du) * norm(d.dv)) {
    EXPECT_NEAR(dot(q.normal, d.du) / norm(d.du), 0.0, 1e-12);
    EXPECT_NEAR(dot(q.normal, d.dv) / norm(d.dv), 0.0, 1e-12);
  }
}

TEST(SurfaceProjector, PlaneGivesTheOrthogonalFoot) {
  const Frame f = test_frame();
  const SurfaceProjector projector = projector_of(test::occt_plane());
  EXPECT_TRUE(projector.degeneracies().empty());
  const double scale = projector.length_scale();
  for (const double a : {-0.9, 0.0, 0.7, 1.9}) {
    for (const double b : {-0.4, 0.3, 1.4}) {
      for (const double c : {-3.0, -0.2, 0.0, 1e-4, 0.8}) {
        const Vec3 foot = f.origin + a * f.x + b * f.y;
        const SurfaceProjection q = projector.project(foot + c * f.z);
        EXPECT_LE(distance(q.point, foot), 1e-9 * scale) << a << " " << b << " " << c;
        EXPECT_NEAR(q.distance, std::abs(c), 1e-9 * scale);
        EXPECT_NEAR(std::abs(dot(q.normal, f.z)), 1.0, 1e-12);
        EXPECT_FALSE(q.on_boundary);
        expect_consistent(projector, q);
      }
    }
  }
}

TEST(SurfaceProjector, CylinderGivesTheAnalyticFoot) {
  const Frame f = test_frame();
  const double radius = 2.0;
  const SurfaceProjector projector = projector_of(test::occt_cylinder());
  EXPECT_TRUE(projector.degeneracies().empty());
  const double scale = projector.length_scale();
  for (const double angle : {0.25, 1.0, 1.7, 2.75}) {
    for (const double height : {-0.9, 0.4, 2.9}) {
      for (const double r : {0.3, 1.0, 1.99, 2.0, 2.3, 4.0}) {
        const Vec3 radial = std::cos(angle) * f.x + std::sin(angle) * f.y;
        const Vec3 axis_point = f.origin + height * f.z;
        const SurfaceProjection q = projector.project(axis_point + r * radial);
        EXPECT_LE(distance(q.point, axis_point + radius * radial), 1e-9 * scale) << angle << " " << height << " " << r;
        EXPECT_NEAR(q.distance, std::abs(radius - r), 1e-9 * scale);
        EXPECT_NEAR(std::abs(dot(q.normal, radial)), 1.0, 1e-12);
        expect_consistent(projector, q);
      }
    }
  }
}

TEST(SurfaceProjector, SphereGivesTheAnalyticFootAndReportsItsPoles) {
  const Frame f = test_frame();
  const double radius = 1.5;
  const SurfaceProjector projector = projector_of(test::occt_sphere());
  const double scale = projector.length_scale();
  // Latitude runs from pole to pole: both v edges collapse to a point and lose their normal.
  const DegeneracyReport& report = projector.degeneracies();
  ASSERT_EQ(report.edges.size(), 2u) << report.describe();
  EXPECT_EQ(report.edges[0].edge, PatchEdge::v_first);
  EXPECT_EQ(report.edges[1].edge, PatchEdge::v_last);
  EXPECT_TRUE(report.edges[0].collapsed && report.edges[1].collapsed);
  EXPECT_TRUE(report.points.empty());
  EXPECT_NE(report.describe().find("pole"), std::string::npos);
  for (const double longitude : {0.1, 1.3, 2.5, 4.4}) {
    for (const double latitude : {-1.5, -0.7, 0.0, 0.4, 1.2, 1.5699}) {
      for (const double r : {0.2, 1.0, 1.5, 1.51, 2.5}) {
        const Vec3 direction = std::cos(latitude) * (std::cos(longitude) * f.x + std::sin(longitude) * f.y) +
                               std::sin(latitude) * f.z;
        const SurfaceProjection q = projector.project(f.origin + r * direction);
        EXPECT_LE(distance(q.point, f.origin + radius * direction), 1e-9 * scale)
            << longitude << " " << latitude << " " << r;
        EXPECT_NEAR(std::abs(dot(q.normal, direction)), 1.0, 1e-9);
        expect_consistent(projector, q);
      }
    }
  }
  // Above a pole: the foot is the pole, on the collapsed edge, with the limit normal.
  for (const double side : {-1.0, 1.0}) {
    const SurfaceProjection q = projector.project(f.origin + side * 2.0 * f.z);
    EXPECT_LE(distance(q.point, f.origin + side * radius * f.z), 1e-9 * scale);
    EXPECT_TRUE(q.on_boundary);
    EXPECT_NEAR(std::abs(dot(q.normal, f.z)), 1.0, 1e-12);
    // The same normal as just off the pole, on the same side of the surface.
    const SurfaceProjection off = projector.at({0, q.where.u, q.where.v - side * 1e-4});
    EXPECT_GT(dot(q.normal, off.normal), 1.0 - 1e-6);
  }
}

TEST(SurfaceProjector, WavyPatchMatchesOpenCascade) {
  const Handle(Geom_BSplineSurface) occt = test::occt_wavy();
  const SurfaceProjector projector = projector_of(occt);
  const double scale = projector.length_scale();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int interior = 0;
  for (int k = 0; k < 200; ++k) {
    const SurfaceProjection base = projector.at({0, 0.05 + 1.9 * unit(random), 1.05 + 0.9 * unit(random)});
    const Vec3 p = base.point + (0.6 * unit(random) - 0.3) * base.normal +
                   Vec3{0.1 * unit(random) - 0.05, 0.1 * unit(random) - 0.05, 0.0};
    const SurfaceProjection q = projector.project(p);
    expect_consistent(projector, q);
    EXPECT_LE(q.distance, sampled_distance(projector, p, 60) + 1e-12 * scale);
    GeomAPI_ProjectPointOnSurf reference(gp_Pnt(p.x, p.y, p.z), occt);
    if (reference.NbPoints() == 0) continue;
    double u = 0.0, v = 0.0;
    reference.LowerDistanceParameters(u, v);
    // OpenCASCADE's extrema are critical points inside the patch: compare where it found one.
    const bool inside = u > 1e-6 && u < 2.0 - 1e-6 && v > 1.0 + 1e-6 && v < 2.0 - 1e-6;
    EXPECT_LE(q.distance, reference.LowerDistance() + 1e-12 * scale);
    if (!inside || q.on_boundary) continue;
    ++interior;
    EXPECT_LE(distance(q.point, vec(reference.NearestPoint().XYZ())), 1e-9 * scale);
    EXPECT_NEAR(q.distance, reference.LowerDistance(), 1e-10 * scale);
  }
  EXPECT_GT(interior, 130);
}

TEST(SurfaceProjector, PointsBeyondTheRectangleLandOnItsEdge) {
  const Frame f = test_frame();
  const double radius = 2.0;
  const SurfaceProjector projector = projector_of(test::occt_cylinder());
  const double scale = projector.length_scale();
  const auto radial = [&](double angle) { return std::cos(angle) * f.x + std::sin(angle) * f.y; };
  // Beyond the straight edge at angle 2.8: the foot is on that line, at the point's height.
  for (const double height : {-0.5, 1.0, 2.5}) {
    const Vec3 p = f.origin + height * f.z + 2.3 * radial(3.2);
    const SurfaceProjection q = projector.project(p);
    EXPECT_LE(distance(q.point, f.origin + height * f.z + radius * radial(2.8)), 1e-9 * scale);
    EXPECT_TRUE(q.on_boundary);
    EXPECT_EQ(q.where.u, projector.patch(0).domain.u_last);
  }
  // Above the circular edge at height 3: the foot is on the arc (a 1D problem along it).
  for (const double angle : {0.5, 1.5, 2.6}) {
    const Vec3 p = f.origin + 3.4 * f.z + 2.6 * radial(angle);
    const SurfaceProjection q = projector.project(p);
    EXPECT_LE(distance(q.point, f.origin + 3.0 * f.z + radius * radial(angle)), 1e-9 * scale) << angle;
    EXPECT_TRUE(q.on_boundary);
    EXPECT_EQ(q.where.v, projector.patch(0).domain.v_last);
  }
  // Beyond a corner: the corner.
  const SurfaceProjection q = projector.project(f.origin - 1.5 * f.z + 2.5 * radial(-0.3));
  EXPECT_LE(distance(q.point, f.origin - 1.0 * f.z + radius * radial(0.2)), 1e-9 * scale);
  EXPECT_TRUE(q.on_boundary);
}

/// The wavy patch cut at u = 1.1 (a knot) into two patches that share that edge.
std::vector<SurfacePatch> two_halves() {
  Handle(Geom_BSplineSurface) left = test::occt_wavy();
  Handle(Geom_BSplineSurface) right = test::occt_wavy();
  left->Segment(0.0, 1.1, 1.0, 2.0);
  right->Segment(1.1, 2.0, 1.0, 2.0);
  return {bspline_patch(test::from_occt(left)), bspline_patch(test::from_occt(right))};
}

TEST(SurfaceProjector, TwoPatchesSharingAnEdge) {
  const SurfaceProjector whole = projector_of(test::occt_wavy());
  const SurfaceProjector halves(two_halves());
  const double scale = whole.length_scale();
  for (const double u : {1.0, 1.09, 1.0999, 1.1001, 1.11, 1.2}) {
    for (const double v : {1.1, 1.5, 1.9}) {
      for (const double t : {-0.05, 0.0, 0.02}) {
        const SurfaceProjection on = whole.at({0, u, v});
        const Vec3 p = on.point + t * on.normal;
        const SurfaceProjection q = halves.project(p);
        EXPECT_EQ(q.where.patch, u < 1.1 ? 0 : 1) << u << " " << v << " " << t;
        EXPECT_LE(distance(q.point, on.point), 1e-9 * scale);
        EXPECT_FALSE(q.on_boundary);
      }
    }
  }
  // On the shared edge both patches give the same point; the hint's patch wins the tie.
  for (const double v : {1.05, 1.5, 1.95}) {
    const SurfaceProjection on = whole.at({0, 1.1, v});
    const Vec3 p = on.point + 0.01 * on.normal;
    const SurfaceProjection cold = halves.project(p);
    const SurfaceProjection from_left = halves.project(p, {0, 1.05, v});
    const SurfaceProjection from_right = halves.project(p, {1, 1.15, v});
    EXPECT_EQ(cold.where.patch, 0);
    EXPECT_EQ(from_left.where.patch, 0);
    EXPECT_EQ(from_right.where.patch, 1);
    for (const SurfaceProjection& q : {cold, from_left, from_right}) {
      EXPECT_LE(distance(q.point, on.point), 1e-9 * scale);
      EXPECT_TRUE(q.on_boundary);
    }
    EXPECT_NEAR(from_left.where.u, 1.1, 1e-12);
    EXPECT_NEAR(from_right.where.u, 1.1, 1e-12);
    EXPECT_GT(dot(from_left.normal, from_right.normal), 1.0 - 1e-9);
  }
  // A hint on the wrong patch: the point has moved over the edge onto the other one.
  const SurfaceProjection on = whole.at({0, 1.3, 1.4});
  const SurfaceProjection q = halves.project(on.point + 0.01 * on.normal, {0, 1.0, 1.4});
  EXPECT_EQ(q.where.patch, 1);
  EXPECT_LE(distance(q.point, on.point), 1e-9 * scale);
  EXPECT_FALSE(q.from_hint);
}

TEST(SurfaceProjector, WarmStartsAgreeWithColdOnes) {
  std::vector<SurfacePatch> patches = two_halves();
  patches.push_back(bspline_patch(test::from_occt(test::occt_sphere())));
  const SurfaceProjector projector(std::move(patches));
  const double scale = projector.length_scale();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int from_hint = 0;
  for (int k = 0; k < 240; ++k) {
    const int patch = k % 3;
    const ParameterRectangle& r = projector.patch(static_cast<std::size_t>(patch)).domain;
    const double u = r.u_first + (r.u_last - r.u_first) * (0.5 + 0.49 * unit(random));
    const double v = r.v_first + (r.v_last - r.v_first) * (0.5 + 0.49 * unit(random));
    const SurfaceProjection base = projector.at({patch, u, v});
    const Vec3 p = base.point + 0.01 * unit(random) * base.normal;
    const SurfaceProjection before = projector.project(p);
    // A small move, as between two Newton steps of the mesh motion.
    const Vec3 moved = p + 0.003 * Vec3{unit(random), unit(random), unit(random)};
    const SurfaceProjection cold = projector.project(moved);
    const SurfaceProjection warm = projector.project(moved, before.where);
    EXPECT_LE(distance(warm.point, cold.point), 1e-9 * scale) << k;
    EXPECT_NEAR(warm.distance, cold.distance, 1e-12 * scale);
    EXPECT_LE(cold.distance, sampled_distance(projector, moved, 40) + 1e-12 * scale);
    from_hint += warm.from_hint ? 1 : 0;
  }
  EXPECT_GT(from_hint, 200);  // mostly the warm start's own answer
}

/// One patch folded like a hairpin: sheets z = 0 and z = gap for x in [0, 10], joined by a U-turn
/// at x ~ 10 (quadratic in u, knots 0.45, 0.5, 0.55), y in [0, 2] linear in v.
BSplineSurface hairpin_sheet(double gap) {
  const std::vector<std::pair<double, double>> xz{{0, 0}, {10, 0}, {10 + gap, 0}, {10 + gap, gap}, {10, gap}, {0, gap}};
  std::vector<Vec3> poles;
  for (const auto& [x, z] : xz) {
    for (const double y : {0.0, 2.0}) poles.push_back({x, y, z});
  }
  return BSplineSurface(2, 1, {0, 0, 0, 0.45, 0.5, 0.55, 1, 1, 1}, {0, 0, 1, 1}, std::move(poles));
}

TEST(SurfaceProjector, WarmStartOnTheFarSheetOfAFoldFindsTheNearOne) {
  const SurfaceProjector checked({bspline_patch(hairpin_sheet(0.1))});
  SurfaceProjectorOptions options;
  options.verify_warm_starts = false;
  const SurfaceProjector unchecked({bspline_patch(hairpin_sheet(0.1))}, options);
  for (const double x : {1.0, 5.0, 9.0}) {
    // 0.03 above the lower sheet, 0.07 below the upper one; the hint on the upper sheet.
    const Vec3 p{x, 1.0, 0.03};
    const SurfaceProjection on_upper = checked.project({x, 1.0, 0.2});
    ASSERT_NEAR(on_upper.point.z, 0.1, 1e-12);
    for (const SurfaceProjection& q : {checked.project(p), checked.project(p, on_upper.where)}) {
      EXPECT_NEAR(q.distance, 0.03, 1e-12) << x;
      EXPECT_NEAR(q.point.z, 0.0, 1e-12);
    }
    // Unchecked, the warm start keeps the upper sheet's local minimum: the documented trade-off.
    const SurfaceProjection fast = unchecked.project(p, on_upper.where);
    EXPECT_NEAR(fast.distance, 0.07, 1e-12);
    EXPECT_TRUE(fast.from_hint);
  }
}

/// A smooth displacement field over [0, 2] x [1, 2] (the wavy patch's rectangle): bicubic, its
/// own knots, vector poles.
BSplineSurface bulge_field() {
  std::vector<Vec3> poles;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 5; ++j) {
      poles.push_back({0.02 * std::sin(1.1 * i + j), -0.03 * std::cos(0.8 * j), 0.1 * std::sin(0.9 * i) * std::sin(0.7 * j + 0.3)});
    }
  }
  return BSplineSurface(3, 3, {0, 0, 0, 0, 0.8, 1.3, 2, 2, 2, 2}, {1, 1, 1, 1, 1.5, 2, 2, 2, 2}, std::move(poles));
}

TEST(SurfaceProjector, DeformedPatchHasAnOrthogonalResidual) {
  const BSplineSurface face = test::from_occt(test::occt_wavy());
  const BSplineSurface field = bulge_field();
  const SurfaceProjector projector({displaced_patch(face, field)});
  const double scale = projector.length_scale();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 120; ++k) {
    const Vec3 p = face.point(0.1 + 1.8 * unit(random), 1.05 + 0.9 * unit(random)) +
                   Vec3{0.1 * unit(random) - 0.05, 0.1 * unit(random) - 0.05, 0.4 * unit(random) - 0.2};
    const SurfaceProjection q = projector.project(p);
    ASSERT_EQ(q.where.patch, 0);
    // The point is S + d at the parameters, evaluated independently.
    EXPECT_LE(distance(q.point, face.point(q.where.u, q.where.v) + field.point(q.where.u, q.where.v)), 1e-13 * scale);
    EXPECT_LE(q.distance, sampled_distance(projector, p, 60) + 1e-12 * scale);
    if (q.on_boundary) continue;
    const SurfaceDerivatives s = face.derivatives(q.where.u, q.where.v);
    const SurfaceDerivatives d = field.derivatives(q.where.u, q.where.v);
    const Vec3 residual = q.point - p;
    if (norm(residual) < 1e-6 * scale) continue;
    EXPECT_LE(std::abs(dot(residual, s.du + d.du)) / (norm(residual) * norm(s.du + d.du)), 1e-9);
    EXPECT_LE(std::abs(dot(residual, s.dv + d.dv)) / (norm(residual) * norm(s.dv + d.dv)), 1e-9);
  }
  // Half the displacement is another surface: S + d/2.
  const SurfaceProjector half({displaced_patch(face, field, 0.5)});
  const SurfaceProjection q = half.at({0, 0.7, 1.3});
  EXPECT_LE(distance(q.point, face.point(0.7, 1.3) + 0.5 * field.point(0.7, 1.3)), 1e-14 * scale);
}

TEST(SurfaceProjector, RejectsBadInput) {
  EXPECT_THROW(SurfaceProjector({}), std::invalid_argument);
  EXPECT_THROW(SurfaceProjector({SurfacePatch{}}), std::invalid_argument);
  SurfacePatch nan_patch = bspline_patch(test::from_occt(test::occt_plane()));
  nan_patch.evaluate = [](double, double) { return SurfaceDerivatives{{std::nan(""), 0, 0}, {}, {}, {}, {}, {}}; };
  EXPECT_THROW(SurfaceProjector({nan_patch}), std::invalid_argument);
  SurfacePatch empty = bspline_patch(test::from_occt(test::occt_plane()));
  empty.domain.u_last = empty.domain.u_first;
  EXPECT_THROW(SurfaceProjector({empty}), std::invalid_argument);
  // A displacement field over another rectangle.
  const BSplineSurface face = test::from_occt(test::occt_wavy());
  const BSplineSurface other(1, 1, {0, 0, 1, 1}, {1, 1, 2, 2}, std::vector<Vec3>(4));
  EXPECT_THROW(displaced_patch(face, other), std::invalid_argument);
}

TEST(SurfaceProjector, InvalidHintsAndPointsAreSafe) {
  const SurfaceProjector projector = projector_of(test::occt_wavy());
  const Vec3 p{1.0, 1.5, 0.5};
  const SurfaceProjection cold = projector.project(p);
  for (const SurfaceParameter& hint : {SurfaceParameter{3, 1.0, 1.5}, SurfaceParameter{0, std::nan(""), 1.5},
                                       SurfaceParameter{0, -50.0, 70.0}}) {
    const SurfaceProjection q = projector.project(p, hint);
    EXPECT_LE(distance(q.point, cold.point), 1e-12 * projector.length_scale());
  }
  const SurfaceProjection none = projector.project({std::nan(""), 0.0, 0.0});
  EXPECT_EQ(none.where.patch, -1);
  EXPECT_TRUE(std::isnan(none.distance));
}

TEST(SurfaceProjector, ConcurrentProjectionsMatchSerialOnes) {
  const SurfaceProjector projector(two_halves());
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i) points.push_back({0.005 * i, 1.0 + 0.0025 * i, 0.3 * std::sin(0.1 * i)});
  std::vector<Vec3> serial;
  for (const Vec3& p : points) serial.push_back(projector.project(p).point);
  std::vector<Vec3> parallel(points.size());
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] {
      for (std::size_t i = k; i < points.size(); i += 4) parallel[i] = projector.project(points[i]).point;
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(parallel, serial);
}

}  // namespace
}  // namespace hotmesh::geometry
