// Tests of walls on CAD faces of any shape (section 4.2 on surfaces, issue 23): FEM nodes
// projected onto the faces, d(t, s) per face, the deflected faces as a BoundaryShape; and the
// scattered-data motion of prescribed walls without CAD.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/surface_shape.hpp"
#include "occt_surfaces.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

/// The bilinear face [x0, x1] x [y0, y1] of the plane z = 0, parameters (x, y).
BSplineSurface flat_face(double x0, double x1, double y0, double y1) {
  return BSplineSurface(1, 1, {x0, x0, x1, x1}, {y0, y0, y1, y1}, {{x0, y0, 0}, {x0, y1, 0}, {x1, y0, 0}, {x1, y1, 0}});
}

DeflectionSamples cartesian(std::vector<Vec3> points, std::vector<Vec3> deflections) {
  DeflectionSamples s;
  s.frame = SampleFrame::cartesian;
  s.points = std::move(points);
  s.deflections = std::move(deflections);
  s.source = "wall.csv";
  return s;
}

/// FEM nodes at S(u_i, v_j) on an n x n grid of the face's parameters, with deflection f(u, v).
template <class F>
DeflectionSamples grid_samples(const BSplineSurface& s, int n, F f) {
  const ParameterRectangle r = s.domain();
  std::vector<Vec3> points, deflections;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = r.u_first + (r.u_last - r.u_first) * i / (n - 1);
      const double v = r.v_first + (r.v_last - r.v_first) * j / (n - 1);
      points.push_back(s.point(u, v));
      deflections.push_back(f(u, v));
    }
  }
  return cartesian(points, deflections);
}

// Deflections that are polynomials of degree <= q in (t, s), given at a grid of FEM nodes, are
// reproduced by the deflected face to round-off everywhere (global interpolation, eq. 21 in
// each direction), on a rational face too.
TEST(SurfaceShape, ReproducesPolynomialDeflectionsOfDegreeQ) {
  for (const auto& occt : {test::occt_wavy(), test::occt_wavy_rational()}) {
    const BSplineSurface face = test::from_occt(occt);
    for (int q = 1; q <= 3; ++q) {
      const auto f = [q](double u, double v) {
        const double a = std::pow(u, q) * v, b = u * std::pow(v, q), c = std::pow(u * v, q);
        return Vec3{0.01 * a - 0.002, -0.02 * b + 0.001 * u, 0.005 * c + 0.003 * v};
      };
      const SurfaceShapeFit fit = make_surface_shape({{7, face}}, grid_samples(face, 7, f), {.degree = q});
      ASSERT_EQ(fit.report.faces.size(), 1u);
      EXPECT_EQ(fit.report.faces[0].face, 7);
      EXPECT_EQ(fit.report.faces[0].fit.method, SurfaceFitMethod::interpolation);
      EXPECT_EQ(fit.report.used_nodes, 49u);
      std::mt19937 random(static_cast<unsigned>(q));
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      const ParameterRectangle r = face.domain();
      for (int k = 0; k < 50; ++k) {
        const double u = r.u_first + (r.u_last - r.u_first) * unit(random);
        const double v = r.v_first + (r.v_last - r.v_first) * unit(random);
        const Vec3 expected = face.point(u, v) + 0.5 * f(u, v);
        EXPECT_LT(distance(fit.shape->at({u, v, 0}, 0.5, {}).point, expected), 1e-12) << "q " << q;
        EXPECT_LT(distance(fit.shape->at({u, v, 0}, 0.0, {}).point, face.point(u, v)), 1e-14);
      }
    }
  }
}

// A smooth deflection of a cylinder (a rational face) from scattered FEM nodes: the deflected
// face converges to the exact one as the nodes get denser, at about the order q + 1 of the fit
// (measured orders printed; docs/method-reconstruction.md records them).
TEST(SurfaceShape, ConvergesOnASmoothFieldFromScatteredNodes) {
  const BSplineSurface face = test::from_occt(test::occt_cylinder());
  const ParameterRectangle r = face.domain();
  const auto deflection = [](const Vec3& x) {
    return 0.01 * Vec3{std::sin(x.x + 0.5 * x.z), std::cos(0.7 * x.y), 0.3 * x.x * std::cos(0.5 * x.z)};
  };
  for (int q = 1; q <= 2; ++q) {
    std::vector<double> errors;
    for (const int n : {8, 16, 32}) {
      std::mt19937 random(11);
      std::uniform_real_distribution<double> jitter(-0.3, 0.3);
      std::vector<Vec3> points, deflections;
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          const double a = std::clamp((i + (i > 0 && i < n ? jitter(random) : 0.0)) / n, 0.0, 1.0);
          const double b = std::clamp((j + (j > 0 && j < n ? jitter(random) : 0.0)) / n, 0.0, 1.0);
          points.push_back(face.point(r.u_first + a * (r.u_last - r.u_first), r.v_first + b * (r.v_last - r.v_first)));
          deflections.push_back(deflection(points.back()));
        }
      }
      const SurfaceShapeFit fit = make_surface_shape({{1, face}}, cartesian(points, deflections), {.degree = q});
      EXPECT_EQ(fit.report.faces[0].fit.method, SurfaceFitMethod::least_squares);
      double worst = 0.0;
      for (int i = 0; i <= 40; ++i) {
        for (int j = 0; j <= 40; ++j) {
          const double u = r.u_first + (r.u_last - r.u_first) * i / 40.0;
          const double v = r.v_first + (r.v_last - r.v_first) * j / 40.0;
          const Vec3 x = face.point(u, v);
          worst = std::max(worst, distance(fit.shape->at({u, v, 0}, 1.0, {}).point, x + deflection(x)));
        }
      }
      errors.push_back(worst / 0.01);
    }
    const double order = std::log2(errors[1] / errors[2]);
    std::printf("cylinder, scattered nodes, q = %d: relative errors %.3g %.3g %.3g, order %.2f then %.2f\n", q,
                errors[0], errors[1], errors[2], std::log2(errors[0] / errors[1]), order);
    EXPECT_GT(order, q + 0.5) << "q " << q;
  }
}

// Sliding nodes are projected onto the deflected faces of a stage: the point found lies on that
// stage (S + lambda d at its parameters) and the offset is normal to it; a warm start from the
// previous parameters lands at the same place.
TEST(SurfaceShape, ProjectsOntoTheDeflectedFacesOfAStage) {
  const BSplineSurface face = test::from_occt(test::occt_wavy());
  const auto f = [](double u, double v) { return Vec3{0.02 * std::sin(2 * u), 0.01 * v * v, 0.05 * std::cos(u + v)}; };
  const SurfaceShapeFit fit = make_surface_shape({{1, face}}, grid_samples(face, 9, f), {.degree = 3});
  const ParameterRectangle r = face.domain();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.1, 0.9);
  for (int k = 0; k < 100; ++k) {
    const double u = r.u_first + (r.u_last - r.u_first) * unit(random);
    const double v = r.v_first + (r.v_last - r.v_first) * unit(random);
    const double lambda = 0.25 * (k % 5);
    const ShapePoint on = fit.shape->at({u, v, 0}, lambda, {});
    const Vec3 p = on.point + 0.01 * (unit(random) - 0.5) * on.normal;
    const ShapePoint q = fit.shape->project(p, lambda);
    EXPECT_LT(distance(q.point, fit.shape->at(q.parameter, lambda, {}).point), 1e-12);
    EXPECT_LT(norm(cross(p - q.point, q.normal)), 1e-9) << k;
    const ShapePoint warm = fit.shape->project(p + Vec3{1e-4, 0, 0}, lambda, q.parameter);
    EXPECT_LT(distance(warm.point, fit.shape->project(p + Vec3{1e-4, 0, 0}, lambda).point), 1e-10);
  }
}

// Two faces joined along an edge: the FEM nodes on the edge are samples of both, so with the
// nodes on grids the two deflected faces meet exactly along it.
TEST(SurfaceShape, FacesSharingAnEdgeMeetAfterTheDeflection) {
  const std::vector<CadFace> faces{{1, flat_face(0, 1, 0, 1)}, {2, flat_face(1, 2, 0, 1)}};
  std::vector<Vec3> points, deflections;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 4; ++j) {
      points.push_back({0.25 * i, 0.25 * j, 0.0});
      deflections.push_back({0.0, 0.0, 0.05 * std::sin(3.0 * points.back().x) * std::cos(2.0 * points.back().y)});
    }
  }
  const SurfaceShapeFit fit = make_surface_shape(faces, cartesian(points, deflections), {.degree = 1});
  EXPECT_EQ(fit.report.used_nodes, 45u);
  EXPECT_EQ(fit.report.faces[0].nodes + fit.report.faces[1].nodes, 45u + 5u);  // the edge's 5 nodes on both
  EXPECT_LT(fit.report.max_edge_gap, 1e-14);
  for (int j = 0; j <= 10; ++j) {
    const double y = 0.1 * j;
    EXPECT_LT(distance(fit.shape->at({1.0, y, 0}, 1.0, {}).point, fit.shape->at({1.0, y, 1}, 1.0, {}).point), 1e-14);
  }
  // A point of the deflected edge lies on the deflected wall, whichever face takes it.
  EXPECT_LT(fit.shape->project(fit.shape->at({1.0, 0.5, 0}, 1.0, {}).point, 1.0).distance, 1e-12);
}

/// The bilinear face with corners p00 (u first, v first), p10 (u last, v first), p01 and p11,
/// parameters [u0, u1] x [v0, v1].
BSplineSurface quad_face(Vec3 p00, Vec3 p10, Vec3 p01, Vec3 p11, double u0 = 0, double u1 = 1, double v0 = 0,
                         double v1 = 1) {
  return BSplineSurface(1, 1, {u0, u0, u1, u1}, {v0, v0, v1, v1}, {p00, p01, p10, p11});
}

/// FEM nodes scattered at random over the square [0, 2]^2 of the plane z = 0, none within 0.01
/// of the lines x = 1 and y = 1 (farther than the default distance tolerance, so each lies on
/// one face only), with deflection f(x, y).
template <class F>
DeflectionSamples scattered_on_square(int n, F f) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 2.0);
  std::vector<Vec3> points, deflections;
  while (static_cast<int>(points.size()) < n) {
    const Vec3 p{unit(random), unit(random), 0.0};
    if (std::abs(p.x - 1.0) < 0.01 || std::abs(p.y - 1.0) < 0.01) continue;
    points.push_back(p);
    deflections.push_back(f(p.x, p.y));
  }
  return cartesian(points, deflections);
}

// Issue 23 item 1: four faces of the square [0, 2]^2 meeting at (1, 1), each parametrised its
// own way (directions turned and reversed, other ranges), with FEM nodes scattered so that each
// face's field is a least-squares fit and none of them lies on an edge. The fields are joined:
// the deflected faces meet along every shared edge and at the common corner to round-off, while
// the fit keeps its accuracy, and a cubic field is still reproduced exactly.
TEST(SurfaceShape, ScatteredFitsOnFacesSharingEdgesAreJoinedSoTheDeflectedFacesMeet) {
  const std::vector<CadFace> faces{
      {1, quad_face({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0})},
      {2, quad_face({2, 0, 0}, {1, 0, 0}, {2, 1, 0}, {1, 1, 0}, 3.0, 5.0)},            // u from x = 2 to x = 1
      {3, quad_face({0, 2, 0}, {0, 1, 0}, {1, 2, 0}, {1, 1, 0}, 0.0, 1.0, -1.0, 2.0)},  // u along -y, v along x
      {4, quad_face({2, 2, 0}, {1, 2, 0}, {2, 1, 0}, {1, 1, 0})}};
  // A point of the wall on face f at (x, y), and the deflected point there.
  const auto parameters = [](std::size_t f, double x, double y) -> std::array<double, 2> {
    if (f == 0) return {x, y};
    if (f == 1) return {3.0 + 2.0 * (2.0 - x), y};
    if (f == 2) return {2.0 - y, -1.0 + 3.0 * x};
    return {2.0 - x, 2.0 - y};
  };
  const auto smooth = [](double x, double y) {
    return Vec3{0.01 * std::sin(2.0 * x), 0.02 * std::cos(3.0 * y), 0.05 * std::sin(2.0 * x + y)};
  };
  const SurfaceShapeFit fit = make_surface_shape(faces, scattered_on_square(600, smooth), {.degree = 3});
  EXPECT_EQ(fit.report.shared_edges, 4u);
  EXPECT_EQ(fit.report.joined_edges, 4u);
  EXPECT_LT(fit.report.max_edge_gap, 1e-15);
  const auto deflected = [&](std::size_t f, double x, double y) {
    const auto [u, v] = parameters(f, x, y);
    return fit.shape->at({u, v, static_cast<int>(f)}, 1.0, {}).point;
  };
  double largest_error = 0.0;
  for (int k = 0; k <= 20; ++k) {
    const double a = 0.05 * k;
    EXPECT_LT(distance(deflected(0, 1.0, a), deflected(1, 1.0, a)), 1e-15) << a;        // x = 1, y < 1
    EXPECT_LT(distance(deflected(2, 1.0, 1 + a), deflected(3, 1.0, 1 + a)), 1e-15) << a;  // x = 1, y > 1
    EXPECT_LT(distance(deflected(0, a, 1.0), deflected(2, a, 1.0)), 1e-15) << a;        // y = 1, x < 1
    EXPECT_LT(distance(deflected(1, 1 + a, 1.0), deflected(3, 1 + a, 1.0)), 1e-15) << a;  // y = 1, x > 1
    for (std::size_t f = 0; f < 4; ++f) {
      const double x = (f % 2 == 0 ? 0.0 : 1.0) + a, y = (f < 2 ? 0.0 : 1.0) + 0.5;
      largest_error = std::max(largest_error, distance(deflected(f, x, y), Vec3{x, y, 0} + smooth(x, y)));
    }
  }
  for (std::size_t f = 1; f < 4; ++f) EXPECT_LT(distance(deflected(0, 1, 1), deflected(f, 1, 1)), 1e-15) << f;
  EXPECT_LT(largest_error, 2e-4);  // of deflections up to 0.05: the fit's accuracy, edges included
  EXPECT_LT(fit.report.max_node_residual, 2e-4);
  // The report counts the joined fields' poles (knots were inserted along the edges).
  const FaceDeflections fields = reconstruct_on_faces(faces, scattered_on_square(600, smooth), {.degree = 3});
  for (std::size_t f = 0; f < 4; ++f) {
    EXPECT_EQ(fields.report.faces[f].fit.u_poles, fields.fields[f].u_count()) << f;
    EXPECT_EQ(fields.report.faces[f].fit.v_poles, fields.fields[f].v_count()) << f;
  }
  // A cubic in (x, y) is a cubic in every face's parameters: reproduced, joins and all.
  const auto cubic = [](double x, double y) {
    return Vec3{0.01 * x * x * y, 0.02 * (y * y * y - x), 0.03 * x * y * (x - y)};
  };
  const SurfaceShapeFit exact = make_surface_shape(faces, scattered_on_square(200, cubic), {.degree = 3});
  EXPECT_EQ(exact.report.joined_edges, 4u);
  EXPECT_LT(exact.report.max_node_residual, 1e-13);
  for (std::size_t f = 0; f < 4; ++f) {
    const Vec3 there{0.3 + (f % 2 == 0 ? 0.0 : 1.0), 0.7 + (f < 2 ? 0.0 : 1.0), 0.0};
    const auto [u, v] = parameters(f, there.x, there.y);
    EXPECT_LT(distance(exact.shape->at({u, v, static_cast<int>(f)}, 1.0, {}).point, there + cubic(there.x, there.y)), 1e-13) << f;
  }
}

// A wall that turns by more than 90 degrees across an edge: a second face that rises at 100
// degrees from the first (an overhang), or folds back over it at 170 (a thin fin, a lip). The
// turn is measured from the directions into each face, not from their normals, whose signs
// follow each face's parametrisation: a fold of 170 degrees is not taken for one of 10.
TEST(SurfaceShape, SharpTurnsAcrossAnEdgeAreToldFromTheirSupplements) {
  for (const double degrees : {100.0, 170.0}) {
    SCOPED_TRACE(degrees);
    const double turn = degrees * M_PI / 180.0;
    const Vec3 out{std::cos(turn), 0.0, std::sin(turn)};  // from the edge x = 1 into the second face
    for (const bool flipped : {false, true}) {  // the second face's parameters either way round
      const Vec3 far = Vec3{1, 0, 0} + out;
      const BSplineSurface second =
          flipped ? BSplineSurface(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {far, far + Vec3{0, 1, 0}, {1, 0, 0}, {1, 1, 0}})
                  : BSplineSurface(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {{1, 0, 0}, {1, 1, 0}, far, far + Vec3{0, 1, 0}});
      const std::vector<CadFace> faces{{1, flat_face(0, 1, 0, 1)}, {2, second}};
      std::vector<Vec3> points, deflections;
      for (int i = 0; i <= 4; ++i) {
        for (int j = 0; j <= 4; ++j) {
          points.push_back({0.25 * i, 0.25 * j, 0.0});  // x = 1: on both faces
          deflections.push_back({0.0, 0.0, 0.01});
          if (i == 0) continue;
          points.push_back(Vec3{1, 0.25 * j, 0} + 0.25 * i * out);
          deflections.push_back({0.0, 0.0, 0.01});
        }
      }
      const SurfaceShapeFit fit = make_surface_shape(faces, cartesian(points, deflections), {.degree = 1});
      const auto creases = fit.shape->creases(25.0 * M_PI / 180.0);
      ASSERT_EQ(creases.size(), 1u) << flipped;
      EXPECT_NEAR(creases[0].angle, turn, 1e-9) << flipped;
      EXPECT_EQ(fit.shape->crease_sides({1.0, 0.5, 0}, 25.0 * M_PI / 180.0).size(), 2u) << flipped;
      EXPECT_TRUE(fit.shape->crease_sides({1.0, 0.5, 0}, turn + 0.01).empty()) << flipped;
    }
  }
}

/// The square [x0, x0 + 1] x [0, 1] of the plane z = 0 with u along x and v running unevenly
/// along y: y(v) = 1.6 v - 0.6 v^2 (a quadratic, speed 1.6 at v = 0 and 0.4 at v = 1).
BSplineSurface uneven_face(double x0) {
  return BSplineSurface(1, 2, {0, 0, 1, 1}, {0, 0, 0, 1, 1, 1},
                        {{x0, 0, 0}, {x0, 0.8, 0}, {x0, 1, 0}, {x0 + 1, 0, 0}, {x0 + 1, 0.8, 0}, {x0 + 1, 1, 0}});
}

/// v at height y on an uneven_face: the root in [0, 1] of 0.6 v^2 - 1.6 v + y = 0.
double uneven_v(double y) { return (1.6 - std::sqrt(2.56 - 2.4 * y)) / 1.2; }

/// FEM nodes at n random points of [0, width] x [0, 1] in the plane z = 0, deflection f(x, y).
template <class F>
DeflectionSamples scattered_on_strip(int n, double width, F f) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points, deflections;
  for (int k = 0; k < n; ++k) {
    points.push_back({width * unit(random), unit(random), 0.0});
    deflections.push_back(f(points.back().x, points.back().y));
  }
  return cartesian(points, deflections);
}

// Faces whose parameters run along their shared edge at speeds that are not in a constant ratio
// (the second face's v is quadratic in y) cannot carry fields that meet exactly (a B-spline in
// one face's parameter is not one in the other's): the fields are fitted to their mean along
// the edge, in each face's parameter, with the knot spans there halved until the two agree to
// 1e-10 of the wall's size. The deflected faces then meet along the edge at the points the test
// finds itself (inverting y(v)), and beside it the deflection is as accurate as the fit's.
TEST(SurfaceShape, AnEdgeParametrisedUnevenlyByItsFacesIsJoinedToATolerance) {
  const std::vector<CadFace> faces{{1, quad_face({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0})}, {2, uneven_face(1.0)}};
  const auto smooth = [](double x, double y) { return Vec3{0.0, 0.0, 0.05 * std::sin(3.0 * x + 2.0 * y)}; };
  const DeflectionSamples samples = scattered_on_strip(300, 2.0, smooth);
  const SurfaceShapeFit fit = make_surface_shape(faces, samples, {.degree = 3});
  const double size = std::sqrt(5.0);  // the diagonal of [0, 2] x [0, 1]
  EXPECT_EQ(fit.report.shared_edges, 1u);
  EXPECT_EQ(fit.report.joined_edges, 1u);
  EXPECT_LT(fit.report.max_edge_gap, 1e-10 * size);  // the fits alone: 6e-4 apart along it
  const auto deflected = [&](double x, double y) {
    return x <= 1.0 ? fit.shape->at({x, y, 0}, 1.0, {}).point : fit.shape->at({x - 1.0, uneven_v(y), 1}, 1.0, {}).point;
  };
  double beside = 0.0, away = 0.0;
  for (int k = 0; k <= 24; ++k) {
    const double y = k / 24.0;
    EXPECT_LT(distance(fit.shape->at({1.0, y, 0}, 1.0, {}).point, fit.shape->at({0.0, uneven_v(y), 1}, 1.0, {}).point),
              1e-10 * size) << y;
    for (const double x : {0.97, 0.995, 1.005, 1.03}) {
      beside = std::max(beside, distance(deflected(x, y), Vec3{x, y, 0} + smooth(x, y)));
    }
    for (const double x : {0.5, 1.5}) away = std::max(away, distance(deflected(x, y), Vec3{x, y, 0} + smooth(x, y)));
  }
  std::printf("uneven edge: gap %.3g; largest error beside it %.3g, away from it %.3g; poles along it %zu, %zu\n",
              fit.report.max_edge_gap, beside, away, fit.report.faces[0].fit.v_poles, fit.report.faces[1].fit.v_poles);
  EXPECT_LT(beside, 3e-4);  // of deflections up to 0.05: the fits alone err by 5.3e-4 there
  EXPECT_LT(fit.report.max_node_residual, 2e-4);
  // The knot spans along the edge were halved in both fields: the report counts their poles.
  const FaceDeflections fields = reconstruct_on_faces(faces, samples, {.degree = 3});
  for (std::size_t f = 0; f < 2; ++f) {
    EXPECT_EQ(fields.report.faces[f].fit.v_poles, fields.fields[f].v_count()) << f;
  }
  EXPECT_EQ(fields.fields[0].v_count(), fields.fields[1].v_count());  // the same breaks along the edge
}

// A field that is a polynomial of degree <= q in both faces' parameters (cubic in x, linear in
// y: quadratic in the uneven face's v) is reproduced by both fits, which meet along the edge
// already: the join leaves them as they are.
TEST(SurfaceShape, APolynomialFieldStaysExactAcrossAnUnevenEdge) {
  const std::vector<CadFace> faces{{1, quad_face({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0})}, {2, uneven_face(1.0)}};
  const auto polynomial = [](double x, double y) {
    return Vec3{0.01 * x * x * x + 0.02 * x * y, -0.03 * x * x * y, 0.01 * y - 0.02 * x * x};
  };
  const SurfaceShapeFit fit = make_surface_shape(faces, scattered_on_strip(300, 2.0, polynomial), {.degree = 3});
  EXPECT_EQ(fit.report.joined_edges, 1u);
  EXPECT_LT(fit.report.max_edge_gap, 1e-13);
  EXPECT_LT(fit.report.max_node_residual, 1e-13);
  for (int k = 0; k <= 10; ++k) {
    const double y = 0.1 * k;
    for (const double x : {0.3, 0.999, 1.0, 1.001, 1.7}) {
      const Vec3 at = x <= 1.0 ? fit.shape->at({x, y, 0}, 1.0, {}).point
                               : fit.shape->at({x - 1.0, uneven_v(y), 1}, 1.0, {}).point;
      EXPECT_LT(distance(at, Vec3{x, y, 0} + polynomial(x, y)), 1e-12) << x << " " << y;
    }
  }
}

// Four faces around the common corner (1, 1) of the square [0, 2]^2, one of them (x > 1,
// y < 1) running unevenly along y: its edge with the face at x < 1 is uneven, its edge with the
// face above it affine. Every edge is joined, the affine ones to round-off and the uneven one
// to 1e-10 of the size, and the corner of the four faces stays one point.
TEST(SurfaceShape, UnevenAndAffineEdgesMeetingAtACornerAreAllJoined) {
  const std::vector<CadFace> faces{{1, quad_face({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0})},
                                   {2, uneven_face(1.0)},
                                   {3, quad_face({0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0})},
                                   {4, quad_face({1, 1, 0}, {2, 1, 0}, {1, 2, 0}, {2, 2, 0})}};
  const auto parameters = [](std::size_t f, double x, double y) -> std::array<double, 2> {
    if (f == 0) return {x, y};
    if (f == 1) return {x - 1.0, uneven_v(y)};
    if (f == 2) return {x, y - 1.0};
    return {x - 1.0, y - 1.0};
  };
  const auto smooth = [](double x, double y) {
    return Vec3{0.01 * std::sin(2.0 * x), 0.02 * std::cos(3.0 * y), 0.05 * std::sin(2.0 * x + y)};
  };
  const SurfaceShapeFit fit = make_surface_shape(faces, scattered_on_square(600, smooth), {.degree = 3});
  const double size = 2.0 * std::sqrt(2.0);
  EXPECT_EQ(fit.report.shared_edges, 4u);
  EXPECT_EQ(fit.report.joined_edges, 4u);
  EXPECT_LT(fit.report.max_edge_gap, 1e-10 * size);
  const auto deflected = [&](std::size_t f, double x, double y) {
    const auto [u, v] = parameters(f, x, y);
    return fit.shape->at({u, v, static_cast<int>(f)}, 1.0, {}).point;
  };
  for (int k = 0; k <= 20; ++k) {
    const double a = 0.05 * k;
    EXPECT_LT(distance(deflected(0, 1.0, a), deflected(1, 1.0, a)), 1e-10 * size) << a;  // uneven
    EXPECT_LT(distance(deflected(2, 1.0, 1 + a), deflected(3, 1.0, 1 + a)), 1e-15) << a;
    EXPECT_LT(distance(deflected(0, a, 1.0), deflected(2, a, 1.0)), 1e-15) << a;
    EXPECT_LT(distance(deflected(1, 1 + a, 1.0), deflected(3, 1 + a, 1.0)), 1e-15) << a;
  }
  for (std::size_t f = 1; f < 4; ++f) EXPECT_LT(distance(deflected(0, 1, 1), deflected(f, 1, 1)), 1e-15) << f;
  EXPECT_LT(fit.report.max_node_residual, 2e-4);
}

// The knots the uneven edge's refinement puts into a face travel on through that face's
// affine edges: three faces in a row, the last two running unevenly along y alike, so that
// their edge is affine and the first edge uneven. Both edges are joined; the affine one stays
// exact to round-off with the refined knots.
TEST(SurfaceShape, KnotsRefiningAnUnevenEdgeTravelThroughAffineEdges) {
  const std::vector<CadFace> faces{
      {1, quad_face({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0})}, {2, uneven_face(1.0)}, {3, uneven_face(2.0)}};
  const auto smooth = [](double x, double y) { return Vec3{0.01 * std::cos(x), 0.0, 0.05 * std::sin(2.0 * x + 2.0 * y)}; };
  const DeflectionSamples samples = scattered_on_strip(450, 3.0, smooth);
  const FaceDeflections fields = reconstruct_on_faces(faces, samples, {.degree = 3});
  EXPECT_EQ(fields.report.shared_edges, 2u);
  EXPECT_EQ(fields.report.joined_edges, 2u);
  EXPECT_LT(fields.report.max_edge_gap, 1e-10 * std::sqrt(10.0));
  EXPECT_EQ(fields.fields[1].v_count(), fields.fields[2].v_count());
  for (int k = 0; k <= 20; ++k) {
    const double v = 0.05 * k;
    EXPECT_LT(distance(fields.fields[1].point(1.0, v), fields.fields[2].point(0.0, v)), 1e-15) << v;
  }
}

// A T-junction: the faces below and above y = 1 (x < 1) each share part of the side x = 1 of a
// face twice as tall that runs unevenly along y. Both uneven edges are joined, each to its part
// of the tall face's side, and the point where the three faces meet stays one point.
TEST(SurfaceShape, TwoFacesAlongOneSideOfAnUnevenFaceAreJoinedToIt) {
  const BSplineSurface tall(1, 2, {0, 0, 1, 1}, {0, 0, 0, 1, 1, 1},
                            {{1, 0, 0}, {1, 1.6, 0}, {1, 2, 0}, {2, 0, 0}, {2, 1.6, 0}, {2, 2, 0}});
  const std::vector<CadFace> faces{{1, quad_face({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0})},
                                   {2, quad_face({0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0})},
                                   {3, tall}};
  const auto smooth = [](double x, double y) { return Vec3{0.0, 0.01 * x * y, 0.05 * std::sin(2.0 * x + 1.5 * y)}; };
  const SurfaceShapeFit fit = make_surface_shape(faces, scattered_on_square(600, smooth), {.degree = 3});
  const double size = 2.0 * std::sqrt(2.0);
  EXPECT_EQ(fit.report.shared_edges, 3u);
  EXPECT_EQ(fit.report.joined_edges, 3u);
  EXPECT_LT(fit.report.max_edge_gap, 1e-10 * size);
  const auto on_tall = [&](double y) { return fit.shape->at({0.0, uneven_v(0.5 * y), 2}, 1.0, {}).point; };
  for (int k = 0; k <= 20; ++k) {
    const double y = 0.05 * k;
    EXPECT_LT(distance(fit.shape->at({1.0, y, 0}, 1.0, {}).point, on_tall(y)), 1e-10 * size) << y;
    EXPECT_LT(distance(fit.shape->at({1.0, y, 1}, 1.0, {}).point, on_tall(1.0 + y)), 1e-10 * size) << y;
  }
  EXPECT_LT(distance(fit.shape->at({1.0, 1.0, 0}, 1.0, {}).point, fit.shape->at({1.0, 0.0, 1}, 1.0, {}).point), 1e-15);
}

// Creases without mesh nodes (issue 20 item 2 on faces): a face rising by 30 degrees from a flat
// one along x = 1 is a crease of 30 degrees, not one of 40; the crease's point nearest any point
// is on the edge (1, y, 0) at the point's y, with the faces' normals there, both undeformed
// and after a deflection that lifts the wall by 0.1 (the edge then at z = 0.1).
TEST(SurfaceShape, ACreaseIsFoundAndItsPointsAreOnTheSharedEdge) {
  const double rise = std::tan(M_PI / 6.0);
  const BSplineSurface rising(1, 1, {1, 1, 2, 2}, {0, 0, 1, 1}, {{1, 0, 0}, {1, 1, 0}, {2, 0, rise}, {2, 1, rise}});
  const std::vector<CadFace> faces{{1, flat_face(0, 1, 0, 1)}, {2, rising}};
  std::vector<Vec3> points, deflections;
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const double x = 0.25 * i;
      points.push_back({x, 0.25 * j, x > 1.0 ? (x - 1.0) * rise : 0.0});
      deflections.push_back({0.0, 0.0, 0.1});
    }
  }
  const SurfaceShapeFit fit = make_surface_shape(faces, cartesian(points, deflections), {.degree = 1});
  const auto creases = fit.shape->creases(20.0 * M_PI / 180.0);
  ASSERT_EQ(creases.size(), 1u);
  EXPECT_EQ(creases[0].faces, (std::array<int, 2>{0, 1}));
  EXPECT_NEAR(creases[0].angle, M_PI / 6.0, 1e-12);
  EXPECT_TRUE(fit.shape->creases(40.0 * M_PI / 180.0).empty());
  for (const double lambda : {0.0, 1.0}) {
    for (const Vec3& p : {Vec3{0.7, 0.3, 0.2}, Vec3{1.4, 0.8, -0.1}, Vec3{1.0, 0.55, 0.0}}) {
      const CreasePoint c = fit.shape->crease_point(creases[0], p, lambda);
      EXPECT_LT(distance(c.point, {1.0, p.y, 0.1 * lambda}), 1e-12) << p.x << " " << lambda;
      EXPECT_NEAR(std::abs(c.normals[0].z), 1.0, 1e-12);
      EXPECT_NEAR(std::abs(dot(c.normals[1], Vec3{-std::sin(M_PI / 6.0), 0.0, std::cos(M_PI / 6.0)})), 1.0, 1e-12);
    }
  }
  // Each face is a region of its own between creases of 20 degrees, and one region with the
  // other under 40: a point above the rising face, projected within the flat face's region,
  // lands on the flat face's edge; within the whole wall, on the rising face.
  const int flat = fit.shape->crease_region(0, 20.0 * M_PI / 180.0);
  EXPECT_NE(flat, fit.shape->crease_region(1, 20.0 * M_PI / 180.0));
  EXPECT_EQ(fit.shape->crease_region(0, 40.0 * M_PI / 180.0), fit.shape->crease_region(1, 40.0 * M_PI / 180.0));
  const Vec3 above{1.5, 0.5, 0.5 * rise + 0.3};
  const ShapePoint kept = fit.shape->project(above, 0.0, {0.5, 0.5, 0}, {.region = flat});
  EXPECT_EQ(kept.parameter.face, 0);
  EXPECT_LT(distance(kept.point, {1.0, 0.5, 0.0}), 1e-9);
  EXPECT_EQ(fit.shape->project(above, 0.0, {0.5, 0.5, 0}).parameter.face, 1);
  // A plane has no creases.
  const PlaneShape plane({0, 0, 0}, {0, 0, 1});
  EXPECT_TRUE(plane.creases(0.1).empty());
  EXPECT_THROW(plane.crease_point(creases[0], {0, 0, 0}, 0.0), std::logic_error);
}

TEST(SurfaceShape, RefusesTablesThatDoNotDescribeTheFaces) {
  const std::vector<CadFace> faces{{3, flat_face(0, 1, 0, 1)}, {4, flat_face(1, 2, 0, 1)}};
  DeflectionSamples left = grid_samples(flat_face(0, 0.9, 0, 1), 4, [](double, double) { return Vec3{0, 0, 0.01}; });
  EXPECT_THAT([&] { reconstruct_on_faces(faces, left); },
              ThrowsMessage<InputError>(HasSubstr("no FEM node lies on CAD face 4")));
  DeflectionSamples off = left;
  off.points[5].z = 0.1;
  off.ids.resize(off.size());
  for (std::size_t j = 0; j < off.size(); ++j) off.ids[j] = static_cast<std::int64_t>(100 + j);
  EXPECT_THAT([&] { reconstruct_on_faces({faces.data(), 1}, off); },
              ThrowsMessage<InputError>(HasSubstr("1 of 16 FEM nodes are farther than")));
  EXPECT_THAT([&] { reconstruct_on_faces({faces.data(), 1}, off); },
              ThrowsMessage<InputError>(HasSubstr("node 105 at distance 0.1")));
  const FaceDeflections dropped = reconstruct_on_faces({faces.data(), 1}, off, {.far_nodes = FarNodePolicy::drop});
  ASSERT_EQ(dropped.report.rejected_nodes.size(), 1u);
  EXPECT_EQ(dropped.report.used_nodes, 15u);
  DeflectionSamples meridional = left;
  meridional.frame = SampleFrame::meridional;
  EXPECT_THAT([&] { reconstruct_on_faces({faces.data(), 1}, meridional); },
              ThrowsMessage<InputError>(HasSubstr("needs a cartesian (x, y, z) table")));
  DeflectionSamples few = cartesian({{0.1, 0.1, 0}, {0.9, 0.1, 0}, {0.5, 0.9, 0}}, {{}, {}, {}});
  EXPECT_THAT([&] { reconstruct_on_faces({faces.data(), 1}, few, {.degree = 2}); },
              ThrowsMessage<InputError>(HasSubstr("CAD face 3: ")));
}

// A restart (section 4.3) goes from the previous run's deflected faces (stage 0) to the new
// ones (stage 1), at the same material parameters.
TEST(SurfaceShape, RestartGoesFromThePreviousDeflectionToTheNext) {
  const BSplineSurface face = test::from_occt(test::occt_wavy());
  const auto first = [](double u, double v) { return Vec3{0.01 * u, 0.0, 0.02 * v}; };
  const auto second = [](double u, double v) { return Vec3{0.0, 0.03 * u * v, -0.01}; };
  const DeflectionSamples before = grid_samples(face, 5, first);
  const SurfaceShapeFit fit = make_surface_shape({{1, face}}, grid_samples(face, 5, second), {.degree = 2}, &before);
  const ParameterRectangle r = face.domain();
  for (int k = 0; k <= 4; ++k) {
    const double u = r.u_first + 0.2 * k * (r.u_last - r.u_first), v = r.v_first + 0.1 * k * (r.v_last - r.v_first);
    EXPECT_LT(distance(fit.shape->at({u, v, 0}, 0.0, {}).point, face.point(u, v) + first(u, v)), 1e-12);
    EXPECT_LT(distance(fit.shape->at({u, v, 0}, 1.0, {}).point, face.point(u, v) + second(u, v)), 1e-12);
  }
}

// Faces that cannot carry a field d(t, s) are refused naming them: a sphere's face, whose
// edges collapse to its poles ((t, s) is not unique there), with the FEM nodes nearest the
// pole; and faces that share no edge with the rest of the wall.
TEST(SurfaceShape, RefusesDegenerateAndSeparateFaces) {
  const BSplineSurface sphere = test::from_occt(test::occt_sphere());
  DeflectionSamples on_sphere = grid_samples(sphere, 6, [](double, double) { return Vec3{0, 0, 0.01}; });
  EXPECT_THAT([&] { reconstruct_on_faces(std::vector<CadFace>{{9, sphere}}, on_sphere); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("CAD face 9: its parametrisation degenerates (an edge "
                                                        "collapses to one point (a pole)"),
                                              HasSubstr("FEM nodes nearest that point: sample "))));
  const std::vector<CadFace> apart{{1, flat_face(0, 1, 0, 1)}, {2, flat_face(1, 2, 0, 1)}, {5, flat_face(3, 4, 0, 1)}};
  std::vector<Vec3> points, deflections;
  for (int i = 0; i <= 16; ++i) {
    for (int j = 0; j <= 4; ++j) {
      points.push_back({0.25 * i, 0.25 * j, 0.0});
      deflections.push_back({0, 0, 0.01});
    }
  }
  EXPECT_THAT([&] { reconstruct_on_faces(apart, cartesian(points, deflections), {.far_nodes = FarNodePolicy::drop}); },
              ThrowsMessage<InputError>(HasSubstr("the CAD faces of the wall do not join: they form 2 separate parts "
                                                  "(faces 1, 2; 5)")));
}

// Without CAD a prescribed wall moves by the table interpolated over it; on a restart each node
// is taken back to its material point through the previous deflection first.
TEST(ScatteredShape, MovesMaterialPointsFromTheirPreviousDeflection) {
  std::vector<Vec3> points;
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) points.push_back({0.1 * i, 0.1 * j, 0.2 * std::sin(0.1 * i)});
  }
  const auto first = [](const Vec3& x) { return Vec3{0.01 * x.y, 0.0, 0.02 * x.x * x.x}; };
  const auto second = [](const Vec3& x) { return Vec3{0.0, -0.01 * x.x, 0.03 * x.y}; };
  std::vector<Vec3> d1, d2;
  for (const Vec3& x : points) {
    d1.push_back(first(x));
    d2.push_back(second(x));
  }
  const ScatteredShape fresh{std::make_shared<const ScatteredField>(points, d1)};
  const ScatteredShape restarted{std::make_shared<const ScatteredField>(points, d2),
                                 std::make_shared<const ScatteredField>(points, d1)};
  for (std::size_t k = 0; k < points.size(); k += 7) {
    const Vec3& x0 = points[k];
    EXPECT_LT(distance(fresh.at({}, 1.0, x0).point, x0 + first(x0)), 1e-13);
    EXPECT_LT(distance(fresh.at({}, 0.0, x0).point, x0), 1e-15);
    const Vec3 previous = x0 + first(x0);  // where the first run left the node
    EXPECT_LT(distance(restarted.at({}, 0.0, previous).point, previous), 1e-13);
    EXPECT_LT(distance(restarted.at({}, 1.0, previous).point, x0 + second(x0)), 1e-13);
  }
  EXPECT_EQ(fresh.project(points[12], 0.0).distance, 0.0);
  EXPECT_GT(fresh.project({5.0, 5.0, 5.0}, 0.0).distance, 4.0);
}

}  // namespace
}  // namespace hotmesh::geometry
