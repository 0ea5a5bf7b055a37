// hotmesh deform (internal): what the processes of a job (hotmesh/deform/processes.hpp)
// exchange. Items handed out to ranks (sliding nodes to project, cells to partition) go in
// contiguous, balanced shares of a list; a rank computes its share and gather_shares() gives
// every rank the whole list again. With one process none of these calls MPI.
#pragma once

#include <cstddef>
#include <span>

#include "hotmesh/deform/processes.hpp"

namespace hotmesh::deform::detail {

/// Initialises PETSc once per process (MPI with it: as a singleton without a launcher), for
/// the amg solver or for a job of several processes; finalised at exit.
void start_petsc();

struct Share {
  std::size_t begin = 0, end = 0;  ///< the items [begin, end) of a list
};
/// The share of `count` items of rank `rank` of `ranks`: counts differ by at most one.
Share share_of(std::size_t count, int rank, int ranks);
inline Share my_share(std::size_t count) {
  const Processes job = processes();
  return share_of(count, job.rank, job.count);
}

/// `items` holds `width` doubles per item of a list; each rank has filled its share. After
/// the call every rank holds every share.
void gather_shares(std::span<double> items, std::size_t width);
/// Every rank's `values` replaced by their sum over the ranks.
void sum_over_processes(std::span<double> values);
double max_over_processes(double value);

}  // namespace hotmesh::deform::detail
