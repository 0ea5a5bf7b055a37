// Tests of deflection fields joined along edges that cross a face's parameter rectangle
// (trimmed faces, issue 23 item 1): a curved fence standing on a plate, its foot a curve across
// the plate's rectangle, found by geometry (the fence's side lies on the plate) or named by the
// CAD file (CadFace::edges). The deflected faces meet along the foot where the fields fitted on
// their own do not.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "cad_test_helpers.hpp"
#include "hotmesh/geometry/surface_shape.hpp"

namespace hotmesh::geometry {
namespace {

/// The plate z = 0 over [-1, 1]^2, parameters (x, y).
BSplineSurface plate() {
  return BSplineSurface(1, 1, {-1, -1, 1, 1}, {-1, -1, 1, 1}, {{-1, -1, 0}, {-1, 1, 0}, {1, -1, 0}, {1, 1, 0}});
}

/// A fence 0.5 high whose foot is the cubic Bezier curve through (-0.6, 0), (-0.2, 0.4),
/// (0.2, 0.4), (0.6, 0) (parameter u), rising along v.
BSplineSurface fence() {
  const std::array<Vec3, 4> foot{Vec3{-0.6, 0, 0}, Vec3{-0.2, 0.4, 0}, Vec3{0.2, 0.4, 0}, Vec3{0.6, 0, 0}};
  std::vector<Vec3> poles;
  for (const Vec3& p : foot) poles.insert(poles.end(), {p, p + Vec3{0, 0, 0.5}});
  return BSplineSurface(3, 1, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 1, 1}, poles);
}

/// A straight foot along y = 0 from x = -0.5 to 0.5, as edge 7 of the CAD file.
FaceEdge straight_foot() {
  FaceEdge foot{7, {}};
  for (int k = 0; k < kFaceEdgePoints; ++k) foot.points.push_back({-0.5 + k / (kFaceEdgePoints - 1.0), 0.0, 0.0});
  return foot;
}

/// The plate trimmed to y <= 0, its loop the straight foot (edge 7) and free edges (the rest of
/// y = 0 and the rectangle's other sides).
CadFace plate_ending_at(const FaceEdge& foot) {
  CadFace half{1, plate(), {foot}, {}};
  half.trims = {{7, {{-0.5, 0.0}, {0.5, 0.0}}},
                {0, {{0.5, 0.0}, {1.0, 0.0}, {1.0, -1.0}, {-1.0, -1.0}, {-1.0, 0.0}, {-0.5, 0.0}}}};
  return half;
}

Vec3 field(const Vec3& p) {
  return {0.01 * std::sin(2.0 * p.x + p.y), 0.02 * std::cos(3.0 * p.y) + 0.01 * p.z,
          0.03 * std::sin(p.x) * std::cos(2.0 * p.y) + 0.02 * p.z * p.z};
}

/// FEM nodes scattered over both faces, none on the foot.
DeflectionSamples scattered_nodes() {
  DeflectionSamples s;
  s.frame = SampleFrame::cartesian;
  s.source = "wall.csv";
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const BSplineSurface f = fence();
  for (int k = 0; k < 500; ++k) s.points.push_back({2.0 * unit(random) - 1.0, 2.0 * unit(random) - 1.0, 0.0});
  for (int k = 0; k < 200; ++k) s.points.push_back(f.point(unit(random), 0.02 + 0.98 * unit(random)));
  for (const Vec3& p : s.points) s.deflections.push_back(field(p));
  return s;
}

/// The largest difference between the two faces' fields along the foot, at 400 points.
double gap_along_foot(const std::vector<BSplineSurface>& fields) {
  const BSplineSurface f = fence();
  double gap = 0.0;
  for (int k = 0; k <= 400; ++k) {
    const double u = k / 400.0;
    const Vec3 p = f.point(u, 0.0);
    gap = std::max(gap, distance(fields[1].point(u, 0.0), fields[0].point(p.x, p.y)));
  }
  return gap;
}

// The fence's foot found by geometry (its side lies inside the plate's rectangle), or named by
// the CAD file as one edge of both faces: either way one shared edge, joined, the deflected
// faces meeting along it to 1e-10 of the wall's size where the fields fitted on their own differ
// by 1e-5; and the fields still as accurate as the fits beside the foot.
TEST(TraceJoins, AFenceStandingOnAPlateMeetsItAlongItsFoot) {
  const DeflectionSamples nodes = scattered_nodes();
  ReconstructionOptions options{.degree = 3};
  options.far_nodes = FarNodePolicy::drop;
  const std::vector<BSplineSurface> alone{reconstruct_on_faces({{{1, plate()}}}, nodes, options).fields[0],
                                          reconstruct_on_faces({{{2, fence()}}}, nodes, options).fields[0]};
  const double unjoined = gap_along_foot(alone);
  EXPECT_GT(unjoined, 1e-6);

  FaceEdge foot{7, {}};
  for (int k = 0; k < kFaceEdgePoints; ++k) foot.points.push_back(fence().point(k / (kFaceEdgePoints - 1.0), 0.0));
  for (const bool named : {false, true}) {
    SCOPED_TRACE(named ? "named by the CAD file" : "found by geometry");
    std::vector<CadFace> faces{{1, plate(), {}}, {2, fence(), {}}};
    if (named) {
      faces[0].edges.push_back(foot);
      faces[1].edges.push_back(foot);
    }
    const FaceDeflections joined = reconstruct_on_faces(faces, nodes, {.degree = 3});
    EXPECT_EQ(joined.report.shared_edges, 1u);
    EXPECT_EQ(joined.report.joined_edges, 1u);
    const double size = std::sqrt(2.0 * 2.0 + 2.0 * 2.0 + 0.5 * 0.5);
    EXPECT_LT(joined.report.max_edge_gap, 1e-10 * size);
    EXPECT_LT(gap_along_foot(joined.fields), 1e-10 * size);
    // The plate, the trimmed face, leads: its field is the one fitted alone. The fence's row
    // along its foot follows it (its knots along the foot refined: more poles that way only),
    // so along the foot the fence is as accurate as the plate's fit.
    for (std::size_t i = 0; i < alone[0].poles().size(); ++i) {
      EXPECT_EQ(joined.fields[0].poles()[i], alone[0].poles()[i]) << i;
    }
    EXPECT_GT(joined.fields[1].u_count(), alone[1].u_count());
    EXPECT_EQ(joined.fields[1].v_count(), alone[1].v_count());
    double plate_error = 0.0, fence_error = 0.0;
    for (int k = 0; k <= 100; ++k) {
      const Vec3 p = fence().point(k / 100.0, 0.0);
      plate_error = std::max(plate_error, distance(joined.fields[0].point(p.x, p.y), field(p)));
      fence_error = std::max(fence_error, distance(joined.fields[1].point(k / 100.0, 0.0), field(p)));
    }
    EXPECT_LT(fence_error, plate_error + 1e-10 * size);
    EXPECT_LT(plate_error, 1e-4);  // of deflections up to 0.04
  }
}

// The fence reaching below the plate, trimmed at its foot as the plate is: the foot crosses
// both faces' rectangles (the plate's diagonally to its knot lines), a side of neither. Both
// fields are corrected towards their mean along it, smoothly, their spans along it halved until
// they meet to 1e-10 of the wall's size where the fits alone differ by 5e-5: checked at 2000
// points along the foot, so no spike between the points the correction was fitted at. Along
// the foot the joined field is no worse than the worse of the two fits, and at the nodes the
// residuals grow by less than the gap closed.
TEST(TraceJoins, AFootThatTrimsBothFacesIsJoined) {
  const double foot_v = 2.0 / 7.0;  // the fence rises from 0.2 below the plate to 0.5 above it
  const BSplineSurface base = fence();
  std::vector<Vec3> poles;
  for (std::size_t i = 0; i < base.u_count(); ++i) {
    const Vec3 foot = base.poles()[2 * i];
    poles.insert(poles.end(), {foot - Vec3{0, 0, 0.2}, foot + Vec3{0, 0, 0.5}});
  }
  const BSplineSurface deep(3, 1, base.u_knots(), base.v_knots(), poles);
  FaceEdge foot{7, {}};
  for (int k = 0; k < kFaceEdgePoints; ++k) foot.points.push_back(deep.point(k / (kFaceEdgePoints - 1.0), foot_v));
  // The nodes of the fence above the plate, and of the plate away from the foot (a node near it
  // would be a sample of both faces, its deflection put at its projection onto the fence).
  const DeflectionSamples all = scattered_nodes();
  DeflectionSamples nodes = all;
  nodes.points.clear();
  nodes.deflections.clear();
  for (std::size_t i = 0; i < all.points.size(); ++i) {
    double to_foot = 1.0;
    for (const Vec3& f : foot.points) to_foot = std::min(to_foot, distance(f, all.points[i]));
    if (all.points[i].z != 0.0 || to_foot > 0.05) {
      nodes.points.push_back(all.points[i]);
      nodes.deflections.push_back(all.deflections[i]);
    }
  }
  const std::vector<CadFace> faces{{1, plate(), {foot}, {}}, {2, deep, {foot}, {}}};
  ReconstructionOptions options{.degree = 3};
  options.far_nodes = FarNodePolicy::drop;
  const FaceDeflections plate_alone = reconstruct_on_faces({{faces[0]}}, nodes, options);
  const FaceDeflections fence_alone = reconstruct_on_faces({{faces[1]}}, nodes, options);
  const std::vector<BSplineSurface> alone{plate_alone.fields[0], fence_alone.fields[0]};
  // The gap along the foot, and the larger of the two fields' errors there.
  const auto gap = [&](const std::vector<BSplineSurface>& fields, double& error) {
    double largest = 0.0;
    error = 0.0;
    for (int k = 0; k <= 2000; ++k) {
      const double u = k / 2000.0;
      const Vec3 p = deep.point(u, foot_v);
      largest = std::max(largest, distance(fields[1].point(u, foot_v), fields[0].point(p.x, p.y)));
      error = std::max({error, distance(fields[0].point(p.x, p.y), field(p)), distance(fields[1].point(u, foot_v), field(p))});
    }
    return largest;
  };
  double alone_error = 0.0, joined_error = 0.0;
  const double unjoined = gap(alone, alone_error);
  EXPECT_GT(unjoined, 1e-6);
  const FaceDeflections joined = reconstruct_on_faces(faces, nodes, options);
  EXPECT_EQ(joined.report.shared_edges, 1u);
  EXPECT_EQ(joined.report.joined_edges, 1u);
  const double size = std::sqrt(2.0 * 2.0 + 2.0 * 2.0 + 0.7 * 0.7);
  EXPECT_LT(joined.report.max_edge_gap, 1e-10 * size);
  EXPECT_LT(gap(joined.fields, joined_error), 1e-10 * size);
  EXPECT_LE(joined_error, alone_error);
  // The correction moves each field by at most about half the gap it closes.
  EXPECT_LT(joined.report.max_node_residual,
            std::max(plate_alone.report.max_node_residual, fence_alone.report.max_node_residual) + unjoined);
}

// A fence leaning at 30 degrees, its surface running on below the plate that trims it: a plate
// node 4e-3 beside the foot, on the side the surface runs on under, is within the tolerance
// (2.9e-3) of that surface (2e-3 away) but not of the fence (the foot is 4e-3 away). It is a
// sample of the plate only: its deflection is not put onto the fence below the plate.
TEST(TraceJoins, ANodeBesideAFootIsNoSampleOfTheSurfaceBeyondTheTrimmingCurve) {
  const double lean = M_PI / 6.0;
  const Vec3 up{0.0, std::cos(lean), std::sin(lean)};
  const double foot_v = 2.0 / 7.0;
  const Vec3 left{-0.5, 0, 0}, right{0.5, 0, 0};
  const FaceEdge foot = straight_foot();
  CadFace fence{2,
                BSplineSurface(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1},
                               {left - 0.2 * up, left + 0.5 * up, right - 0.2 * up, right + 0.5 * up}),
                {foot},
                {}};
  fence.trims = {{7, {{0.0, foot_v}, {1.0, foot_v}}}, {0, {{1.0, foot_v}, {1.0, 1.0}, {0.0, 1.0}, {0.0, foot_v}}}};
  DeflectionSamples nodes;
  nodes.frame = SampleFrame::cartesian;
  nodes.source = "wall.csv";
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= 4; ++j) {
      nodes.points.push_back({-1.0 + 0.5 * i, -1.0 + 0.5 * j, 0.0});
      nodes.points.push_back(fence.surface.point(0.25 * i, foot_v + (1.0 - foot_v) * 0.25 * j));
    }
  }
  const std::size_t beside = nodes.points.size();
  nodes.points.push_back({0.2, -4e-3, 0.0});
  for (const Vec3& p : nodes.points) nodes.deflections.push_back(field(p));
  const std::vector<CadFace> faces{{1, plate(), {foot}, {}}, fence};
  const FaceDeflections fit = reconstruct_on_faces(faces, nodes, {.degree = 1});
  ASSERT_GT(fit.report.tolerance, 2.5e-3);  // 1e-3 of the faces' size
  ASSERT_LT(fit.report.tolerance, 4e-3);
  std::vector<std::size_t> faces_of_beside;
  for (const NodePlacement& p : fit.placements) {
    if (p.node == beside) faces_of_beside.push_back(p.face);
  }
  EXPECT_EQ(faces_of_beside, std::vector<std::size_t>{0});
}

// A fence on a plate is a crease along its foot: the plate is trimmed there, the fence's side
// crosses the plate's rectangle. Upright it turns the wall by 90 degrees; leaning at 30 degrees
// to the plate (or its mirror image, at 150) by 30. The crease's point nearest a point is on the
// foot, with both faces' normals, undeformed and after a deflection that shifts the wall; a
// point of either face on the foot lies on the crease (each face a shape of its own, so that a
// node there slides along the foot), one beside it does not.
TEST(TraceJoins, AFenceMeetsThePlateItStandsOnAtACrease) {
  for (const double degrees : {90.0, 30.0, 150.0}) {
    SCOPED_TRACE(degrees);
    const double lean = degrees * M_PI / 180.0;
    const Vec3 up{0.0, std::cos(lean), std::sin(lean)};
    const BSplineSurface leaning(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1},
                                 {{-0.5, 0, 0}, Vec3{-0.5, 0, 0} + 0.5 * up, {0.5, 0, 0}, Vec3{0.5, 0, 0} + 0.5 * up});
    std::vector<Vec3> points, deflections;
    for (int i = 0; i <= 4; ++i) {
      for (int j = 0; j <= 4; ++j) {
        points.push_back({-1.0 + 0.5 * i, -1.0 + 0.5 * j, 0.0});
        points.push_back(leaning.point(0.25 * i, 0.25 * j));
      }
    }
    const Vec3 shift{0.01, 0.02, 0.03};
    deflections.assign(points.size(), shift);
    DeflectionSamples nodes;
    nodes.frame = SampleFrame::cartesian;
    nodes.source = "wall.csv";
    nodes.points = points;
    nodes.deflections = deflections;
    const SurfaceShapeFit fit = make_surface_shape({{1, plate()}, {2, leaning}}, nodes, {.degree = 1});
    const auto creases = fit.shape->creases(25.0 * M_PI / 180.0);
    ASSERT_EQ(creases.size(), 1u);
    EXPECT_EQ(creases[0].faces, (std::array<int, 2>{1, 0}));  // the fence's side first
    EXPECT_NEAR(creases[0].angle, degrees == 150.0 ? M_PI / 6.0 : lean, 1e-6);
    EXPECT_TRUE(fit.shape->creases(creases[0].angle + 0.01).empty());
    for (const double lambda : {0.0, 1.0}) {
      const CreasePoint c = fit.shape->crease_point(creases[0], {0.2, 0.3, 0.4}, lambda);
      EXPECT_LT(distance(c.point, Vec3{0.2, lambda * shift.y, lambda * shift.z}), 1e-9) << lambda;
      EXPECT_NEAR(std::abs(dot(c.normals[1], Vec3{0, 0, 1})), 1.0, 1e-12);
      EXPECT_NEAR(dot(c.normals[0], up), 0.0, 1e-12);
    }
    EXPECT_EQ(fit.shape->crease_sides({0.7, 0.0, 1}, 25.0 * M_PI / 180.0).size(), 2u);  // the fence's foot
    EXPECT_EQ(fit.shape->crease_sides({0.2, 0.0, 0}, 25.0 * M_PI / 180.0).size(), 2u);  // the plate under it
    EXPECT_TRUE(fit.shape->crease_sides({0.2, 0.1, 0}, 25.0 * M_PI / 180.0).empty());  // the plate beside it
    EXPECT_TRUE(fit.shape->crease_sides({0.7, 0.0, 1}, creases[0].angle + 0.01).empty());
  }
}

// A plate that ends at the fence's foot (trimmed to y <= 0, its loop the foot and free edges),
// the foot an edge both faces name: the plate goes on to the side its loop keeps, so a fence
// leaning back over it at 150 degrees folds the wall by 150 degrees, and one leaning away at 30
// turns it by 30. Without the loop the two read alike (the test above).
TEST(TraceJoins, ATrimmedPlateTellsAFenceFoldingBackFromOneLeaningAway) {
  const FaceEdge foot = straight_foot();
  const CadFace half_plate = plate_ending_at(foot);
  for (const double degrees : {30.0, 150.0}) {
    SCOPED_TRACE(degrees);
    const double lean = degrees * M_PI / 180.0;
    const Vec3 up{0.0, std::cos(lean), std::sin(lean)};
    const BSplineSurface leaning(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1},
                                 {{-0.5, 0, 0}, Vec3{-0.5, 0, 0} + 0.5 * up, {0.5, 0, 0}, Vec3{0.5, 0, 0} + 0.5 * up});
    const auto wall = undeformed_surface_shape({half_plate, {2, leaning, {foot}, {}}});
    const auto creases = wall->creases(25.0 * M_PI / 180.0);
    ASSERT_EQ(creases.size(), 1u);
    EXPECT_NEAR(creases[0].angle, lean, 1e-6);
    EXPECT_EQ(wall->crease_sides({0.2, 0.0, 0}, 25.0 * M_PI / 180.0).size(), 2u);
    EXPECT_TRUE(wall->crease_sides({0.2, 0.0, 0}, lean + 0.01).empty());
  }
}

// The fence's surface reaching below the plate and trimmed by it, as the plate is trimmed by the
// fence: the foot crosses both faces' rectangles, a side of neither. It is a crease of the angle
// the fence leans at, told from its supplement by both faces' loops; its nearest point lies on
// the foot at both stages; points of either face on the foot lie on it, others not; and the
// faces are one crease region only for angles above the crease's.
TEST(TraceJoins, AnEdgeThatTrimsBothFacesIsACrease) {
  const FaceEdge foot = straight_foot();
  const CadFace half_plate = plate_ending_at(foot);
  const double foot_v = 2.0 / 7.0;  // where the fence's height, -0.2 to 0.5 along v, is 0
  for (const double degrees : {90.0, 30.0, 150.0}) {
    SCOPED_TRACE(degrees);
    const double lean = degrees * M_PI / 180.0;
    const Vec3 up{0.0, std::cos(lean), std::sin(lean)};
    const Vec3 left{-0.5, 0, 0}, right{0.5, 0, 0};
    CadFace fence{2,
                  BSplineSurface(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1},
                                 {left - 0.2 * up, left + 0.5 * up, right - 0.2 * up, right + 0.5 * up}),
                  {foot},
                  {}};
    fence.trims = {{7, {{0.0, foot_v}, {1.0, foot_v}}}, {0, {{1.0, foot_v}, {1.0, 1.0}, {0.0, 1.0}, {0.0, foot_v}}}};
    const Vec3 shift{0.01, 0.02, 0.03};
    std::vector<BSplineSurface> fields;
    for (const CadFace& f : {half_plate, fence}) {
      const ParameterRectangle r = f.surface.domain();
      fields.emplace_back(1, 1, std::vector<double>{r.u_first, r.u_first, r.u_last, r.u_last},
                          std::vector<double>{r.v_first, r.v_first, r.v_last, r.v_last}, std::vector<Vec3>(4, shift));
    }
    const auto wall = std::make_shared<SurfaceShape>(std::vector<CadFace>{half_plate, fence}, fields);
    const double min_angle = 25.0 * M_PI / 180.0;
    const auto creases = wall->creases(min_angle);
    ASSERT_EQ(creases.size(), 1u);
    EXPECT_EQ(creases[0].faces, (std::array<int, 2>{0, 1}));
    EXPECT_NEAR(creases[0].angle, lean, 1e-6);
    for (const double lambda : {0.0, 1.0}) {
      const CreasePoint c = wall->crease_point(creases[0], {0.2, 0.3, 0.4}, lambda);
      EXPECT_LT(distance(c.point, Vec3{0.2, lambda * shift.y, lambda * shift.z}), 1e-12) << lambda;
      EXPECT_NEAR(std::abs(c.normals[0].z), 1.0, 1e-12);
      EXPECT_NEAR(dot(c.normals[1], up), 0.0, 1e-12);
    }
    EXPECT_EQ(wall->crease_sides({0.2, 0.0, 0}, min_angle).size(), 2u);     // the plate at the foot
    EXPECT_EQ(wall->crease_sides({0.7, foot_v, 1}, min_angle).size(), 2u);  // the fence at the foot
    EXPECT_TRUE(wall->crease_sides({0.2, -0.1, 0}, min_angle).empty());     // the plate beside it
    EXPECT_TRUE(wall->crease_sides({0.7, 0.5, 1}, min_angle).empty());      // the fence above it
    EXPECT_TRUE(wall->crease_sides({0.2, 0.0, 0}, lean + 0.01).empty());
    EXPECT_NE(wall->crease_region(0, min_angle), wall->crease_region(1, min_angle));
    EXPECT_EQ(wall->crease_region(0, lean + 0.01), wall->crease_region(1, lean + 0.01));
    // Sliding on the fence below the foot is held at it.
    const ShapePoint below = wall->project_on_face(1, Vec3{0.2, 0.0, 0.0} - 0.1 * up + Vec3{0, 0, -0.05}, 0.0, kNoHint);
    EXPECT_NEAR(below.parameter.s, foot_v, 1e-9);
  }
}

// A tube of radius 0.5 standing in a hole of the plate, its surface running on below the plate
// that trims it, as the hole's circle trims the plate: a closed edge across both rectangles. On
// the plate the circle's trace starts and ends at angle 0; the crease's nearest point to a point
// just before that (angle -0.01) is found there, past the curve's end, not at its end.
TEST(TraceJoins, TheNearestPointOfAClosedTrimmingCurveIsFoundPastItsEnds) {
  constexpr int kAround = 1024;
  FaceEdge circle{9, {}};
  for (int k = 0; k < kFaceEdgePoints; ++k) {
    const double a = 2.0 * M_PI * k / (kFaceEdgePoints - 1.0);
    circle.points.push_back({0.5 * std::cos(a), 0.5 * std::sin(a), 0.0});
  }
  CadFace holed{1, plate(), {circle}, {}};
  std::vector<Vec2> round;
  for (int k = 0; k <= kAround; ++k) {
    const double a = 2.0 * M_PI * k / kAround;
    round.push_back({0.5 * std::cos(a), 0.5 * std::sin(a)});
  }
  round.back() = round.front();  // closed exactly, as a CAD file's circle
  holed.trims = {{0, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}}}, {9, round}};
  // The tube: a rational quadratic circle (9 poles) along u, z from -0.2 to 0.5 along v.
  const double w = std::sqrt(0.5);
  const std::array<Vec3, 9> ring{Vec3{1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0},
                                 {-1, -1, 0}, {0, -1, 0}, {1, -1, 0}, {1, 0, 0}};
  std::vector<Vec3> poles;
  std::vector<double> weights;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    for (const double z : {-0.2, 0.5}) {
      poles.push_back(0.5 * ring[i] + Vec3{0, 0, z});
      weights.push_back(i % 2 == 0 ? 1.0 : w);
    }
  }
  const double foot_v = 2.0 / 7.0;
  CadFace tube{2,
               BSplineSurface(2, 1, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, {0, 0, 1, 1}, poles, weights),
               {circle},
               {}};
  tube.trims = {{9, {{0.0, foot_v}, {0.25, foot_v}, {0.5, foot_v}, {0.75, foot_v}, {1.0, foot_v}}},
                {0, {{1.0, foot_v}, {1.0, 1.0}, {0.0, 1.0}, {0.0, foot_v}}}};
  const auto wall = undeformed_surface_shape({holed, tube});
  const auto creases = wall->creases(25.0 * M_PI / 180.0);
  ASSERT_EQ(creases.size(), 1u);
  EXPECT_NEAR(creases[0].angle, M_PI / 2.0, 1e-6);
  for (const double a : {-0.01, 0.01}) {  // before the end, after the start
    const CreasePoint c = wall->crease_point(creases[0], {0.6 * std::cos(a), 0.6 * std::sin(a), 0.1}, 0.0);
    // Within the spline through the trace's points (1 024 chords: 1e-8 of the circle); 5e-3
    // when the search stopped at the curve's end.
    EXPECT_LT(distance(c.point, Vec3{0.5 * std::cos(a), 0.5 * std::sin(a), 0.0}), 2e-8) << a;
  }
}

// A real CAD file: I-DEAS's cylinder, a B-rep solid of three rational B-spline faces, the
// lateral face (its u around the axis) and two caps whose circles trim their square
// rectangles. The caps meet the lateral face along its sides (circles across the caps'
// rectangles), named by the file's edges: two shared edges, whatever the order of the faces,
// along which the deflected faces meet a thousand times closer than the fits alone.
TEST(TraceJoins, TheCapsOfARealCylinderMeetItsSide) {
  const CadModel model = test::read_mm("OCC8842_cylinder_Ideas.igs");
  DeflectionSamples nodes;
  nodes.frame = SampleFrame::cartesian;
  nodes.source = "cylinder.csv";
  const auto deflection = [](const Vec3& p) {
    return Vec3{0.1 * std::sin(0.04 * p.y) + 0.008 * p.x, 0.1 * std::cos(0.03 * p.x), 0.006 * p.z + 0.0007 * p.y};
  };
  for (int i = 0; i < 24; ++i) {
    for (int j = 0; j <= 12; ++j) {
      const double angle = 2.0 * M_PI * i / 24.0;
      nodes.points.push_back({25.0 * std::cos(angle), -75.0 + 12.5 * j, 25.0 * std::sin(angle)});
    }
  }
  for (const double y : {-75.0, 75.0}) {
    for (const double r : {0.0, 7.5, 15.0, 22.5}) {
      for (int i = 0; i < (r == 0.0 ? 1 : 12); ++i) {
        nodes.points.push_back({r * std::cos(2.0 * M_PI * i / 12.0 + r), y, r * std::sin(2.0 * M_PI * i / 12.0 + r)});
      }
    }
  }
  for (const Vec3& p : nodes.points) nodes.deflections.push_back(deflection(p));
  // The gap along both circles, between the lateral face (position `side`) and each cap.
  const auto gap = [&](const std::vector<CadFace>& faces, const std::vector<BSplineSurface>& fields, std::size_t side) {
    const SurfaceProjector lateral({bspline_patch(faces[side].surface)});
    double largest = 0.0;
    for (std::size_t cap = 0; cap < faces.size(); ++cap) {
      if (cap == side) continue;
      const SurfaceProjector disc({bspline_patch(faces[cap].surface)});
      for (int k = 0; k < 360; ++k) {
        const double angle = 2.0 * M_PI * (k + 0.5) / 360.0;
        const Vec3 p{25.0 * std::cos(angle), faces[cap].surface.point(0.0, 0.0).y, 25.0 * std::sin(angle)};
        const SurfaceParameter on_side = lateral.project(p).where, on_cap = disc.project(p).where;
        largest = std::max(largest, distance(fields[side].point(on_side.u, on_side.v), fields[cap].point(on_cap.u, on_cap.v)));
      }
    }
    return largest;
  };
  std::vector<CadFace> faces{model.cad_face(2), model.cad_face(1), model.cad_face(3)};  // a cap first
  ReconstructionOptions options{.degree = 3};
  options.far_nodes = FarNodePolicy::drop;
  std::vector<BSplineSurface> alone;
  for (const CadFace& f : faces) alone.push_back(reconstruct_on_faces({{f}}, nodes, options).fields[0]);
  const double unjoined = gap(faces, alone, 1);
  const FaceDeflections joined = reconstruct_on_faces(faces, nodes, {.degree = 3});
  EXPECT_EQ(joined.report.shared_edges, 2u);
  EXPECT_LT(gap(faces, joined.fields, 1), 1e-3 * unjoined);  // 1.6e-3 alone, 2e-7 joined
  EXPECT_LT(joined.report.max_edge_gap, 1e-3 * unjoined);
  EXPECT_LT(joined.report.max_edge_gap, 1e-8 * 170.0);  // of the wall's size
}

}  // namespace
}  // namespace hotmesh::geometry
