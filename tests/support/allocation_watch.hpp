// hotmesh tests: a replacing operator new that watches the calling thread's allocations while
// armed: how many, and the largest size asked for. It defines the test program's operator new
// and delete, so exactly one source file of a test program includes it. Not under
// AddressSanitizer, whose operator new it would replace: HOTMESH_WATCH_ALLOCATIONS is then 0
// and the tests that need it skip.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <new>

#include "sanitizer_build.hpp"

#if HOTMESH_TEST_UNDER_ASAN
#define HOTMESH_WATCH_ALLOCATIONS 0
#else
#define HOTMESH_WATCH_ALLOCATIONS 1

namespace test::allocations {
inline thread_local bool armed = false;
inline thread_local long count = 0;
inline thread_local std::size_t largest = 0;

/// Arms the watch with zero counts.
inline void arm() {
  count = 0;
  largest = 0;
  armed = true;
}
}  // namespace test::allocations

// A pair on malloc and free. GCC at -O1 (the tests' level), inlining this delete into a test,
// takes the new it sees there for another allocator's.
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
