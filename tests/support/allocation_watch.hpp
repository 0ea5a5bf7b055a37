// hotmesh tests: the calling thread's allocations while armed: how many, and the largest size
// asked for. allocation_watch.cpp, linked into the test programs that use this header,
// replaces the program's operator new to count them. Not under AddressSanitizer, whose
// operator new it would replace: HOTMESH_WATCH_ALLOCATIONS is then 0 and the tests that need
// it skip.
#pragma once

#include <cstddef>

#include "sanitizer_build.hpp"

#if HOTMESH_TEST_UNDER_ASAN
#define HOTMESH_WATCH_ALLOCATIONS 0
#else
#define HOTMESH_WATCH_ALLOCATIONS 1
#endif

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
