// hotmesh tests: boundary shapes defined in code. A polyline in the x-y plane (extruded along
// z for 3D meshes: points are projected in their own z plane) whose vertices move with a
// given function of the stage lambda, so tests can prescribe rigid rotations, affine maps
// and ramps exactly.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <memory>

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/deflection_samples.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::test {

using geometry::ShapePoint;
using geometry::Vec3;

class TestCurveShape final : public geometry::BoundaryShape {
 public:
  using Motion = std::function<Vec3(const Vec3& p, double lambda)>;

  TestCurveShape(std::vector<Vec3> vertices, Motion motion) : vertices_(std::move(vertices)), motion_(std::move(motion)) {}

  ShapePoint project(const Vec3& p, double lambda, const geometry::ShapeParameter& /*hint*/,
                     const geometry::ParameterRange& /*range*/ = {}) const override {
    ShapePoint best;
    best.distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < vertices_.size(); ++i) {
      const Vec3 a = moved(i, lambda, p.z), b = moved(i + 1, lambda, p.z);
      const Vec3 ab = b - a;
      const double s = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
      const Vec3 q = a + s * ab;
      const double d = distance(p, q);
      if (d < best.distance) {
        best = {q, Vec3{ab.y, -ab.x, 0.0} / norm(ab), {.t = static_cast<double>(i) + s}, d};
      }
    }
    return best;
  }

  ShapePoint at(const geometry::ShapeParameter& where, double lambda, const Vec3& reference) const override {
    const double t = where.t;
    const auto i = std::min(static_cast<std::size_t>(std::max(t, 0.0)), vertices_.size() - 2);
    const double s = t - static_cast<double>(i);
    const Vec3 a = moved(i, lambda, reference.z), b = moved(i + 1, lambda, reference.z);
    const Vec3 ab = b - a;
    return {a + s * ab, Vec3{ab.y, -ab.x, 0.0} / norm(ab), where, 0.0};
  }

 private:
  Vec3 moved(std::size_t i, double lambda, double z) const {
    Vec3 v = vertices_[i];
    v.z = z;
    return motion_(v, lambda);
  }
  std::vector<Vec3> vertices_;
  Motion motion_;
};

/// Every point lies on this shape and moves by the affine map x -> x + lambda (G x + g).
class AffineShape final : public geometry::BoundaryShape {
 public:
  AffineShape(std::array<Vec3, 3> g, Vec3 shift) : g_(g), shift_(shift) {}
  ShapePoint project(const Vec3& p, double, const geometry::ShapeParameter&, const geometry::ParameterRange&) const override {
    return {p, {1, 0, 0}, {}, 0.0};
  }
  ShapePoint at(const geometry::ShapeParameter& where, double lambda, const Vec3& x) const override {
    const Vec3 gx{dot(g_[0], x), dot(g_[1], x), dot(g_[2], x)};
    return {x + lambda * (gx + shift_), {1, 0, 0}, where, 0.0};
  }
  Vec3 moved(const Vec3& x) const { return at({}, 1, x).point; }

 private:
  std::array<Vec3, 3> g_;
  Vec3 shift_;
};

/// Rotation about the z axis through `centre` by lambda * angle.
inline TestCurveShape::Motion rotation(double angle, Vec3 centre = {}) {
  return [=](const Vec3& p, double lambda) {
    const double c = std::cos(lambda * angle), s = std::sin(lambda * angle);
    const Vec3 r = p - centre;
    return centre + Vec3{c * r.x - s * r.y, s * r.x + c * r.y, r.z};
  };
}

/// The cylinder r = radius, z in [0, 1], about the z axis, deflected by (dr, dz) =
/// (4 bulge z (1 - z), rise z): a surface of revolution that the geometry kernel builds from
/// `intervals` + 1 meridional FEM nodes, as for a wall of a real case.
inline std::shared_ptr<geometry::BoundaryShape> deflected_cylinder(double radius, double bulge, double rise,
                                                                  int intervals) {
  geometry::DeflectionSamples samples;
  samples.frame = geometry::SampleFrame::meridional;
  for (int j = 0; j <= intervals; ++j) {
    const double z = static_cast<double>(j) / intervals;
    samples.points.push_back({radius, z, 0.0});
    samples.deflections.push_back({4.0 * bulge * z * (1.0 - z), rise * z, 0.0});
  }
  const geometry::Axis axis;
  auto rebuilt = geometry::reconstruct_from_nodes(geometry::meridional_samples(samples, axis), {});
  return std::make_shared<geometry::RevolvedShape>(std::move(rebuilt.curve), axis);
}

}  // namespace hotmesh::test
