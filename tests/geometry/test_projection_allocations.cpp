// Test that projection, the solver's hot path, allocates no memory: every operator new in
// this test program is counted while a counter is armed on the calling thread. (Skipped under
// AddressSanitizer, which provides its own operator new.)
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

#include "curve_fixtures.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define HOTMESH_COUNT_ALLOCATIONS 0
#else
#define HOTMESH_COUNT_ALLOCATIONS 1

namespace {
thread_local bool counting = false;
thread_local long allocations = 0;
}  // namespace

void* operator new(std::size_t size) {
  if (counting) ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace hotmesh::geometry {
namespace {

TEST(ProjectionAllocations, ProjectAndAtAllocateNothing) {
  if (!HOTMESH_COUNT_ALLOCATIONS) GTEST_SKIP() << "operator new belongs to the sanitizer";
#if HOTMESH_COUNT_ALLOCATIONS
  const RevolvedShape shape(DeflectedCurve(test::hairpin(0.01)), Axis({0, 0, 0}, {1, 0, 0}));
  const PlaneShape plane({0, 0, 0}, {0, 1, 0});
  double checksum = 0.0;
  allocations = 0;
  counting = true;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p{0.01 * i, 0.3 + 0.001 * i, 0.2};
    const ShapePoint cold = shape.project(p, 0.5);
    const ShapePoint warm = shape.project(p + Vec3{0.001, 0.0, 0.0}, 0.5, cold.parameter);
    checksum += warm.distance + shape.at({.t = 0.3}, 0.7, p).point.x + plane.project(p, 0.0).distance;
  }
  counting = false;
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(checksum, 0.0);
  // The counter works: a vector allocates.
  counting = true;
  std::vector<double> v(10);
  counting = false;
  EXPECT_EQ(allocations, 1);
  EXPECT_EQ(v.size(), 10u);
#endif
}

}  // namespace
}  // namespace hotmesh::geometry
