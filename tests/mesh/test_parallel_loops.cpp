// Tests of how an exception leaves an OpenMP loop (mesh/include/hotmesh/mesh/parallel_loops.hpp): a std::bad_alloc
// thrown in one body comes out of the loop, on one thread or several, where it would otherwise
// end the process with std::terminate; and the threads of a process start up front
// (hotmesh/mesh/parallel_loops.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <new>
#include <stdexcept>

#include "hotmesh/mesh/parallel_loops.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::mesh {
namespace {

TEST(LoopExceptions, BadAllocInOneBodyLeavesTheLoop) {
  for (const int threads : {1, 2, 4}) {
    constexpr std::ptrdiff_t n = 10'000;
    LoopExceptions errors;
    std::atomic<std::ptrdiff_t> done{0};
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      errors.run([&] {
        if (i == n / 3) throw std::bad_alloc();
        done.fetch_add(1, std::memory_order_relaxed);
      });
    }
    EXPECT_THROW(errors.rethrow(), std::bad_alloc) << threads << " threads";
    EXPECT_LT(done.load(), n);  // the bodies after the failure were skipped (most of them)
  }
}

TEST(LoopExceptions, FirstOfSeveralIsRethrownAndNoneMeansNothing) {
  LoopExceptions errors;
#pragma omp parallel for schedule(static) num_threads(2)
  for (int i = 0; i < 4; ++i) {
    errors.run([&] { throw std::runtime_error("body " + std::to_string(i)); });
  }
  EXPECT_THROW(errors.rethrow(), std::runtime_error);

  LoopExceptions none;
  int sum = 0;
#pragma omp parallel for reduction(+ : sum) num_threads(2)
  for (int i = 0; i < 100; ++i) none.run([&] { sum += i; });  // `sum`: the thread's copy
  EXPECT_NO_THROW(none.rethrow());
  EXPECT_EQ(sum, 4950);
}

TEST(Threads, StartThreadsSetsTheCountAndStartsThem) {
  const int saved = omp_get_max_threads();
  start_threads(3);
  EXPECT_EQ(omp_get_max_threads(), 3);
  int team = 0;
#pragma omp parallel
  {
#pragma omp single
    team = omp_get_num_threads();
  }
  EXPECT_EQ(team, 3);
  start_threads(0);  // keeps the count
  EXPECT_EQ(omp_get_max_threads(), 3);
  omp_set_num_threads(saved);
}

}  // namespace
}  // namespace hotmesh::mesh
