// hotmesh parallel: the processes of a run, their start and end. `mpirun -n P hotmesh deform
// case.yaml` starts P processes (ranks) of one job: each reads the inputs and keeps the whole
// mesh, the cells are partitioned among them for the element work and the rows of the
// assembled matrix (the amg solver on PETSc), the sliding nodes for the projections, and
// rank 0 alone writes files and logs progress (docs/parallel-runs.md). A process not started
// by an MPI launcher is a job of one process and needs no MPI at all.
#pragma once

#include "hotmesh/parallel/rank_exchange.hpp"

namespace hotmesh::parallel {

struct Processes {
  int rank = 0;
  int count = 1;
  bool root() const { return rank == 0; }
};

/// Starts MPI (with PETSc) when this process was started by an MPI launcher, and returns its
/// place in the job; without a launcher {0, 1}. Call once, early. Throws InputError if a
/// launcher asked for several processes but the MPI hotmesh was built with sees only one
/// (another MPI's launcher: use Open MPI's mpirun) and std::runtime_error if MPI cannot start.
Processes start_processes();

/// The job's processes ({0, 1} until start_processes() started MPI for several).
Processes processes();

/// What the job's processes exchange: over MPI after start_processes() started several,
/// otherwise one_process().
const RankExchange& job_exchange();

/// Ends every process of the job with `exit_code` (after the caller has reported why): one
/// process that stops alone would leave the others waiting for it forever.
[[noreturn]] void abort_processes(int exit_code);

/// Gives the C library back its own handling of large blocks: allocated with mmap and given back
/// to the system when freed, and the heap's top trimmed. PETSc brings SuperLU_DIST, whose
/// CombBLAS part turns both off for the whole process as it is loaded (mallopt(M_MMAP_MAX, 0)
/// and mallopt(M_TRIM_THRESHOLD, -1) in a static initialiser): every block freed then stays
/// resident, and the multigrid set-up's work space stayed part of the run's memory (at the
/// paper's 2.7 million cells, 1.2 GB a process; docs/performance.md). Call first thing in main().
void restore_malloc_defaults();

/// Initialises PETSc once per process (MPI with it: as a singleton without a launcher), for
/// the amg solver or for a job of several processes; finalised at exit.
void start_petsc();

}  // namespace hotmesh::parallel
