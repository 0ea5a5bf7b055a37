// Tests of trimmed faces (issue 23): the region inside a face's trimming loops, the loops read
// from a CAD file in the (t, s) of the face's B-spline form, and sliding that stays inside them
// where the wall goes on across them: a plate with a hole, whose top face is a plane trimmed by
// the hole's circle, and the hole's wall.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "cad_test_helpers.hpp"
#include "hotmesh/geometry/surface_shape.hpp"
#include "hotmesh/geometry/trim_region.hpp"
#include "hotmesh/geometry/wall_deviation.hpp"
#include "occt_fixtures.hpp"

namespace hotmesh::geometry {
namespace {

/// `n` points on the circle of radius r about c, from angle a0 to a1.
std::vector<Vec2> arc(const Vec2& c, double r, double a0, double a1, int n) {
  std::vector<Vec2> points;
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    points.push_back(c + r * Vec2{std::cos(a), std::sin(a)});
  }
  return points;
}

// A square [0, 10]^2 with a round hole of radius 2 about (5, 5), given as the square's four
// sides in one curve and the hole as two half circles running opposite ways, in no order: the
// even-odd rule needs neither order nor orientation. 20 000 random points agree with the exact
// region wherever they are farther than the polygon's chord error from the circle.
TEST(TrimRegion, AnswersWhetherAPointLiesInsideLoopsGivenInAnyOrder) {
  const double pi = std::numbers::pi;
  std::vector<TrimRegion::Curve> curves;
  curves.push_back({arc({5, 5}, 2.0, pi, 0.0, 200), true});
  curves.push_back({{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, false});
  curves.push_back({arc({5, 5}, 2.0, pi, 2.0 * pi, 200), true});
  const TrimRegion region(curves, {0.0, 10.0, 0.0, 10.0});
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-1.0, 11.0);
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec2 p{coordinate(random), coordinate(random)};
    const double r = distance(p, Vec2{5, 5});
    if (std::abs(r - 2.0) < 1e-3) continue;
    const bool inside = p.x >= 0 && p.x <= 10 && p.y >= 0 && p.y <= 10 && r > 2.0;
    ASSERT_EQ(region.contains(p.x, p.y), inside) << p.x << ", " << p.y;
    ++checked;
  }
  EXPECT_GT(checked, 19900);
  EXPECT_FALSE(region.contains(5.0, 5.0));
  EXPECT_TRUE(region.contains(5.0, 7.01));
  EXPECT_FALSE(region.contains(5.0, 6.99));
}

TEST(TrimRegion, RefusesCurvesWithoutASegment) {
  EXPECT_THROW(TrimRegion({{{{1, 1}}, true}}, {0, 1, 0, 1}), std::invalid_argument);
  EXPECT_THROW(TrimRegion({{{{0, 0}, {1, 1}}, true}}, {0, 0, 0, 1}), std::invalid_argument);
}

class PlateWithHole : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto path = dir_ / "plate.step";
    test::write_primitive(path, test::Primitive::plate_with_hole, Axis({0, 0, 0}, {0, 0, 1}));
    CadReadOptions options;
    options.unit = LengthUnit::millimetre;
    const CadModel model = CadModel::read(path, options);
    for (const FaceInfo& info : model.faces()) {
      CadFace face = model.cad_face(info.id);
      const ParameterRectangle r = face.surface.domain();
      const Vec3 middle = face.surface.point(0.5 * (r.u_first + r.u_last), 0.5 * (r.v_first + r.v_last));
      if (info.kind == SurfaceKind::cylinder) hole.emplace(std::move(face));
      if (info.kind == SurfaceKind::plane && std::abs(middle.z - 2.0) < 1e-9) top.emplace(std::move(face));
    }
    ASSERT_TRUE(hole && top);
    hole_ = &*hole;
    top_ = &*top;
    ASSERT_FALSE(hole_->trims.empty());
    ASSERT_FALSE(top_->trims.empty());
  }
  /// A wall of the faces, each moved by `shift` at stage 1.
  static std::shared_ptr<SurfaceShape> moved(std::vector<CadFace> faces, const Vec3& shift) {
    std::vector<BSplineSurface> fields;
    for (const CadFace& f : faces) {
      const ParameterRectangle r = f.surface.domain();
      fields.emplace_back(1, 1, std::vector<double>{r.u_first, r.u_first, r.u_last, r.u_last},
                          std::vector<double>{r.v_first, r.v_first, r.v_last, r.v_last},
                          std::vector<Vec3>(4, shift));
    }
    return std::make_shared<SurfaceShape>(std::move(faces), std::move(fields));
  }

  hotmesh::test::TempDir dir_;
  std::optional<CadFace> top;
  std::optional<CadFace> hole;
  const CadFace* top_ = nullptr;
  const CadFace* hole_ = nullptr;
};

// The top face's loops, read from the file in its own (t, s): the square's sides and the hole's
// circle, which runs through the middle of its rectangle. Points of the circle's trace lie on
// the circle of radius 2 mm; the region holds the plate's points and not the hole's. The hole's
// wall is a cylinder whose rational B-spline form runs at another speed than its angle: its
// loops (two circles and the seam, twice) map onto its rectangle's sides, so it is untrimmed.
TEST_F(PlateWithHole, TheTopFaceIsTrimmedByTheHoleAndTheHolesWallIsNot) {
  const auto region = trim_region(*top_, [](int) { return true; });
  ASSERT_NE(region, nullptr);
  double worst = 0.0;
  std::size_t on_circle = 0;
  for (const TrimCurve& c : top_->trims) {
    for (const Vec2& q : c.points) {
      const Vec3 p = top_->surface.point(q.x, q.y);
      const double r = std::hypot(p.x, p.y);
      if (r < 3.0) worst = std::max(worst, std::abs(r - 2.0)), ++on_circle;
      EXPECT_NEAR(p.z, 2.0, 1e-12);
    }
  }
  EXPECT_GT(on_circle, 64u);
  EXPECT_LT(worst, 1e-9);
  const auto inside = [&](double x, double y) {
    // The plane's (t, s) to (x, y): its B-spline form is affine in them.
    const ParameterRectangle r = top_->surface.domain();
    const Vec3 o = top_->surface.point(r.u_first, r.v_first);
    const Vec3 du = (top_->surface.point(r.u_last, r.v_first) - o) / (r.u_last - r.u_first);
    const Vec3 dv = (top_->surface.point(r.u_first, r.v_last) - o) / (r.v_last - r.v_first);
    const Vec3 q{x - o.x, y - o.y, 0.0};
    const double det = du.x * dv.y - du.y * dv.x;
    return region->contains(r.u_first + (q.x * dv.y - q.y * dv.x) / det, r.v_first + (du.x * q.y - du.y * q.x) / det);
  };
  EXPECT_FALSE(inside(0.0, 0.0));
  EXPECT_FALSE(inside(1.9, 0.3));
  EXPECT_TRUE(inside(2.1, 0.3));
  EXPECT_TRUE(inside(-4.9, 4.9));
  EXPECT_EQ(trim_region(*hole_, [](int) { return true; }), nullptr);
}

// Sliding on the plate and the hole's wall: a point above the hole's footprint, 0.5 mm over the
// plate at 1.5 mm from the axis, would project onto the top plane's rectangle inside the hole
// (0.5 mm away); the wall has no point there, and its nearest is the hole's rim at radius 2,
// sqrt(0.5) mm away (the top face's rim and the hole's wall agree on it). The same point moved with the wall at stage 1 finds the moved rim. A point
// over the plate itself projects straight down.
TEST_F(PlateWithHole, SlidingStaysOnThePlateWhereTheHoleCutsIt) {
  for (const double lambda : {0.0, 1.0}) {
    const Vec3 shift{1.0, 0.5, 0.2};
    const auto wall = moved({*top_, *hole_}, shift);
    const Vec3 offset = lambda * shift;
    const ShapePoint over_hole = wall->project(Vec3{1.5, 0.0, 2.5} + offset, lambda);
    EXPECT_NEAR(over_hole.distance, std::sqrt(0.5), 1e-9) << lambda;
    EXPECT_NEAR(distance(over_hole.point, Vec3{2.0, 0.0, 2.0} + offset), 0.0, 1e-9) << lambda;
    EXPECT_NEAR(over_hole.point.z, 2.0 + offset.z, 1e-12) << lambda;
    const ShapePoint over_plate = wall->project(Vec3{3.5, -1.0, 2.5} + offset, lambda);
    EXPECT_NEAR(over_plate.distance, 0.5, 1e-12) << lambda;
    EXPECT_NEAR(distance(over_plate.point, Vec3{3.5, -1.0, 2.0} + offset), 0.0, 1e-12) << lambda;
    // Warm started from the rim, a point drifting into the footprint stays on the rim.
    const ShapePoint drifted = wall->project(Vec3{1.8, 0.1, 2.2} + offset, lambda, over_hole.parameter);
    const Vec3 q = drifted.point - offset;
    EXPECT_NEAR(std::hypot(q.x, q.y), 2.0, 1e-9) << lambda;
    EXPECT_NEAR(q.z, 2.0, 1e-12) << lambda;
  }
}

// Where the hole's wall is not part of the wall (its circle bounds the plate's patch only, a
// free edge), the plate reaches on beyond it as beyond its rectangle's free sides.
TEST_F(PlateWithHole, AFreeTrimmingLoopDoesNotHoldANodeIn) {
  const auto wall = moved({*top_}, {0, 0, 0});
  const ShapePoint over_hole = wall->project({1.5, 0.0, 2.5}, 0.0);
  EXPECT_NEAR(over_hole.distance, 0.5, 1e-12);
}

// A mesh of the wall, the plate's top face round the hole (an annulus out to radius 4.5) and the
// hole's wall down to its end, measured both ways against the faces: the top face's samples
// over the hole are no points of it (beyond its trimming loop), so they do not count, where the
// hole's wall, joined to the annulus along the circle, would be 2 mm from the hole's middle.
TEST_F(PlateWithHole, AMeshOfTheWallIsMeasuredAgainstTheTrimmedFaceOnly) {
  constexpr int kAround = 48;
  std::vector<Vec3> points;
  const auto node = [](int k, int i) { return static_cast<std::int32_t>((k % kAround) * 10 + i); };
  for (int k = 0; k < kAround; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kAround;
    for (int i = 0; i <= 5; ++i) points.push_back({(2.0 + 0.5 * i) * std::cos(a), (2.0 + 0.5 * i) * std::sin(a), 2.0});
    for (int j = 1; j <= 4; ++j) points.push_back({2.0 * std::cos(a), 2.0 * std::sin(a), 2.0 - 0.5 * j});
  }
  WallFaces faces;
  for (int k = 0; k < kAround; ++k) {
    for (int i = 0; i < 5; ++i) {
      const std::int32_t quad[4] = {node(k, i), node(k + 1, i), node(k + 1, i + 1), node(k, i + 1)};
      faces.add(quad);
    }
    for (int j = 0; j < 4; ++j) {  // the circle's node, then the wall's below it
      const std::int32_t quad[4] = {node(k, j == 0 ? 0 : 5 + j), node(k, 6 + j), node(k + 1, 6 + j),
                                    node(k + 1, j == 0 ? 0 : 5 + j)};
      faces.add(quad);
    }
  }
  const auto wall = undeformed_surface_shape({*top_, *hole_});
  const WallDeviation w = wall_deviation(*wall, points, faces, {.lambda = 0.0});
  const double chord = 2.0 * (1.0 - std::cos(std::numbers::pi / kAround));  // the polygon's sag at the circle
  EXPECT_LT(w.shape_to_mesh.distance, 4.5 * chord);
  EXPECT_LT(w.mesh_to_shape.distance, 4.5 * chord);
  EXPECT_GT(w.uncovered_samples, 0u);
}

// CATIA's IGES cylinder is four separate surfaces that share no edge in the file: read, they
// are sewn, so each cap names the edges of its circle that the lateral halves name too, and
// the two halves share their straight seams. I-DEAS's solid shares its edges already.
TEST(TrimRegion, SeparateSurfacesAreSewnSoThatTheyShareTheirEdges) {
  for (const char* file : {"OCC8842_cylinder_CATIA.igs", "OCC8842_cylinder_Ideas.igs"}) {
    SCOPED_TRACE(file);
    const CadModel model = test::read_mm(file);
    std::map<int, std::set<int>> faces_of_edge;
    for (const FaceInfo& info : model.faces()) {
      for (const FaceEdge& e : model.cad_face(info.id).edges) faces_of_edge[e.edge].insert(info.id);
    }
    std::size_t shared = 0;
    for (const auto& entry : faces_of_edge) shared += entry.second.size() == 2 ? 1u : 0u;
    EXPECT_GE(shared, std::string(file).find("CATIA") != std::string::npos ? 6u : 2u);
  }
}

// Real CAD files: the cylinders of CATIA (four separate trimmed surfaces, sewn at read) and of
// I-DEAS (a solid whose caps share their circles with the lateral face). A point just outside
// the cylinder beside a cap, over the cap's square rectangle, projects onto the cap's rim, not
// into the square's corner beyond the circle: the circle binds, named by both faces.
TEST(TrimRegion, RealCylindersHoldSlidingOnTheirCapsInsideTheCircles) {
  struct Case {
    const char* file;
    Vec3 outside;  // beside the cap at the axis's start, 2 mm out from the radius
    Vec3 rim;
  };
  for (const Case& c : {Case{"OCC8842_cylinder_CATIA.igs", {-0.5, 0.0, 52.0}, {0.0, 0.0, 50.0}},
                        Case{"OCC8842_cylinder_Ideas.igs", {0.0, -75.5, 27.0}, {0.0, -75.0, 25.0}}}) {
    SCOPED_TRACE(c.file);
    const CadModel model = test::read_mm(c.file);
    std::vector<CadFace> faces;
    for (const FaceInfo& info : model.faces()) faces.push_back(model.cad_face(info.id));
    const auto wall = undeformed_surface_shape(faces);
    const ShapePoint q = wall->project(c.outside, 0.0);
    EXPECT_NEAR(q.distance, std::sqrt(0.25 + 4.0), 1e-6);
    EXPECT_LT(distance(q.point, c.rim), 1e-4);
  }
}

}  // namespace
}  // namespace hotmesh::geometry
