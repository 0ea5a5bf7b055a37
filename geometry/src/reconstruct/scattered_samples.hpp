// hotmesh geometry (private): what the interpolations of a table over a wall without CAD share
// (scattered_field.cpp): the samples checked and their duplicates merged, and the principal
// axes of points.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "hotmesh/core/vec3.hpp"
#include "hotmesh/geometry/scattered_field.hpp"

namespace hotmesh::geometry {

/// The samples with points closer than options.same_point (of the data's bounding-box
/// diagonal) merged into the first of them. Throws hotmesh::InputError for a coordinate or
/// value that is not finite, or for merged samples whose values differ by more than
/// options.same_value of the largest; std::invalid_argument for sizes that differ.
struct DistinctSamples {
  std::vector<Vec3> points;
  std::vector<Vec3> values;
  std::size_t merged = 0;  ///< samples merged into an earlier one
};
DistinctSamples distinct_finite_samples(std::vector<Vec3> points, std::vector<Vec3> values,
                                        const ScatteredFieldOptions& options);

/// options.coordinate_precision times the largest |coordinate|: what rounding may have moved a
/// point by.
double rounding(const std::vector<Vec3>& points, const ScatteredFieldOptions& options);

/// Principal axes of points: centroid, directions, RMS extents (largest first) and the number
/// of extents above both `flatness` times the largest and `noise`.
struct Hull {
  Vec3 centroid;
  std::array<Vec3, 3> axes;
  std::array<double, 3> extent{};
  int dimension = 0;
};
Hull affine_hull(const std::vector<Vec3>& points, std::span<const std::uint32_t> members, double flatness, double noise);

}  // namespace hotmesh::geometry
