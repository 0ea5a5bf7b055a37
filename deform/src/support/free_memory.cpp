// hotmesh deform: release_free_memory (free_memory.hpp), glibc's malloc_trim.
#include "support/free_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>  // malloc_trim
#endif

namespace hotmesh::deform::detail {

void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace hotmesh::deform::detail
