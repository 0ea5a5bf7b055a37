// hotmesh deform (internal): giving freed memory back to the system during a long run.
#pragma once

namespace hotmesh::deform::detail {

/// Gives the pages of freed memory back to the system (glibc's malloc_trim; nothing elsewhere).
/// glibc keeps freed blocks under its mmap threshold (raised up to 32 MB as large blocks are
/// freed) in its heap, resident. A run frees such blocks in every increment: the multigrid
/// hierarchy and its set-up's work space (on two ranks of the 300 000-cell sector each rank grew
/// from 1.14 to 1.45 GB over ten increments without this, and stayed at 1.12 GB with it), and
/// after each increment the checkpoint's copies, the moved mesh's quality and the predictor's
/// vectors (on two ranks of the 200 000-cell sector each rank then rose by 12 MB in the second
/// increment instead of 20 MB; at 2.7 million cells the rise of 0.17 GB a rank stayed: it is
/// live data, docs/performance.md).
void release_free_memory();

}  // namespace hotmesh::deform::detail
