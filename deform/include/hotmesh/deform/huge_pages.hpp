// hotmesh deform: memory for the largest array of a run (the stiffness operator's blocks),
// asked of Linux in transparent huge pages (2 MiB) where the system gives them only on request
// (/sys/kernel/mm/transparent_hugepage/enabled set to madvise, as Debian and Ubuntu ship it).
// A product streams the blocks: in 4 KiB pages a product on a 1000^2 quad block took 17.8 ms
// in two runs of three, against 11.5-12.2 ms in huge pages (bench_operator, docs/performance.md).
#pragma once

#include <cstddef>
#include <new>

namespace hotmesh::deform {

/// `bytes` of memory, untouched; arrays of 2 MiB or more aligned to 2 MiB and marked for huge
/// pages (madvise) before their first touch. Throws std::bad_alloc.
void* allocate_huge(std::size_t bytes);
void free_huge(void* memory) noexcept;

/// An allocator for std::vector on allocate_huge.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_huge(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { free_huge(p); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
};

}  // namespace hotmesh::deform
