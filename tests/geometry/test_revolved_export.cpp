// Tests of revolved profiles written to STEP (revolved_export.hpp) and read back with CadModel:
// face order and names, analytic kinds for straight meridians, axes, meridional curves equal
// to the meridians given, sector and full sweeps, reproducible files and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "cad_test_helpers.hpp"
#include "hotmesh/geometry/revolved_export.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::HasSubstr;
using test::distance_to;
using test::is_axis;

BSplineCurve2d segment(Vec2 a, Vec2 b) { return BSplineCurve2d(1, {0, 0, 1, 1}, {a, b}); }

/// A quarter circle of radius 0.5 centred at (r, z) = (2, 1), from (2.5, 1) to (2, 1.5): a
/// rational quadratic, exact.
BSplineCurve2d arc() {
  const double w = std::numbers::sqrt2 / 2.0;
  return BSplineCurve2d(2, {0, 0, 0, 1, 1, 1}, {{2.5, 1.0}, {2.5, 1.5}, {2.0, 1.5}}, {1.0, w, 1.0});
}

/// A cubic wavy meridian from (1, 2) to (1.5, 3).
BSplineCurve2d wavy() {
  return BSplineCurve2d(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{1.0, 2.0}, {1.3, 2.2}, {1.1, 2.5}, {1.6, 2.8}, {1.5, 3.0}});
}

/// An off-origin, tilted axis, so nothing lines up with the coordinate axes by chance.
const Axis kAxis({0.2, -0.1, 0.3}, {1.0, 2.0, 2.0});

RevolvedModel model(double angle) {
  RevolvedModel m;
  m.axis = kAxis;
  m.angle = angle;
  m.faces = {{"disc", segment({1.0, 0.0}, {2.0, 0.0})},       // normal to the axis: plane
             {"drum", segment({2.0, 0.0}, {2.0, 1.0})},       // parallel: cylinder
             {"cone", segment({2.0, 1.0}, {3.0, 1.5})},       // slanted: cone
             {"fillet", arc()},                               // rational B-spline: revolution
             {"profile", wavy()}};
  return m;
}

class RevolvedExport : public ::testing::TestWithParam<double> {};

TEST_P(RevolvedExport, FacesComeBackInOrderWithNamesKindsAndTheAxis) {
  hotmesh::test::TempDir dir;
  hotmesh::test::write_text(dir / "profile.step", to_step(model(GetParam())));
  const CadModel cad = CadModel::read(dir / "profile.step");
  ASSERT_EQ(cad.faces().size(), 5u);
  const char* names[] = {"disc", "drum", "cone", "fillet", "profile"};
  const SurfaceKind kinds[] = {SurfaceKind::plane, SurfaceKind::cylinder, SurfaceKind::cone, SurfaceKind::revolution,
                               SurfaceKind::revolution};
  for (int id = 1; id <= 5; ++id) {
    const FaceInfo& face = cad.face(id);
    const auto i = static_cast<std::size_t>(id - 1);
    EXPECT_EQ(face.name, names[i]);
    EXPECT_EQ(face.kind, kinds[i]) << names[i] << " is " << to_string(face.kind);
    if (face.kind != SurfaceKind::plane) {
      EXPECT_EQ(face.axis_source, AxisSource::analytic) << names[i];
      EXPECT_TRUE(is_axis(face.axis, kAxis.origin(), kAxis.direction(), 1e-12)) << names[i];
    }
  }
}

TEST_P(RevolvedExport, MeridionalCurvesAreTheMeridiansGiven) {
  hotmesh::test::TempDir dir;
  const RevolvedModel m = model(GetParam());
  hotmesh::test::write_text(dir / "profile.step", to_step(m));
  const CadModel cad = CadModel::read(dir / "profile.step");
  for (int id = 1; id <= 5; ++id) {
    const int ids[] = {id};
    const MeridionalCurve back = cad.meridional_curve(ids, {.axis = kAxis});
    const BSplineCurve2d& given = m.faces[static_cast<std::size_t>(id - 1)].meridian;
    for (int k = 0; k <= 20; ++k) {
      const double t = k / 20.0;
      EXPECT_NEAR(distance_to(back.curve, given.point(t)), 0.0, 1e-9) << m.faces[static_cast<std::size_t>(id - 1)].name;
      EXPECT_NEAR(distance_to(given, back.curve.point(t)), 0.0, 1e-9) << m.faces[static_cast<std::size_t>(id - 1)].name;
    }
  }
  // The drum, cone and fillet join into one profile, as the faces of one wall should.
  const int chain[] = {2, 3};
  const MeridionalCurve wall = cad.meridional_curve(chain, {.axis = kAxis});
  EXPECT_NEAR(distance(wall.curve.point(0.0), Vec2{2.0, 0.0}), 0.0, 1e-9);
  EXPECT_NEAR(distance(wall.curve.point(1.0), Vec2{3.0, 1.5}), 0.0, 1e-9);
}

TEST_P(RevolvedExport, TheSweepStartsAtThetaZeroAndCoversTheAngle) {
  hotmesh::test::TempDir dir;
  hotmesh::test::write_text(dir / "profile.step", to_step(model(GetParam())));
  const CadModel cad = CadModel::read(dir / "profile.step");
  // The drum is the cylinder r = 2 about the axis for z in [0, 1], over theta in [0, angle]:
  // its B-spline form's corners lie at theta = 0 and theta = angle.
  const BSplineSurface drum = cad.face_bspline(2);
  double lo = 10.0, hi = -10.0;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 8; ++j) {
      const Vec3 p = drum.point(drum.u_first() + (drum.u_last() - drum.u_first()) * i / 8,
                                drum.v_first() + (drum.v_last() - drum.v_first()) * j / 8);
      const Cylindrical c = kAxis.to_cylindrical(p);
      EXPECT_NEAR(c.r, 2.0, 1e-9);
      const double theta = c.theta < -1e-9 ? c.theta + 2.0 * std::numbers::pi : c.theta;
      lo = std::min(lo, theta);
      hi = std::max(hi, theta);
    }
  }
  EXPECT_NEAR(lo, 0.0, 1e-9);
  EXPECT_NEAR(hi, GetParam(), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Sweeps, RevolvedExport, ::testing::Values(3.6 * std::numbers::pi / 180.0, 1.5 * std::numbers::pi),
                         [](const auto& param) { return param.index == 0 ? std::string("Sector") : std::string("ThreeQuarters"); });

TEST(RevolvedExportFile, AGivenTimeStampMakesTheFileReproducible) {
  RevolvedModel m = model(0.1);
  m.time_stamp = "2000-01-01T00:00:00";
  const std::string text = to_step(m);
  EXPECT_THAT(text, HasSubstr("'2000-01-01T00:00:00'"));
  EXPECT_THAT(text, HasSubstr("ADVANCED_FACE('fillet'"));
  EXPECT_THAT(text, HasSubstr("PRODUCT('fillet','fillet'"));
  EXPECT_EQ(to_step(m), text);  // also after other files were written
}

TEST(RevolvedExportFile, BadInputIsRefused) {
  RevolvedModel m = model(0.0);
  EXPECT_THROW(to_step(m), std::invalid_argument);
  m.angle = 7.0;
  EXPECT_THROW(to_step(m), std::invalid_argument);
  m.angle = 1.0;
  m.faces.push_back({"behind the axis", segment({-0.5, 0.0}, {1.0, 0.0})});
  EXPECT_THROW(to_step(m), std::invalid_argument);
  m.faces.clear();
  EXPECT_THROW(to_step(m), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::geometry
