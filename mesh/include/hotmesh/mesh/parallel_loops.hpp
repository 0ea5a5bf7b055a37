// hotmesh mesh: how the loops over cells and nodes (here and in deform) run on OpenMP threads.
// Below the sizes here a loop runs on one thread, because starting and joining a thread team
// costs more than the work. It costs far more on a loaded machine, where OpenMP threads that
// spin while they wait steal the time slices of the others: a small case on a busy machine
// then runs tens of times slower in parallel than serially. So `hotmesh deform` lets waiting
// threads sleep, and takes threads only for the cores other processes leave free
// (hotmesh/parallel/threads.hpp); the loops below hand out dynamic chunks.
// And: how an exception leaves an OpenMP loop, and starting the threads up front. libgomp
// creates a loop's threads when the first loop runs on them and ends the process when it
// cannot (exit code 1, "libgomp: Thread creation failed"), as under a memory limit without
// room for their stacks. start_threads() creates them first, where a failure is an exception
// the command reports as out of memory (exit code 4).
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>

namespace hotmesh::mesh {

inline constexpr std::ptrdiff_t kParallelVector = 1 << 16;   ///< entries of a vector kernel
inline constexpr std::ptrdiff_t kParallelNodes = 1 << 15;    ///< nodes of a cheap nodal loop
inline constexpr std::ptrdiff_t kParallelCells = 256;        ///< cells of an element-matrix loop
inline constexpr std::ptrdiff_t kParallelProjections = 256;  ///< nodes projected on boundaries
/// Multiply-adds of a product y = K x (the entries of K's node blocks).
inline constexpr std::ptrdiff_t kParallelProduct = 1 << 18;

/// The loops run every Newton step and every CG iteration hand out their work in chunks of
/// these sizes as threads ask for it (schedule(dynamic)), not in one fixed share per thread: a
/// thread whose core another process holds then delays the loop by one chunk, not by its
/// share. Each iteration's arithmetic does not depend on the thread that does it, and
/// reductions sum fixed chunks in order, so results stay the same for any thread count.
inline constexpr int kChunkVector = 4096;  ///< entries of a vector kernel
inline constexpr int kChunkNodes = 1024;   ///< nodes of a nodal loop
inline constexpr int kChunkCells = 64;     ///< cells of an element loop

/// Carries an exception out of an OpenMP loop. One that escapes a parallel region (even one
/// that runs on a single thread) calls std::terminate: a std::bad_alloc would end hotmesh with
/// SIGABRT instead of its out-of-memory exit code. A loop whose body may throw (it calls code
/// behind an interface, such as a boundary shape's projection) runs each body through run()
/// and calls rethrow() after the loop:
///
///     LoopExceptions errors;
///     #pragma omp parallel for
///     for (std::ptrdiff_t i = 0; i < n; ++i) errors.run([&] { ... });
///     errors.rethrow();
///
/// Once a body has thrown, the bodies not yet started are skipped; the first exception caught
/// is rethrown. Loops that cannot throw (arithmetic on arrays) do without.
class LoopExceptions {
 public:
  // Kept out of line: inlined into a loop's outlined function, GCC 12 at -O2 with the sanitizers
  // left its handler out of the exception tables, and the exception reached the region's
  // std::terminate (Sliding.OutOfMemoryInAProjectionLeavesTheRunAsBadAlloc). One call per body.
  template <class Body>
  [[gnu::noinline]] void run(Body&& body) noexcept {
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      body();
    } catch (...) {
      keep(std::current_exception());
    }
  }

  void rethrow() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  void keep(std::exception_ptr e) noexcept {
#pragma omp critical(hotmesh_loop_exceptions)
    if (!first_) first_ = std::move(e);
    failed_.store(true, std::memory_order_relaxed);
  }

  std::atomic<bool> failed_{false};
  std::exception_ptr first_;
};

/// Sets the number of threads of the loops (`count` > 0; 0 keeps OpenMP's: OMP_NUM_THREADS, or
/// one per core) and starts them now, before the run holds its memory. Throws std::bad_alloc
/// if the system cannot create that many threads. OpenMP keeps them for the loops that follow.
void start_threads(int count = 0);

}  // namespace hotmesh::mesh
