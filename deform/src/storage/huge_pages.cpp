// hotmesh deform: allocate_huge (huge_pages.hpp).
#include "hotmesh/deform/huge_pages.hpp"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace hotmesh::deform {

void* allocate_huge(std::size_t bytes) {
  constexpr std::size_t kHugePage = std::size_t{1} << 21;
  if (bytes < kHugePage) {
    void* memory = std::malloc(bytes == 0 ? 1 : bytes);
    if (!memory) throw std::bad_alloc();
    return memory;
  }
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* memory = std::aligned_alloc(kHugePage, rounded);
  if (!memory) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(memory, rounded, MADV_HUGEPAGE);  // a hint: without huge pages the memory is the same
#endif
  return memory;
}

void free_huge(void* memory) noexcept { std::free(memory); }

}  // namespace hotmesh::deform
