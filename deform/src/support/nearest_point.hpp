// hotmesh deform (internal): the nearest of a set of points to a query, through CGAL's k-d tree
// (its headers only in nearest_point.cpp). Used to pair periodic nodes and to measure how far
// cells lie from the moving walls.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform::detail {

class NearestPoint {
 public:
  struct Found {
    std::int32_t index = -1;  ///< into the points given at construction; -1 for none
    double distance = std::numeric_limits<double>::infinity();
  };

  /// Builds the tree now, so that threads may search it at once.
  explicit NearestPoint(std::span<const Vec3> points);
  ~NearestPoint();
  NearestPoint(const NearestPoint&) = delete;
  NearestPoint& operator=(const NearestPoint&) = delete;

  Found nearest(const Vec3& p) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

/// For each of `points`, the distance to the nearest of `nodes` (none: +infinity each).
/// Parallel over the points.
std::vector<double> nearest_distances(std::span<const Vec3> points, std::span<const Vec3> nodes);

}  // namespace hotmesh::deform::detail
