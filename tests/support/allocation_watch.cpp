// hotmesh tests: the test program's operator new and delete, counting the allocations of a
// thread whose watch is armed (allocation_watch.hpp). Nothing under AddressSanitizer, which
// provides its own.
#include "allocation_watch.hpp"

#if HOTMESH_WATCH_ALLOCATIONS
#include <algorithm>
#include <cstdlib>
#include <new>

// A pair on malloc and free. GCC at -O1, inlining this delete into a test, takes the new it
// sees there for another allocator's.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
  if (test::allocations::armed) {
    ++test::allocations::count;
    test::allocations::largest = std::max(test::allocations::largest, size);
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif
