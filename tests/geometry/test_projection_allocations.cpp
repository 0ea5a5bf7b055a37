// Test that projection, the solver's hot path, allocates no memory: every operator new in
// this test program is counted while a counter is armed on the calling thread. (Skipped under
// AddressSanitizer, which provides its own operator new.)
#include <gtest/gtest.h>

#include <vector>

#include "allocation_watch.hpp"
#include "curve_fixtures.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"

namespace hotmesh::geometry {
namespace {

TEST(ProjectionAllocations, ProjectAndAtAllocateNothing) {
  if (!HOTMESH_WATCH_ALLOCATIONS) GTEST_SKIP() << "operator new belongs to the sanitizer";
#if HOTMESH_WATCH_ALLOCATIONS
  const RevolvedShape shape(DeflectedCurve(test::hairpin(0.01)), Axis({0, 0, 0}, {1, 0, 0}));
  const PlaneShape plane({0, 0, 0}, {0, 1, 0});
  double checksum = 0.0;
  ::test::allocations::arm();
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p{0.01 * i, 0.3 + 0.001 * i, 0.2};
    const ShapePoint cold = shape.project(p, 0.5);
    const ShapePoint warm = shape.project(p + Vec3{0.001, 0.0, 0.0}, 0.5, cold.parameter);
    checksum += warm.distance + shape.at({.t = 0.3}, 0.7, p).point.x + plane.project(p, 0.0).distance;
  }
  ::test::allocations::armed = false;
  EXPECT_EQ(::test::allocations::count, 0);
  EXPECT_GT(checksum, 0.0);
  // The counter works: a vector allocates.
  ::test::allocations::arm();
  std::vector<double> v(10);
  ::test::allocations::armed = false;
  EXPECT_EQ(::test::allocations::count, 1);
  EXPECT_EQ(v.size(), 10u);
#endif
}

}  // namespace
}  // namespace hotmesh::geometry
