// hotmesh deform: NearestPoint (nearest_point.hpp) on CGAL's k-d tree.
#include "support/nearest_point.hpp"

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>
#include <boost/iterator/counting_iterator.hpp>

namespace hotmesh::deform::detail {

struct NearestPoint::Tree {
  using Kernel = CGAL::Simple_cartesian<double>;
  using PointMap = CGAL::Pointer_property_map<Kernel::Point_3>::type;
  using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;

  explicit Tree(std::span<const Vec3> points)
      : points_(to_cgal(points)),
        map_(CGAL::make_property_map(points_.data())),
        tree_(boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(points_.size()),
              Search::Tree::Splitter(), Traits(map_)) {
    tree_.build();  // else the first search builds it, which threads searching at once would race on
  }

  static std::vector<Kernel::Point_3> to_cgal(std::span<const Vec3> points) {
    std::vector<Kernel::Point_3> out;
    out.reserve(points.size());
    for (const Vec3& p : points) out.emplace_back(p.x, p.y, p.z);
    return out;
  }

  std::vector<Kernel::Point_3> points_;  // the tree points into it
  PointMap map_;
  Search::Tree tree_;
};

NearestPoint::NearestPoint(std::span<const Vec3> points) : tree_(std::make_unique<Tree>(points)) {}
NearestPoint::~NearestPoint() = default;

NearestPoint::Found NearestPoint::nearest(const Vec3& p) const {
  if (tree_->points_.empty()) return {};
  const Tree::Search::Distance distance(tree_->map_);
  const Tree::Search search(tree_->tree_, Tree::Kernel::Point_3(p.x, p.y, p.z), 1, 0.0, true, distance);
  if (search.begin() == search.end()) return {};
  return {static_cast<std::int32_t>(search.begin()->first), distance.inverse_of_transformed_distance(search.begin()->second)};
}

std::vector<double> nearest_distances(std::span<const Vec3> points, std::span<const Vec3> nodes) {
  std::vector<double> d(points.size(), std::numeric_limits<double>::infinity());
  if (nodes.empty()) return d;
  const NearestPoint tree(nodes);
  const auto n = static_cast<std::ptrdiff_t>(points.size());
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (std::ptrdiff_t i = 0; i < n; ++i) d[static_cast<std::size_t>(i)] = tree.nearest(points[static_cast<std::size_t>(i)]).distance;
  return d;
}

}  // namespace hotmesh::deform::detail
