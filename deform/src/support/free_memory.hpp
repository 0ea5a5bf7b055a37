// hotmesh deform (internal): giving freed memory back to the system during a long run.
#pragma once

namespace hotmesh::deform::detail {

/// Gives the pages of freed memory back to the system (glibc's malloc_trim; nothing elsewhere).
/// Blocks from 4 MiB on are mapped apart and unmapped when freed (parallel::
/// restore_malloc_defaults); smaller ones are freed into glibc's heap and stay resident until
/// reused or trimmed. A run frees many of them in every increment: the pieces of the multigrid
/// hierarchy and its set-up's work space, the checkpoint's copies, the moved mesh's quality. At
/// the paper's size a trim after the first set-up gave back 0.1 GB a process; on the 200 000-cell
/// sector it changes nothing measurable.
void release_free_memory();

}  // namespace hotmesh::deform::detail
