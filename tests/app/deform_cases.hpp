// hotmesh tests: cases for `hotmesh deform` run as a command: the ramp sample copied to a
// temporary folder, and the coarse ramp channel of coarse_ramp.hpp.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "coarse_ramp.hpp"
#include "faults.hpp"
#include "output_folders.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::test {

inline const std::filesystem::path kSample = std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples" / "ramp2d";

inline CommandResult hotmesh(const std::string& arguments) { return run_command(std::string(HOTMESH_EXE) + " " + arguments); }
/// `hotmesh arguments` with `faults` injected (faults.hpp).
inline CommandResult hotmesh(const std::string& arguments, const Faults& faults) {
  return run_command(fault_variables(faults) + HOTMESH_EXE + " " + arguments);
}

/// A copy of the ramp sample in a temporary folder, with its case file replaced by `yaml`.
struct RampCase {
  TempDir dir;
  explicit RampCase(const std::string& yaml) {
    std::filesystem::copy_file(kSample / "ramp2d.msh", dir / "ramp2d.msh");
    std::filesystem::copy_file(kSample / "ramp.csv", dir / "ramp.csv");
    write_text(dir / "case.yaml", yaml);
  }
  std::string case_file() const { return shell_quote((dir / "case.yaml").string()); }
};

}  // namespace hotmesh::test
