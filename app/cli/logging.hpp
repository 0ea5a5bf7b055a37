// hotmesh app: log output on stderr (progress, warnings, errors); results go to stdout.
#pragma once

namespace hotmesh::app {

/// verbosity: -1 quiet (warnings and errors), 0 normal (progress), 1 debug, 2 trace.
void configure_logging(int verbosity);

/// A rank other than 0 of an MPI job: errors only, each prefixed with the rank (rank 0 logs
/// the progress of the job).
void quiet_other_ranks(int rank);

}  // namespace hotmesh::app
