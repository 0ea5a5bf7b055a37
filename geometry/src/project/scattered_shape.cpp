// hotmesh geometry: a prescribed wall without CAD faces moved by its table's field
// (surface_shape.hpp, ScatteredShape): a point is its own closest point, and a stage moves the
// material point at `reference`.
#include "hotmesh/geometry/surface_shape.hpp"

namespace hotmesh::geometry {

ScatteredShape::ScatteredShape(std::shared_ptr<const WallField> after, std::shared_ptr<const WallField> before)
    : after_(std::move(after)), before_(std::move(before)) {}

ShapePoint ScatteredShape::project(const Vec3& p, double /*lambda*/, const ShapeParameter& /*hint*/,
                                   const ParameterRange& /*range*/) const {
  return {p, {}, {}, after_->outside(p)};
}

// x = x0 + before(x0) by fixed-point iteration x0 <- x - before(x0): a contraction wherever the
// deflection's gradient is below 1, as any FEM deflection of a wall is by orders of magnitude.
Vec3 ScatteredShape::material_point(const Vec3& x) const {
  if (!before_) return x;
  constexpr int kMaxIterations = 100;
  const double tolerance = 1e-15 * (1.0 + norm(x));
  Vec3 x0 = x - (*before_)(x);
  for (int k = 0; k < kMaxIterations; ++k) {
    const Vec3 next = x - (*before_)(x0);
    const double step = distance(next, x0);
    x0 = next;
    if (step <= tolerance) break;
  }
  return x0;
}

ShapePoint ScatteredShape::at(const ShapeParameter& where, double lambda, const Vec3& reference) const {
  const Vec3 x0 = material_point(reference);
  const Vec3 start = before_ ? (*before_)(x0) : Vec3{};
  return {x0 + start + lambda * ((*after_)(x0) - start), {}, where, 0.0};
}

}  // namespace hotmesh::geometry
