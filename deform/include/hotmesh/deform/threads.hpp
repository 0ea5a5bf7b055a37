// hotmesh deform: the OpenMP threads of a process. libgomp creates a loop's threads when the
// first loop runs on them and ends the process when it cannot (exit code 1, "libgomp: Thread
// creation failed"), as under a memory limit without room for their stacks. start_threads()
// creates them first, where a failure is an exception the command reports as out of memory
// (exit code 4).
#pragma once

namespace hotmesh::deform {

/// Sets the number of threads of the loops (`count` > 0; 0 keeps OpenMP's: OMP_NUM_THREADS, or
/// one per core) and starts them now, before the run holds its memory. Throws std::bad_alloc
/// if the system cannot create that many threads. OpenMP keeps them for the loops that follow.
void start_threads(int count = 0);

}  // namespace hotmesh::deform
