// hotmesh app: log output on stderr (progress, warnings, errors); results go to stdout.
#pragma once

namespace hotmesh::app {

/// verbosity: -1 quiet (warnings and errors), 0 normal (progress), 1 debug, 2 trace.
void configure_logging(int verbosity);

}  // namespace hotmesh::app
