// hotmesh tests: helpers for CAD tests: files in tests/data/cad, axis comparisons up to sign,
// and distances of points to a meridional curve.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "test_support.hpp"

namespace hotmesh::geometry::test {

inline std::filesystem::path cad_file(const std::string& name) { return hotmesh::test::data_path("cad/" + name); }

inline CadModel read_mm(const std::string& name) {
  CadReadOptions options;
  options.unit = LengthUnit::millimetre;
  return CadModel::read(cad_file(name), options);
}

/// The axis is the line through `point` along `direction` (either sign), within tolerance.
inline ::testing::AssertionResult is_axis(const std::optional<Axis>& axis, const Vec3& point, const Vec3& direction,
                                          double tolerance) {
  if (!axis) return ::testing::AssertionFailure() << "no axis";
  const Vec3 d = direction / norm(direction);
  const double sine = norm(cross(axis->direction(), d));
  const Vec3 off = point - axis->origin();
  const double miss = norm(off - dot(off, axis->direction()) * axis->direction());
  if (sine > tolerance || miss > tolerance) {
    return ::testing::AssertionFailure() << "axis through (" << axis->origin().x << ", " << axis->origin().y << ", "
                                         << axis->origin().z << ") along (" << axis->direction().x << ", "
                                         << axis->direction().y << ", " << axis->direction().z << "): sine " << sine
                                         << ", misses the point by " << miss;
  }
  return ::testing::AssertionSuccess();
}

/// Distance from (r, z) to a curve.
inline double distance_to(const BSplineCurve2d& curve, Vec2 p) {
  return CurveProjector(DeflectedCurve(curve)).project(p, 0.0).distance;
}

}  // namespace hotmesh::geometry::test
