// hotmesh tests: running a command (the hotmesh executable, a script) and collecting its
// exit code and output.
#pragma once

#include <string>

namespace hotmesh::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr, interleaved
};

/// Runs `command` with /bin/sh, stderr merged into stdout.
CommandResult run_command(const std::string& command);

/// Quotes a word for /bin/sh.
std::string shell_quote(const std::string& word);

}  // namespace hotmesh::test
