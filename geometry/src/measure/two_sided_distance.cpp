// hotmesh geometry: what both measures of wall_deviation.hpp share (two_sided_distance.hpp): the
// wall's faces, the worse of the two directions, and the median edge length.
#include "measure/two_sided_distance.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

namespace hotmesh::geometry {

void WallFaces::add(std::span<const std::int32_t> corners) {
  if (corners.size() < 2) throw std::invalid_argument("WallFaces::add: a face needs at least 2 corners");
  corners_.insert(corners_.end(), corners.begin(), corners.end());
  offsets_.push_back(corners_.size());
}

void WallDeviation::take_worst_direction() {
  const double a = mesh_to_shape.distance, b = shape_to_mesh.distance;
  worst = b > a ? WallDirection::shape_to_mesh : WallDirection::mesh_to_shape;
  hausdorff = std::isnan(a) || std::isnan(b) ? std::numeric_limits<double>::quiet_NaN() : std::max(a, b);
}

const char* to_string(WallDirection direction) {
  return direction == WallDirection::mesh_to_shape ? "mesh_to_shape" : "shape_to_mesh";
}

namespace detail {

double median_length(std::vector<double>& lengths) {
  if (lengths.empty()) return 0.0;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  return lengths[lengths.size() / 2];
}

}  // namespace detail

}  // namespace hotmesh::geometry
