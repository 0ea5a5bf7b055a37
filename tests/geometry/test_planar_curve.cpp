// Tests of CadModel::planar_curve (geometry/src/cad/planar_curve.cpp): the wall of a 2D case from
// the CAD edges drawn in its plane, on the lower wall of a channel with a forward-facing step
// (occt_fixtures.hpp, StepWall) written to STEP by OpenCASCADE and read back as a user's file
// is. The expectations come from the drawing itself: its vertices, and its fillet's circle.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "cad_test_helpers.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/deflected_curve.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "occt_fixtures.hpp"
#include "test_support.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::HasSubstr;
using test::StepWall;
using test::StepWallDrawing;

/// The drawing written and read back in millimetres.
CadModel drawn(StepWallDrawing drawing, const hotmesh::test::TempDir& dir) {
  const auto path = dir / "wall.step";
  test::write_step_wall(path, drawing);
  return CadModel::read(path, {.unit = LengthUnit::millimetre});
}

bool near(const Vec3& p, const Vec2& q) { return std::hypot(p.x - q.x, p.y - q.y) < 1e-9 && std::abs(p.z) < 1e-9; }

/// The wall's edges, found as a user finds them in `hotmesh cad`'s list: those whose ends are
/// two of the wall's vertices (the face's other edges reach y = 10 or run up the outlet).
std::vector<int> wall_edges(const CadModel& model) {
  const std::vector<Vec2> v = StepWall::vertices();
  const auto vertex = [&](const Vec3& p) { return std::any_of(v.begin(), v.end(), [&](const Vec2& q) { return near(p, q); }); };
  std::vector<int> ids;
  for (const EdgeInfo& e : model.edges()) {
    const bool outlet = std::abs(e.start.x - StepWall::kLength) < 1e-9 && std::abs(e.end.x - StepWall::kLength) < 1e-9;
    if (vertex(e.start) && vertex(e.end) && !outlet) ids.push_back(e.id);
  }
  return ids;
}

/// How far a point is from the fillet's circle, moved by `shift`.
double off_circle(const Vec2& p, const Vec2& shift = {0, 0}) {
  return std::abs(distance(p, StepWall::fillet_centre() + shift) - StepWall::kFilletRadius);
}

/// The parameters of `samples` points inside piece k of the curve (between its breaks).
std::vector<double> inside(const PlanarCurve& c, std::size_t k, int samples) {
  std::vector<double> t;
  for (int i = 1; i < samples; ++i) t.push_back(c.edge_breaks[k] + (c.edge_breaks[k + 1] - c.edge_breaks[k]) * i / samples);
  return t;
}

TEST(PlanarCurve, RunsThroughTheCadVerticesInOrderWithXGrowing) {
  const hotmesh::test::TempDir dir;
  const CadModel model = drawn(StepWallDrawing::edges, dir);
  ASSERT_EQ(model.edges().size(), 4u);
  std::vector<int> backwards{4, 3, 2, 1};  // the order given does not matter
  const PlanarCurve c = model.planar_curve(backwards);
  ASSERT_EQ(c.edges.size(), 4u);
  ASSERT_EQ(c.edge_breaks.size(), 5u);
  const std::vector<Vec2> v = StepWall::vertices();
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Vec2 p = c.curve.point(c.edge_breaks[k]);
    EXPECT_LT(distance(p, v[k]), 1e-12 * StepWall::kLength) << "vertex " << k << " at (" << p.x << ", " << p.y << ")";
  }
  EXPECT_EQ(model.edge(c.edges[2]).kind, EdgeKind::circle);
  EXPECT_EQ(c.edge_breaks.front(), 0.0);
  EXPECT_EQ(c.edge_breaks.back(), 1.0);
}

TEST(PlanarCurve, KeepsTheFilletsCircleExactly) {
  const hotmesh::test::TempDir dir;
  const CadModel model = drawn(StepWallDrawing::edges, dir);
  const PlanarCurve c = model.planar_curve(std::vector<int>{1, 2, 3, 4});
  // A polyline through 64 points of the arc would be off by its sagitta, R (1 - cos(pi / 256))
  // = 1.5e-4 R, in the middle of each chord; the rational arc is the circle to round-off.
  double worst = 0.0;
  for (const double t : inside(c, 2, 64)) {
    const Vec2 mid = c.curve.point(t);
    worst = std::max(worst, off_circle(mid));
  }
  EXPECT_LT(worst, 1e-12 * StepWall::kFilletRadius);
}

TEST(PlanarCurve, HasACornerAtTheFootOnlyWhereTheFilletIsTangent) {
  const hotmesh::test::TempDir dir;
  const CadModel model = drawn(StepWallDrawing::edges, dir);
  const PlanarCurve c = model.planar_curve(std::vector<int>{1, 2, 3, 4});
  const std::vector<ShapeFeature> corners = DeflectedCurve(c.curve).corners(5.0 * std::numbers::pi / 180.0);
  ASSERT_EQ(corners.size(), 1u);
  EXPECT_NEAR(corners[0].parameter, c.edge_breaks[1], 1e-12);
  EXPECT_NEAR(corners[0].angle, 0.5 * std::numbers::pi, 1e-9);
}

TEST(PlanarCurve, FaceEdgesGiveTheSameCurveAsTheDrawnEdges) {
  const hotmesh::test::TempDir dir;
  const CadModel face = drawn(StepWallDrawing::face, dir);
  ASSERT_EQ(face.faces().size(), 1u);
  const std::vector<int> ids = wall_edges(face);
  ASSERT_EQ(ids.size(), 4u);
  const PlanarCurve from_face = face.planar_curve(ids);
  const hotmesh::test::TempDir other;
  const PlanarCurve from_edges = drawn(StepWallDrawing::edges, other).planar_curve(std::vector<int>{1, 2, 3, 4});
  for (int i = 0; i <= 100; ++i) {
    EXPECT_LT(distance(from_face.curve.point(i / 100.0), from_edges.curve.point(i / 100.0)), 1e-12 * StepWall::kLength);
  }
}

// Eq. (21) on the edges' curve: a rigid shift of the wall, given at 21 FEM nodes along it,
// interpolated as a displacement d(t) (constant: interpolation keeps constants) leaves the
// fillet a circle, the CAD's curvature between the nodes; interpolated through the deflected
// nodes (form curve) it becomes a cubic through a few of its points, off the circle between
// them.
TEST(PlanarCurve, DisplacementFormKeepsTheFilletsCurvatureBetweenFemNodes) {
  const hotmesh::test::TempDir dir;
  const PlanarCurve c = drawn(StepWallDrawing::edges, dir).planar_curve(std::vector<int>{1, 2, 3, 4});
  const Vec2 shift{0.01, 0.03};
  CurveSamples nodes;
  for (int j = 0; j <= 20; ++j) {
    nodes.points.push_back(c.curve.point(j / 20.0));
    nodes.deflections.push_back(shift);
  }
  ReconstructionOptions options;
  options.degree = 3;
  options.form = DeflectionForm::displacement;
  const DeflectedCurve kept = fit_curve(nodes, &c.curve, options).curve;
  options.form = DeflectionForm::curve;
  const DeflectedCurve through_nodes = fit_curve(nodes, &c.curve, options).curve;
  double kept_off = 0.0, through_off = 0.0;
  for (const double t : inside(c, 2, 64)) {
    kept_off = std::max(kept_off, off_circle(kept.point(t, 1.0), shift));
    through_off = std::max(through_off, off_circle(through_nodes.point(t, 1.0), shift));
  }
  EXPECT_LT(kept_off, 1e-9 * StepWall::kFilletRadius);
  EXPECT_GT(through_off, 1e-4 * StepWall::kFilletRadius);
}

TEST(PlanarCurve, RefusesAnEdgeOffTheMeshPlaneNamingItAndItsDistance) {
  const hotmesh::test::TempDir dir;
  const CadModel model = drawn(StepWallDrawing::lifted, dir);
  int arc = 0;
  for (const EdgeInfo& e : model.edges()) {
    if (e.kind == EdgeKind::circle) arc = e.id;
  }
  ASSERT_GT(arc, 0);
  EXPECT_THAT([&] { model.planar_curve(std::vector<int>{1, 2, 3, 4}); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("edge " + std::to_string(arc) +
                                                             " is not in the mesh's plane z = 0: it reaches 0.5 from it")));
}

TEST(PlanarCurve, RefusesEdgesThatDoNotChain) {
  const hotmesh::test::TempDir dir;
  const CadModel model = drawn(StepWallDrawing::gap, dir);
  EXPECT_THAT([&] { model.planar_curve(std::vector<int>{1, 2, 3, 4}); },
              ::testing::ThrowsMessage<InputError>(AllOf(HasSubstr("the curves of edges 1, 2, 3, 4 do not form one chain"),
                                                         HasSubstr("is 0.5"))));
}

TEST(PlanarCurve, RefusesUnknownAndRepeatedEdges) {
  const hotmesh::test::TempDir dir;
  const CadModel model = drawn(StepWallDrawing::edges, dir);
  EXPECT_THAT([&] { model.planar_curve(std::vector<int>{1, 9}); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("no edge 9: the edges are 1 to 4")));
  EXPECT_THAT([&] { model.planar_curve(std::vector<int>{2, 1, 2}); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("edge 2 is given twice")));
}

}  // namespace
}  // namespace hotmesh::geometry
