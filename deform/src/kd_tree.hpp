// hotmesh deform (internal): a static k-d tree over points, for nearest-node queries (matching
// the nodes of periodic faces). Built once by median splits; a query descends to the closest
// leaf and backtracks only into boxes nearer than the best found so far.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "hotmesh/geometry/vec3.hpp"

namespace hotmesh::deform::detail {

class KdTree {
 public:
  explicit KdTree(std::span<const geometry::Vec3> points) : points_(points.begin(), points.end()), index_(points.size()) {
    for (std::size_t i = 0; i < index_.size(); ++i) index_[i] = static_cast<std::int32_t>(i);
    build(0, index_.size(), 0);
  }

  struct Nearest {
    std::int32_t index = -1;  ///< into the points given at construction
    double distance = std::numeric_limits<double>::infinity();
  };

  Nearest nearest(const geometry::Vec3& p) const {
    Nearest best;
    search(0, index_.size(), 0, p, best);
    if (best.index >= 0) best.distance = std::sqrt(best.distance);
    return best;
  }

 private:
  void build(std::size_t begin, std::size_t end, int axis) {
    if (end - begin <= 1) return;
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(index_.begin() + static_cast<std::ptrdiff_t>(begin), index_.begin() + static_cast<std::ptrdiff_t>(middle),
                     index_.begin() + static_cast<std::ptrdiff_t>(end), [&](std::int32_t a, std::int32_t b) {
                       return points_[static_cast<std::size_t>(a)][axis] < points_[static_cast<std::size_t>(b)][axis];
                     });
    build(begin, middle, (axis + 1) % 3);
    build(middle + 1, end, (axis + 1) % 3);
  }

  /// `best.distance` holds the squared distance during the search.
  void search(std::size_t begin, std::size_t end, int axis, const geometry::Vec3& p, Nearest& best) const {
    if (begin >= end) return;
    const std::size_t middle = begin + (end - begin) / 2;
    const std::int32_t i = index_[middle];
    const geometry::Vec3& q = points_[static_cast<std::size_t>(i)];
    const geometry::Vec3 d = p - q;
    const double squared = dot(d, d);
    if (squared < best.distance) best = {i, squared};
    const double offset = p[axis] - q[axis];
    const int next = (axis + 1) % 3;
    if (offset < 0.0) {
      search(begin, middle, next, p, best);
      if (offset * offset < best.distance) search(middle + 1, end, next, p, best);
    } else {
      search(middle + 1, end, next, p, best);
      if (offset * offset < best.distance) search(begin, middle, next, p, best);
    }
  }

  std::vector<geometry::Vec3> points_;
  std::vector<std::int32_t> index_;
};

}  // namespace hotmesh::deform::detail
