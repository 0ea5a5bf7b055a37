// Tests of CAD import on real files from other CAD systems (tests/data/cad/README.md): face
// counts, surface kinds, names, axes (analytic and fitted to B-spline faces, up to sign),
// units, and meridional curves of revolved, analytic, planar and B-spline faces (and of the
// stator-well sample's casing, two separate profiles).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "cad_test_helpers.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::HasSubstr;
using test::cad_file;
using test::distance_to;
using test::is_axis;
using test::read_mm;

std::vector<SurfaceKind> kinds(const CadModel& model) {
  std::vector<SurfaceKind> result;
  for (const FaceInfo& face : model.faces()) result.push_back(face.kind);
  return result;
}

TEST(CadRealFiles, CatiaConeIsTwoRevolvedHalvesAndAPlane) {
  const CadModel model = read_mm("OCC8842_cone_CATIA.igs");
  EXPECT_EQ(kinds(model), (std::vector{SurfaceKind::revolution, SurfaceKind::revolution, SurfaceKind::plane}));
  for (const int id : {1, 2}) {
    EXPECT_TRUE(is_axis(model.face(id).axis, {0, 0, 80}, {0, 0, 1}, 1e-9)) << id;
    EXPECT_EQ(model.face(id).axis_source, AxisSource::analytic);
  }
  EXPECT_FALSE(model.face(3).axis.has_value());
  EXPECT_NEAR(model.face(3).bounds.min.z, -70.0, 1e-3);
  EXPECT_NEAR(model.face(1).bounds.max.z, 80.0, 1e-3);
}

TEST(CadRealFiles, CatiaCylinderAxisIsX) {
  const CadModel model = read_mm("OCC8842_cylinder_CATIA.igs");
  EXPECT_EQ(kinds(model), (std::vector{SurfaceKind::revolution, SurfaceKind::revolution, SurfaceKind::plane,
                                       SurfaceKind::plane}));
  EXPECT_TRUE(is_axis(model.face(1).axis, {50, 0, 0}, {1, 0, 0}, 1e-9));
  EXPECT_TRUE(is_axis(model.face(2).axis, {0, 0, 0}, {-1, 0, 0}, 1e-9));
}

TEST(CadRealFiles, IdeasBSplineConeAndCylinderGetFittedAxes) {
  const CadModel cone = read_mm("OCC8842_cone_Ideas.igs");
  EXPECT_EQ(kinds(cone), (std::vector{SurfaceKind::bspline, SurfaceKind::bspline}));
  EXPECT_EQ(cone.face(1).axis_source, AxisSource::fitted);
  EXPECT_TRUE(is_axis(cone.face(1).axis, {0, 100, 0}, {0, 1, 0}, 1e-6));
  EXPECT_FALSE(cone.face(2).axis.has_value());  // the planar base has no unique axis
  EXPECT_EQ(cone.face(1).name, "F1(1)");
  EXPECT_EQ(cone.face(2).name, "F2(2)");

  const CadModel cylinder = read_mm("OCC8842_cylinder_Ideas.igs");
  ASSERT_EQ(cylinder.faces().size(), 3u);
  EXPECT_TRUE(is_axis(cylinder.face(1).axis, {0, -75, 0}, {0, 1, 0}, 1e-6));
  EXPECT_FALSE(cylinder.face(2).axis.has_value());
  EXPECT_FALSE(cylinder.face(3).axis.has_value());
}

TEST(CadRealFiles, SpindleTorusBSplineGetsItsAxis) {
  const CadModel model = read_mm("OCC26138_Torus.igs");
  ASSERT_EQ(model.faces().size(), 1u);
  EXPECT_EQ(model.face(1).kind, SurfaceKind::bspline);
  EXPECT_TRUE(is_axis(model.face(1).axis, {117.31, 264.30, 120.0}, {0, 1, 0}, 0.01));
}

TEST(CadRealFiles, SpheresToriBoltAndScrew) {
  const CadModel spheres = read_mm("bug24283_spheres.stp");
  EXPECT_EQ(kinds(spheres), (std::vector{SurfaceKind::sphere, SurfaceKind::sphere}));
  EXPECT_NEAR(distance(spheres.face(2).axis->origin(), Vec3{-0.118, 1.686, -1.244}), 0.0, 1e-3);
  EXPECT_EQ(spheres.face(1).name, "");  // SolidWorks writes 'NONE'

  const CadModel torus = read_mm("bug28414_bug_toroidal_surface.stp");
  EXPECT_EQ(kinds(torus), (std::vector{SurfaceKind::torus}));
  EXPECT_TRUE(is_axis(torus.face(1).axis, {-30, 0, 137}, {1, 0, 0}, 1e-9));

  const CadModel bolt = read_mm("bug3883_xr2-ct-214_bolt.stp");
  const std::vector<SurfaceKind> bolt_kinds = kinds(bolt);
  EXPECT_EQ(std::count(bolt_kinds.begin(), bolt_kinds.end(), SurfaceKind::cylinder), 4);
  EXPECT_EQ(std::count(bolt_kinds.begin(), bolt_kinds.end(), SurfaceKind::plane), 3);
  for (const FaceInfo& face : bolt.faces()) {
    if (face.kind == SurfaceKind::cylinder) {
      EXPECT_TRUE(is_axis(face.axis, {0, 0, 0}, {0, 0, 1}, 1e-9)) << face.id;
    }
  }

  const CadModel screw = read_mm("screw.step");
  const std::vector<SurfaceKind> k = kinds(screw);
  ASSERT_EQ(k.size(), 10u);
  EXPECT_EQ(std::count(k.begin(), k.end(), SurfaceKind::torus), 3);
  EXPECT_EQ(std::count(k.begin(), k.end(), SurfaceKind::cone), 2);
  EXPECT_EQ(std::count(k.begin(), k.end(), SurfaceKind::cylinder), 1);
  EXPECT_EQ(std::count(k.begin(), k.end(), SurfaceKind::plane), 4);
  for (const FaceInfo& face : screw.faces()) {
    if (face.kind != SurfaceKind::plane) {
      EXPECT_TRUE(is_axis(face.axis, {-17.898, -0.826, 0}, {0, 0, 1}, 1e-3)) << face.id;
    }
  }
}

TEST(CadRealFiles, ConvertsToTheRequestedUnit) {
  const CadModel metres = CadModel::read(cad_file("OCC8842_cone_CATIA.igs"));
  EXPECT_EQ(metres.unit(), LengthUnit::metre);
  EXPECT_TRUE(is_axis(metres.face(1).axis, {0, 0, 0.08}, {0, 0, 1}, 1e-12));
  EXPECT_NEAR(metres.face(3).bounds.max.x, 0.06, 1e-6);
  CadReadOptions inches;
  inches.unit = LengthUnit::inch;
  EXPECT_NEAR(CadModel::read(cad_file("bug3883_xr2-ct-214_bolt.stp"), inches).face(7).bounds.max.z, 37.0 / 25.4, 1e-6);
}

TEST(CadRealFiles, MeridionalCurveOfTheCatiaConeRunsFromBaseCentreToApex) {
  const CadModel model = read_mm("OCC8842_cone_CATIA.igs");
  const std::vector<int> ids{1, 2, 3};
  const MeridionalCurve m = model.meridional_curve(ids);
  // Axis origin is the apex (0, 0, 80): the base is at z = -150, radius 60.
  EXPECT_NEAR(distance(m.curve.point(0.0), Vec2{0.0, -150.0}), 0.0, 1e-6);
  EXPECT_NEAR(distance(m.curve.point(1.0), Vec2{0.0, 0.0}), 0.0, 1e-6);
  EXPECT_EQ(m.faces, (std::vector<int>{3, 1}));  // face 2 repeats face 1's meridian
  EXPECT_NEAR(distance_to(m.curve, {60.0, -150.0}), 0.0, 1e-6);
  EXPECT_NEAR(distance_to(m.curve, {30.0, -75.0}), 0.0, 1e-6);  // on the cone's line
  EXPECT_NEAR(distance_to(m.curve, {30.0, -150.0}), 0.0, 1e-6);  // on the base
  EXPECT_NEAR(m.face_breaks[1], 60.0 / (60.0 + std::hypot(60.0, 150.0)), 1e-6);
}

TEST(CadRealFiles, MeridionalCurveOfTheBoltIsItsProfile) {
  const CadModel model = read_mm("bug3883_xr2-ct-214_bolt.stp");
  const std::vector<int> ids{1, 2, 3, 4, 5, 6, 7};
  const MeridionalCurve m = model.meridional_curve(ids);
  EXPECT_EQ(m.curve.degree(), 1);
  // (r, z) about the axis through (0, 0, 3): head r = 7.5 for z in [-3, 0], shank r = 5 up to 34.
  for (const Vec2 p : {Vec2{0, -3}, Vec2{4, -3}, Vec2{7.5, -1.5}, Vec2{6, 0}, Vec2{5, 20}, Vec2{2.5, 34}}) {
    EXPECT_NEAR(distance_to(m.curve, p), 0.0, 1e-3) << p.x << ", " << p.y;
  }
  EXPECT_NEAR(distance_to(m.curve, {6.0, 20.0}), 1.0, 1e-3);
  EXPECT_NEAR(m.curve.point(0.0).y, -3.0, 1e-3);  // z grows along the profile
  EXPECT_NEAR(m.curve.point(1.0).y, 34.0, 1e-3);
}

TEST(CadRealFiles, MeridionalCurveOfATorusIsAnExactArc) {
  const CadModel model = read_mm("bug28414_bug_toroidal_surface.stp");
  const std::vector<int> ids{1};
  const MeridionalCurve m = model.meridional_curve(ids);
  EXPECT_TRUE(m.curve.is_rational());
  for (int i = 0; i <= 20; ++i) EXPECT_NEAR(distance(m.curve.point(i / 20.0), Vec2{19.0, 0.0}), 5.0, 1e-9);
}

TEST(CadRealFiles, MeridionalCurveOfBSplineFacesComesFromASection) {
  const CadModel cone = read_mm("OCC8842_cone_Ideas.igs");
  const std::vector<int> both{1, 2};
  const MeridionalCurve m = cone.meridional_curve(both);
  const double apex = dot(Vec3{0, 100, 0} - m.axis.origin(), m.axis.direction());
  const double base = dot(Vec3{0, 0, 0} - m.axis.origin(), m.axis.direction());
  EXPECT_NEAR(distance_to(m.curve, {35.0, base}), 0.0, 1e-3);
  EXPECT_NEAR(distance_to(m.curve, {17.5, 0.5 * (apex + base)}), 0.0, 1e-3);
  EXPECT_NEAR(distance_to(m.curve, {10.0, base}), 0.0, 1e-3);  // the base disc
  EXPECT_NEAR(distance_to(m.curve, {0.0, apex}), 0.0, 1e-3);

  // The spindle torus: its meridian is an arc of radius about 184.5.
  const CadModel torus = read_mm("OCC26138_Torus.igs");
  const std::vector<int> one{1};
  const MeridionalCurve arc = torus.meridional_curve(one);
  const Vec2 a = arc.curve.point(0.0);
  const Vec2 b = arc.curve.point(0.5);
  const Vec2 c = arc.curve.point(1.0);
  // Circumradius of three points of the arc.
  const double radius = distance(a, b) * distance(b, c) * distance(c, a) / (2.0 * std::abs(cross(b - a, c - a)));
  EXPECT_NEAR(radius, 184.5, 0.5);
  EXPECT_GT(a.x, 42.0);
  EXPECT_LT(c.x, 102.0);
}

TEST(CadRealFiles, ScrewProfileJoinsToriConesCylinderAndTip) {
  const CadModel model = read_mm("screw.step");
  const std::vector<int> ids{4, 5, 6, 7, 8, 9, 10};
  const MeridionalCurve m = model.meridional_curve(ids);
  EXPECT_EQ(m.faces.size(), 5u);  // faces 4 and 5 repeat parts of face 6's meridian
  // The shank: r = 5 at world z = -10, i.e. axial coordinate about the axis (direction -z).
  const double z = dot(Vec3{-17.898, -0.826, -10.0} - m.axis.origin(), m.axis.direction());
  EXPECT_NEAR(distance_to(m.curve, {5.0, z}), 0.0, 1e-3);
}

TEST(CadRealFiles, MeridionalCurveErrorsNameTheFaces) {
  const CadModel bolt = read_mm("bug3883_xr2-ct-214_bolt.stp");
  const auto error = [&](std::vector<int> ids, MeridionalOptions options = {}) {
    try {
      bolt.meridional_curve(ids, options);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error({1}), HasSubstr("none of the faces is a surface of revolution: give the axis"));
  EXPECT_THAT(error({2, 7}), HasSubstr("do not form one connected profile"));
  EXPECT_THAT(error({9}), HasSubstr("no face 9: the faces are 1 to 7"));
  EXPECT_THAT(error({2, 2}), HasSubstr("face 2 is given twice"));
  MeridionalOptions x_axis;
  x_axis.axis = Axis({0, 0, 0}, {1, 0, 0});
  EXPECT_THAT(error({2}, x_axis), HasSubstr("face 2 (cylinder) is not a surface of revolution about the axis"));
  // A plane is rotational about its normal: with the axis given it is a radial line.
  MeridionalOptions z_axis;
  z_axis.axis = Axis({0, 0, 0}, {0, 0, 1});
  const std::vector<int> top{1};
  const MeridionalCurve ring = bolt.meridional_curve(top, z_axis);
  EXPECT_NEAR(distance_to(ring.curve, {6.0, 3.0}), 0.0, 1e-6);
  EXPECT_NEAR(ring.curve.point(0.0).x, 5.0, 1e-3);
  EXPECT_NEAR(ring.curve.point(1.0).x, 7.5, 1e-3);

  const CadModel spheres = read_mm("bug24283_spheres.stp");
  const std::vector<int> both{1, 2};
  EXPECT_THAT([&] { spheres.meridional_curve(both); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("faces 1 and 2 turn about different axes")));
}

TEST(CadRealFiles, StatorWellCasingOnEitherSideOfTheBladeIsTwoSeparateProfiles) {
  // The casing of samples/stator_well: face 3 in front of the blade row (z 0 to 0.034), face 4
  // behind it (z 0.066 to 0.1), both on the cylinder r = 0.45 about the z axis.
  const CadModel model = CadModel::read(std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples/stator_well/stator_well.step");
  const std::vector<int> casing{4, 3};
  EXPECT_THAT([&] { model.meridional_curve(casing); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("do not form one connected profile")));
  const std::vector<MeridionalCurve> profiles = model.meridional_profiles(casing);
  ASSERT_EQ(profiles.size(), 2u);
  EXPECT_EQ(profiles[0].faces, std::vector<int>{4});  // in the order given
  EXPECT_EQ(profiles[1].faces, std::vector<int>{3});
  const auto z_of = [](const MeridionalCurve& m, double t) {
    return m.axis.to_cartesian({m.curve.point(t).x, 0.0, m.curve.point(t).y}).z;
  };
  for (const auto& [profile, z0, z1] : {std::tuple{&profiles[0], 0.066, 0.1}, std::tuple{&profiles[1], 0.0, 0.034}}) {
    EXPECT_TRUE(is_axis(profile->axis, {0, 0, 0}, {0, 0, 1}, 1e-12));
    EXPECT_NEAR(profile->curve.point(0.5).x, 0.45, 1e-12);
    EXPECT_NEAR(std::min(z_of(*profile, 0.0), z_of(*profile, 1.0)), z0, 1e-12);
    EXPECT_NEAR(std::max(z_of(*profile, 0.0), z_of(*profile, 1.0)), z1, 1e-12);
    EXPECT_DOUBLE_EQ(profile->tolerance, profiles[0].tolerance);  // the tolerance of the whole set
  }
  // Faces that form one profile give it alone, as meridional_curve does.
  const std::vector<int> disc_down{40, 41, 42};
  const std::vector<MeridionalCurve> one = model.meridional_profiles(disc_down);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].faces, model.meridional_curve(disc_down).faces);
  // With the blade's leading face (5, the plane z = 0.034), which meets the front casing at
  // its corner: faces 3 and 5 form one profile, face 4 another.
  const std::vector<int> three{3, 4, 5};
  const std::vector<MeridionalCurve> groups = model.meridional_profiles(three);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].faces.size(), 2u);
  EXPECT_THAT(groups[0].faces, ::testing::UnorderedElementsAre(3, 5));
  EXPECT_EQ(groups[1].faces, std::vector<int>{4});
}

// A 2D drawing (lines and arcs, no surface) is read for its edges: the walls of 2D cases.
TEST(CadRealFiles, DrawingWithoutSurfacesIsReadAsItsEdges) {
  const CadModel model = read_mm("Disc.igs");
  EXPECT_TRUE(model.faces().empty());
  ASSERT_EQ(model.edges().size(), 46u);
  int lines = 0, circles = 0;
  for (const EdgeInfo& e : model.edges()) {
    lines += e.kind == EdgeKind::line;
    circles += e.kind == EdgeKind::circle;
    EXPECT_NEAR(e.start.z, 0.0, 1e-9) << "edge " << e.id;  // drawn in the plane z = 0
    EXPECT_GT(e.length, 0.0) << "edge " << e.id;
  }
  EXPECT_EQ(lines + circles, 46);
  EXPECT_GT(circles, 0);
}

TEST(CadRealFiles, FaceAsBSplineSurfaceMatchesTheFace) {
  const CadModel model = read_mm("OCC8842_cone_CATIA.igs");
  const BSplineSurface s = model.face_bspline(1);
  // Points of the revolved face lie on the cone r = 60 (80 - z) / 150.
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const Vec3 p = s.point(s.u_first() + (s.u_last() - s.u_first()) * i / 4, s.v_first() + (s.v_last() - s.v_first()) * j / 4);
      EXPECT_NEAR(std::hypot(p.x, p.y), 60.0 * (80.0 - p.z) / 150.0, 1e-6);
    }
  }
}

// I-DEAS writes rational B-spline faces whose knot vectors float (their ends are not degree + 1
// equal knots, as IGES 128 allows): each is cut out over its range with clamped ends, the same
// surface. The lateral face is the cylinder r = 25 about y from y = -75 to 75, the caps the
// planes y = +-75.
TEST(CadRealFiles, BSplineFacesWithFloatingKnotVectorsAreTheSameSurfaceClamped) {
  const CadModel model = read_mm("OCC8842_cylinder_Ideas.igs");
  for (const int id : {1, 2, 3}) {
    const BSplineSurface s = model.face_bspline(id);
    EXPECT_EQ(s.u_knots().front(), s.u_knots()[static_cast<std::size_t>(s.u_degree())]) << id;
    EXPECT_EQ(s.v_knots().back(), s.v_knots()[s.v_knots().size() - 1 - static_cast<std::size_t>(s.v_degree())]) << id;
    double y_low = 1e9, y_high = -1e9;
    for (int i = 0; i <= 6; ++i) {
      for (int j = 0; j <= 6; ++j) {
        const Vec3 p = s.point(s.u_first() + (s.u_last() - s.u_first()) * i / 6, s.v_first() + (s.v_last() - s.v_first()) * j / 6);
        if (id == 1) {
          EXPECT_NEAR(std::hypot(p.x, p.z), 25.0, 1e-6) << i << " " << j;
        } else {
          EXPECT_NEAR(std::abs(p.y), 75.0, 1e-6) << id;
        }
        y_low = std::min(y_low, p.y);
        y_high = std::max(y_high, p.y);
      }
    }
    if (id == 1) {
      EXPECT_NEAR(y_low, -75.0, 1e-6);
      EXPECT_NEAR(y_high, 75.0, 1e-6);
    }
  }
}

}  // namespace
}  // namespace hotmesh::geometry
