// Tests of the section 4.2 reconstruction: polynomial deflections are reproduced exactly,
// smooth ones converge at O(h^2) for q = 1 and O(h^4) for q = 3 (measured slopes), far nodes
// are reported by id and line, duplicates are merged, and nodes without CAD are ordered.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "curve_fixtures.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::HasSubstr;

/// FEM nodes on r at non-uniform parameters in [a, b], with deflection delta(t).
template <class Deflection>
CurveSamples nodes_on(const BSplineCurve2d& r, int count, Deflection delta, double a = 0.0, double b = 1.0) {
  CurveSamples s;
  s.source = "nodes.csv";
  for (int j = 0; j < count; ++j) {
    double t = a + (b - a) * j / (count - 1);
    if (j > 0 && j + 1 < count) t += 0.2 * (b - a) / (count - 1) * std::sin(7.0 * j);
    s.points.push_back(r.point(t));
    s.deflections.push_back(delta(t));
  }
  return s;
}

double max_error(const Reconstruction& fit, const BSplineCurve2d& r, auto delta) {
  double error = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = fit.report.fem_first + (fit.report.fem_last - fit.report.fem_first) * i / 2000.0;
    error = std::max(error, distance(fit.curve.point(t, 1.0), r.point(t) + delta(t)));
  }
  return error;
}

TEST(Reconstruction, DisplacementFormReproducesPolynomialDeflections) {
  const BSplineCurve2d r = test::quarter_circle(3.0);
  for (int q = 1; q <= 5; ++q) {
    const auto delta = [q](double t) { return Vec2{0.1 * std::pow(t - 0.4, q), 0.05 - 0.2 * std::pow(t, q) + t}; };
    ReconstructionOptions options;
    options.degree = q;
    options.form = DeflectionForm::displacement;
    const Reconstruction fit = reconstruct(r, nodes_on(r, 11, delta), options);
    EXPECT_LT(max_error(fit, r, delta), 1e-10) << "q = " << q;
    EXPECT_LT(fit.report.max_node_residual, 1e-13);
    EXPECT_LT(fit.report.max_node_distance_to_cad, 1e-13);
  }
}

TEST(Reconstruction, CurveFormReproducesPolynomialCurves) {
  // r is a single cubic piece, polynomial in t: with a polynomial deflection c = r + delta
  // is a polynomial of degree <= q, which eq. (21) reproduces for q >= 3.
  const BSplineCurve2d r(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{0, 0}, {1, 2}, {3, -1}, {4, 1}});
  for (int q = 3; q <= 5; ++q) {
    const auto delta = [q](double t) { return Vec2{0.3 * std::pow(t, q), -0.1 * t}; };
    ReconstructionOptions options;
    options.degree = q;
    const Reconstruction fit = reconstruct(r, nodes_on(r, 9, delta), options);
    EXPECT_LT(max_error(fit, r, delta), 1e-10) << "q = " << q;
  }
  // Degree 1 reproduces a straight line moved by a linear deflection.
  const BSplineCurve2d line = BSplineCurve2d::polyline(std::vector<double>{0.0, 1.0}, std::vector<Vec2>{{0, 0}, {2, 1}});
  const auto linear = [](double t) { return Vec2{0.2 * t, 0.1 - 0.3 * t}; };
  EXPECT_LT(max_error(reconstruct(line, nodes_on(line, 5, linear)), line, linear), 1e-10);
}

/// Least-squares slope of log(error) against log(h).
double convergence_slope(DeflectionForm form, int q) {
  const BSplineCurve2d r = test::quarter_circle(2.0);
  const auto delta = [](double t) { return Vec2{0.05 * std::sin(3.0 * t + 0.3), 0.03 * std::cos(5.0 * t)}; };
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const int count : {9, 17, 33, 65, 129}) {
    ReconstructionOptions options;
    options.degree = q;
    options.form = form;
    const double error = max_error(reconstruct(r, nodes_on(r, count, delta), options), r, delta);
    const double x = std::log(1.0 / (count - 1));
    const double y = std::log(error);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(Reconstruction, ConvergesAtSecondOrderForLinearAndFourthForCubic) {
  for (const DeflectionForm form : {DeflectionForm::curve, DeflectionForm::displacement}) {
    const double linear = convergence_slope(form, 1);
    const double cubic = convergence_slope(form, 3);
    RecordProperty(std::string("slope_q1_") + to_string(form), std::to_string(linear));
    RecordProperty(std::string("slope_q3_") + to_string(form), std::to_string(cubic));
    std::cout << "form " << to_string(form) << ": slope q=1 " << linear << ", q=3 " << cubic << "\n";
    EXPECT_NEAR(linear, 2.0, 0.15) << to_string(form);
    EXPECT_NEAR(cubic, 4.0, 0.3) << to_string(form);
  }
}

TEST(Reconstruction, CurveFormFollowsChordsDisplacementFormKeepsTheArc) {
  // Zero deflection on a coarse quarter circle: the displacement form is the arc itself, the
  // curve form (q = 1) the polyline through the nodes, off the arc by the chord height.
  const BSplineCurve2d r = test::quarter_circle(1.0);
  const CurveSamples s = nodes_on(r, 5, [](double) { return Vec2{}; });
  ReconstructionOptions options;
  options.form = DeflectionForm::displacement;
  const Reconstruction keep = reconstruct(r, s, options);
  options.form = DeflectionForm::curve;
  const Reconstruction chord = reconstruct(r, s, options);
  double keep_error = 0.0;
  double chord_error = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double t = i / 400.0;
    keep_error = std::max(keep_error, std::abs(norm(keep.curve.point(t, 1.0)) - 1.0));
    chord_error = std::max(chord_error, std::abs(norm(chord.curve.point(t, 1.0)) - 1.0));
  }
  EXPECT_LT(keep_error, 1e-14);
  EXPECT_GT(chord_error, 0.01);  // sagitta of a 22.5-degree chord is 0.019
  EXPECT_LT(chord_error, 0.03);
}

TEST(Reconstruction, RejectsNodesFarFromTheCurveNamingThem) {
  const BSplineCurve2d r = test::quarter_circle(1.0);
  CurveSamples s = nodes_on(r, 6, [](double) { return Vec2{0.01, 0.0}; });
  s.ids = {101, 102, 103, 104, 105, 106};
  s.lines = {2, 3, 4, 5, 6, 7};
  s.points[2] = s.points[2] * 1.01;  // 0.01 off a curve of size sqrt(2): beyond 0.1 %
  s.points[4] = s.points[4] * 1.2;
  try {
    reconstruct(r, s);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_THAT(text, HasSubstr("nodes.csv: 2 of 6 FEM nodes are farther than 0.00141421"));
    EXPECT_THAT(text, HasSubstr("node 103 (line 4) at distance 0.01;"));
    EXPECT_THAT(text, HasSubstr("node 105 (line 6) at distance 0.2"));
  }
  ReconstructionOptions options;
  options.far_nodes = FarNodePolicy::drop;
  const Reconstruction fit = reconstruct(r, s, options);
  EXPECT_EQ(fit.report.used_nodes, 4u);
  ASSERT_EQ(fit.report.rejected_nodes.size(), 2u);
  EXPECT_EQ(fit.report.rejected_nodes[1].label, "node 105 (line 6)");
  EXPECT_NEAR(fit.report.rejected_nodes[1].distance, 0.2, 1e-12);
  options.tolerance = 0.05;  // an absolute tolerance keeps node 103
  EXPECT_EQ(reconstruct(r, s, options).report.used_nodes, 5u);
}

TEST(Reconstruction, MergesDuplicateNodesAndRejectsConflictingOnes) {
  const BSplineCurve2d r = test::quarter_circle(1.0);
  CurveSamples s = nodes_on(r, 5, [](double t) { return Vec2{t, 0.0}; });
  s.points.push_back(s.points[1]);
  s.deflections.push_back(s.deflections[1]);
  const Reconstruction fit = reconstruct(r, s);
  EXPECT_EQ(fit.report.nodes, 6u);
  EXPECT_EQ(fit.report.used_nodes, 5u);
  EXPECT_EQ(fit.report.merged_duplicates, 1u);
  s.deflections.back() = s.deflections.back() + Vec2{0.0, 0.5};
  EXPECT_THAT([&] { reconstruct(r, s); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("sample 2 and sample 6 are at the same place")));
}

TEST(Reconstruction, ChecksDegreeAndNodeCount) {
  const BSplineCurve2d r = test::quarter_circle(1.0);
  const CurveSamples s = nodes_on(r, 3, [](double) { return Vec2{}; });
  ReconstructionOptions options;
  options.degree = 3;
  EXPECT_THAT([&] { reconstruct(r, s, options); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("needs at least 4 FEM nodes at distinct places")));
  options.degree = 6;
  EXPECT_THAT([&] { reconstruct(r, s, options); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("must be 1 to 5, got 6")));
  EXPECT_THAT([&] { reconstruct(r, CurveSamples{}); }, ::testing::ThrowsMessage<InputError>(HasSubstr("no FEM nodes")));
}

TEST(Reconstruction, ExtendsTheEndDeflectionBeyondTheNodes) {
  const BSplineCurve2d r = test::quarter_circle(1.0);
  const Reconstruction fit = reconstruct(r, nodes_on(r, 5, [](double t) { return Vec2{0.0, 0.1 * t}; }, 0.2, 0.7));
  EXPECT_NEAR(fit.report.fem_first, 0.2, 1e-12);
  EXPECT_NEAR(fit.report.fem_last, 0.7, 1e-12);
  EXPECT_NEAR(fit.curve.deflection(0.0).y, 0.02, 1e-12);
  EXPECT_NEAR(fit.curve.deflection(1.0).y, 0.07, 1e-12);
}

TEST(OrderAlongCurve, RecoversTheOrderOfShuffledNodes) {
  // Nodes on a spiral arc, unevenly spaced, shuffled.
  std::vector<Vec2> ordered;
  for (int j = 0; j < 60; ++j) {
    const double s = std::pow(j / 59.0, 1.5) * 4.0;
    ordered.push_back({(1.0 + 0.3 * s) * std::cos(s), (1.0 + 0.3 * s) * std::sin(s)});
  }
  std::vector<std::size_t> shuffle(ordered.size());
  for (std::size_t i = 0; i < shuffle.size(); ++i) shuffle[i] = i;
  std::shuffle(shuffle.begin(), shuffle.end(), std::mt19937(7));
  std::vector<Vec2> points;
  for (const std::size_t i : shuffle) points.push_back(ordered[i]);
  const std::vector<std::size_t> order = order_along_curve(points);
  std::vector<std::size_t> recovered;
  for (const std::size_t i : order) recovered.push_back(shuffle[i]);
  std::vector<std::size_t> expected(ordered.size());
  for (std::size_t i = 0; i < expected.size(); ++i) expected[i] = ordered.size() - 1 - i;  // starts at smaller x
  EXPECT_EQ(recovered, expected);
}

TEST(OrderAlongCurve, InsertsNodesBesideTheSpine) {
  // A zig-zag: node 3 is nearer to node 1 than the spine makes it look.
  const std::vector<Vec2> points{{0, 0}, {1, 0}, {2, 0}, {1.5, 0.1}, {3, 0}};
  const std::vector<std::size_t> order = order_along_curve(points);
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 3, 2, 4}));
}

TEST(Reconstruction, WithoutCadUsesThePolylineThroughOrderedNodes) {
  CurveSamples s;
  s.source = "ramp.csv";
  const std::vector<Vec2> q{{2, 0}, {0, 0}, {2, 0.5}, {1, 0}, {0.5, 0}, {2, 1}};
  for (const Vec2& p : q) {
    s.points.push_back(p);
    s.deflections.push_back({0.0, 0.1 * p.x});
  }
  const Reconstruction fit = reconstruct_from_nodes(s);
  const BSplineCurve2d& r = fit.curve.undeformed();
  EXPECT_EQ(r.degree(), 1);
  EXPECT_EQ(r.poles(), (std::vector<Vec2>{{0, 0}, {0.5, 0}, {1, 0}, {2, 0}, {2, 0.5}, {2, 1}}));
  EXPECT_EQ(r.first_parameter(), 0.0);
  EXPECT_EQ(r.last_parameter(), 1.0);
  EXPECT_NEAR(r.knots()[4], 2.0 / 3.0, 1e-15);  // parameter of (2, 0): chord length so far
  for (std::size_t i = 0; i < r.poles().size(); ++i) {
    const Vec2 p = r.poles()[i];
    EXPECT_NEAR(distance(fit.curve.point(r.knots()[i + 1], 1.0), p + Vec2{0.0, 0.1 * p.x}), 0.0, 1e-14) << i;
  }
  EXPECT_EQ(fit.report.max_node_distance_to_cad, 0.0);
}

TEST(CurveSamples, CartesianNodesBecomeRadialAndAxialAboutTheAxis) {
  DeflectionSamples samples;
  samples.frame = SampleFrame::cartesian;
  samples.source = "fem.csv";
  const Axis axis({1, 0, 0}, {0, 0, 2});
  const double theta = std::numbers::pi / 3;
  const Vec3 radial{std::cos(theta), std::sin(theta), 0.0};
  const Vec3 around{-std::sin(theta), std::cos(theta), 0.0};
  samples.points.push_back(Vec3{1, 0, 0} + 2.0 * radial + Vec3{0, 0, 5});
  samples.deflections.push_back(0.1 * radial + 0.2 * around + Vec3{0, 0, -0.3});
  const CurveSamples s = meridional_samples(samples, axis);
  EXPECT_NEAR(s.points[0].x, 2.0, 1e-15);
  EXPECT_NEAR(s.points[0].y, 5.0, 1e-15);
  EXPECT_NEAR(s.deflections[0].x, 0.1, 1e-15);
  EXPECT_NEAR(s.deflections[0].y, -0.3, 1e-15);
  EXPECT_NEAR(s.max_out_of_plane_deflection, 0.2, 1e-15);
  samples.frame = SampleFrame::planar;
  EXPECT_THAT([&] { meridional_samples(samples, axis); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("fem.csv: an axisymmetric boundary needs")));
}

}  // namespace
}  // namespace hotmesh::geometry
