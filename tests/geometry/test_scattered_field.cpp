// Tests of ScatteredField, partition-of-unity RBF interpolation of scattered vector data (issue
// 23, item 0): exact at the points, linear fields reproduced, convergence on a smooth field,
// continuity across patches, graded data, and the input errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/scattered_field.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::HasSubstr;

/// A point set: a map from parameters in [0, 1]^3 (the third unused on surfaces).
struct Shape {
  std::string name;
  std::function<Vec3(double, double, double)> map;
};

/// Height of a uniform bicubic B-spline surface over [0, 1]^2: 4 by 4 spans, a 7 by 7 net of
/// wavy control heights.
double bspline_height(double u, double v) {
  const auto basis = [](int a, double t) {  // the uniform cubic B-spline's four pieces
    const double pieces[] = {(1 - t) * (1 - t) * (1 - t), 3 * t * t * t - 6 * t * t + 4,
                             -3 * t * t * t + 3 * t * t + 3 * t + 1, t * t * t};
    return pieces[a] / 6.0;
  };
  const auto span = [](double s, double& t) {
    const double w = 4.0 * std::clamp(s, 0.0, 1.0 - 1e-12);
    t = w - std::floor(w);
    return static_cast<int>(w);
  };
  double tu = 0.0, tv = 0.0;
  const int i = span(u, tu), j = span(v, tv);
  double z = 0.0;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      z += 0.15 * std::sin(1.7 * (i + a) + 0.3) * std::cos(1.3 * (j + b) + 0.5) * basis(a, tu) * basis(b, tv);
    }
  }
  return z;
}

std::vector<Shape> shapes() {
  const Vec3 a = Vec3{1, 2, 2} / 3.0;  // a, b orthonormal: a tilted plane, no coordinate constant
  const Vec3 b = Vec3{2, 1, -2} / 3.0;
  return {
      {"tilted plane", [a, b](double u, double v, double) { return Vec3{0.3, -0.2, 0.5} + u * a + v * b; }},
      {"cylinder", [](double u, double v, double) {
         return Vec3{0.5 * std::cos(4.5 * u), 0.5 * std::sin(4.5 * u), v};
       }},
      {"sphere patch", [](double u, double v, double) {
         const double theta = 0.3 + 1.2 * u, phi = 1.5 * v;
         return Vec3{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
       }},
      {"wavy B-spline", [](double u, double v, double) { return Vec3{u, v, bspline_height(u, v)}; }},
      {"thin curved strip", [](double u, double v, double) {  // 2 long, 0.02 wide
         return Vec3{std::cos(2.0 * u), std::sin(2.0 * u), 0.02 * v};
       }},
      {"volume", [](double u, double v, double w) { return Vec3{u, 0.6 * v, 0.4 * w}; }},
  };
}

Shape shape_named(const std::string& name) {
  for (Shape& shape : shapes()) {
    if (shape.name == name) return shape;
  }
  throw std::logic_error("no shape " + name);
}

std::vector<Vec3> sample(const Shape& shape, std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points(count);
  for (Vec3& p : points) {
    const double u = unit(random), v = unit(random), w = unit(random);
    p = shape.map(u, v, w);
  }
  return points;
}

Vec3 smooth(const Vec3& x) {
  return {std::sin(2.0 * x.x + x.y), x.x * std::cos(3.0 * x.y - x.z), std::exp(0.5 * x.z) + x.x * x.y};
}

Vec3 linear(const Vec3& x) {
  return {0.3 + 2.0 * x.x - x.y + 0.5 * x.z, -1.0 + 0.7 * x.x + 3.0 * x.y - 2.0 * x.z,
          2.0 - x.x + 0.2 * x.y + 4.0 * x.z};
}

std::vector<Vec3> values_of(const std::vector<Vec3>& points, Vec3 (*f)(const Vec3&)) {
  std::vector<Vec3> values;
  for (const Vec3& p : points) values.push_back(f(p));
  return values;
}

double largest(const std::vector<Vec3>& values) {
  double m = 0.0;
  for (const Vec3& v : values) m = std::max(m, norm(v));
  return m;
}

/// Largest |s(x) - f(x)| over `points`, relative to the largest |f|.
double relative_error(const ScatteredField& s, const std::vector<Vec3>& points, Vec3 (*f)(const Vec3&)) {
  double error = 0.0;
  for (const Vec3& p : points) error = std::max(error, distance(s(p), f(p)));
  return error / largest(values_of(points, f));
}

// One patch (80 points) and many (3000): the value at every point is the sample's.
TEST(ScatteredField, IsExactAtThePointsOnSurfacesAndInAVolume) {
  for (const Shape& shape : shapes()) {
    for (const std::size_t count : {80u, 3000u}) {
      const std::vector<Vec3> points = sample(shape, count, 1);
      const ScatteredField s(points, values_of(points, smooth));
      if (count == 80) {
        EXPECT_EQ(s.report().patches, 1u) << shape.name;
      } else {
        EXPECT_GT(s.report().patches, 20u) << shape.name;
      }
      EXPECT_LT(s.report().max_residual, 1e-12 * largest(values_of(points, smooth))) << shape.name;
      EXPECT_LT(relative_error(s, points, smooth), 1e-12) << shape.name << ", " << count << " points";
    }
  }
}

// Off the points, on the same surface; the tilted plane's patches are all flat (the
// polynomial over the plane: (1, x, y, z) would be rank-deficient there), the others none.
TEST(ScatteredField, ReproducesLinearFieldsOffThePoints) {
  for (const Shape& shape : shapes()) {
    for (const std::size_t count : {80u, 3000u}) {
      const std::vector<Vec3> points = sample(shape, count, 2);
      const ScatteredField s(points, values_of(points, linear));
      EXPECT_EQ(s.report().flat_patches, shape.name == "tilted plane" ? s.report().patches : 0u) << shape.name;
      EXPECT_LT(relative_error(s, sample(shape, 500, 3), linear), 1e-10) << shape.name << ", " << count << " points";
    }
  }
}

// Points on a plane make (1, x, y, z) rank-deficient: the polynomial is over the plane, so a
// step e off it (a CFD node off the FEM plane) changes the field by O(e^2) (the kernels' part,
// none for a linear field), not by e times an undetermined normal coefficient. So too for a
// plane far from the origin written with 7 significant digits, whose points are 1e-7 off it.
TEST(ScatteredField, OnAPlaneBarelyChangesAlongTheNormal) {
  const Shape plane = shape_named("tilted plane");
  const Vec3 normal = cross(plane.map(1, 0, 0) - plane.map(0, 0, 0), plane.map(0, 1, 0) - plane.map(0, 0, 0));
  const Vec3 offset{3, -2, 4};
  const auto seven_digits = [](double c) { return static_cast<double>(static_cast<float>(c)); };
  for (const std::size_t count : {80u, 3000u, 10000u}) {
    std::vector<Vec3> points = sample(plane, count, 12);
    if (count == 10000) {
      for (Vec3& p : points) {
        p = {seven_digits(p.x + offset.x), seven_digits(p.y + offset.y), seven_digits(p.z + offset.z)};
      }
    }
    const Vec3 shift = count == 10000 ? offset : Vec3{};
    struct Case {
      Vec3 (*f)(const Vec3&);
      double tolerance;
    };
    for (const Case c : {Case{linear, 1e-12}, Case{smooth, 1e-6}}) {
      std::vector<Vec3> values;
      for (const Vec3& p : points) values.push_back(c.f(p - shift));
      const ScatteredField s(points, values);
      EXPECT_EQ(s.report().flat_patches, s.report().patches) << count;
      double change = 0.0;
      for (const Vec3& x : sample(plane, 200, 13)) {
        change = std::max(change, distance(s(x + shift + 1e-4 * normal), s(x + shift)));
      }
      // Rounded points are not on the plane: the kernels take up the difference, O(e^2) off it.
      const double tolerance = count == 10000 ? 1e-6 : c.tolerance;
      EXPECT_LT(change, tolerance * largest(values)) << count;
    }
  }
}

// Smooth field on the wavy surface, jittered grids of spacing h, 2h, 4h: the largest error off
// the points falls at least as h^1.5 (r^3 with a linear polynomial on a surface: about h^2.5).
TEST(ScatteredField, ConvergesOnASmoothFieldAsThePointsAreRefined) {
  const Shape wavy = shape_named("wavy B-spline");
  const std::vector<Vec3> probes = sample(wavy, 2000, 4);
  std::vector<double> errors;
  for (const int k : {20, 40, 80}) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    std::vector<Vec3> points;
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; j <= k; ++j) {
        const double u = std::clamp((i + jitter(random)) / k, 0.0, 1.0);
        const double v = std::clamp((j + jitter(random)) / k, 0.0, 1.0);
        points.push_back(wavy.map(u, v, 0.0));
      }
    }
    const ScatteredField s(points, values_of(points, smooth));
    errors.push_back(relative_error(s, probes, smooth));
    std::printf("  %zu points, %zu patches: max error %.3g\n", points.size(), s.report().patches, errors.back());
  }
  for (std::size_t r = 1; r < errors.size(); ++r) {
    const double order = std::log2(errors[r - 1] / errors[r]);
    std::printf("  observed order %.2f\n", order);
    EXPECT_GE(order, 1.5);
  }
}

// Along a curve on the surface that crosses many patch boundaries, the largest first
// difference of neighbouring values shrinks like the step h (a jump would not) and the largest
// second difference like h^2 (a kink, e.g. from C0 weights, only like h).
TEST(ScatteredField, IsSmoothAcrossPatches) {
  const Shape wavy = shape_named("wavy B-spline");
  const std::vector<Vec3> points = sample(wavy, 4000, 6);
  const ScatteredField s(points, values_of(points, smooth));
  EXPECT_GT(s.report().patches, 50u);
  struct Differences {
    double first = 0.0, second = 0.0;
  };
  const auto largest_differences = [&](int steps) {
    Differences d;
    std::vector<Vec3> v;
    for (int i = 0; i <= steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      v.push_back(s(wavy.map(0.05 + 0.9 * t, 0.1 + 0.8 * t * t, 0.0)));
    }
    for (std::size_t i = 1; i < v.size(); ++i) {
      d.first = std::max(d.first, distance(v[i], v[i - 1]));
      if (i + 1 < v.size()) d.second = std::max(d.second, norm(v[i + 1] - 2.0 * v[i] + v[i - 1]));
    }
    return d;
  };
  const Differences coarse = largest_differences(1000), fine = largest_differences(100000);
  EXPECT_LT(fine.first, 0.02 * coarse.first) << coarse.first << " " << fine.first;
  EXPECT_LT(fine.second, 1e-3 * coarse.second) << coarse.second << " " << fine.second;
}

// FEM meshes are graded: points 1000 times denser in one corner still give patches of bounded
// size (a uniform grid of patches would put most points into one), and exact values.
TEST(ScatteredField, KeepsPatchesSmallOnGradedData) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < 3000; ++i) points.push_back({std::pow(unit(random), 4.0), std::pow(unit(random), 4.0), 0.0});
  const ScatteredField s(points, values_of(points, smooth));
  EXPECT_LE(s.report().largest_patch, 150u);
  EXPECT_LT(relative_error(s, points, smooth), 1e-12);
}

// Far from the data the nearest patch's interpolant is used: for a linear field, exact.
TEST(ScatteredField, FarFromThePointsUsesTheNearestPatch) {
  const std::vector<Vec3> points = sample(shape_named("cylinder"), 3000, 8);
  const ScatteredField s(points, values_of(points, linear));
  for (const Vec3& far : {Vec3{10, -3, 4}, Vec3{0, 0, 0}, Vec3{0, 0, -2}}) {
    EXPECT_LT(distance(s(far), linear(far)), 1e-9 * norm(linear(far))) << far.x;
  }
}

TEST(ScatteredField, MergesDuplicatesWithEqualValues) {
  std::vector<Vec3> points = sample(shape_named("tilted plane"), 200, 9);
  points.push_back(points[17]);
  points.push_back(points[40] + Vec3{1e-13, 0, 0});  // within the same-point tolerance
  std::vector<Vec3> values = values_of(points, smooth);
  values.back() = values[40];
  const ScatteredField s(points, values);
  EXPECT_EQ(s.report().samples, 202u);
  EXPECT_EQ(s.report().merged_duplicates, 2u);
  EXPECT_LT(distance(s(points[17]), values[17]), 1e-12);
}

TEST(ScatteredField, RefusesDuplicatesWithDifferentValues) {
  std::vector<Vec3> points = sample(shape_named("tilted plane"), 200, 10);
  points.push_back(points[3]);
  std::vector<Vec3> values = values_of(points, smooth);
  values.back().x += 0.01;
  try {
    const ScatteredField s(points, values);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("samples 3 and 200"));
  }
}

TEST(ScatteredField, RefusesTooFewOrCollinearOrNonFinitePoints) {
  EXPECT_THROW(ScatteredField({}, {}), InputError);
  EXPECT_THROW(ScatteredField({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}), InputError);
  EXPECT_THROW(ScatteredField({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}), InputError);
  std::vector<Vec3> line;
  for (int i = 0; i < 50; ++i) line.push_back(Vec3{1, 2, 3} * (0.1 * i));
  try {
    const ScatteredField s(line, line);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("on one line"));
  }
  std::vector<Vec3> points = sample(shape_named("tilted plane"), 10, 11);
  std::vector<Vec3> values = values_of(points, smooth);
  values[4].y = std::nan("");
  EXPECT_THROW(ScatteredField(points, values), InputError);
  EXPECT_THROW(ScatteredField(points, {{0, 0, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace hotmesh::geometry
