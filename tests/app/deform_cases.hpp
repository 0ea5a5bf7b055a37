// hotmesh tests: cases for `hotmesh deform` run as a command: the ramp sample copied to a
// temporary folder, and a coarse ramp channel built in code (fast, with sliding walls).
#pragma once

#include <filesystem>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/io/gmsh.hpp"
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

/// A coarse ramp channel written to `dir`, with tables for the half and the full ramp.
inline void write_coarse_ramp(const std::filesystem::path& dir) {
  const auto xs = mesh::uniform_line(0.0, 2.0, 21);
  const auto ys = mesh::stretched_line(0.0, 1.0, 12, 0.004);
  io::write_gmsh(dir / "ramp.msh", mesh::structured_quads(xs, ys, {"left", "right", "bottom", "top"}));
  for (const auto& [name, height] : {std::pair{"half.csv", 0.25}, std::pair{"full.csv", 0.5}}) {
    write_text(dir / name, fmt::format("x,y,dx,dy\n0,0,0,0\n0.975,0,0,0\n1.025,0,0,{}\n2,0,0,{}\n", height, height));
  }
}

/// The coarse ramp's case: both walls sliding, the lower one over `table`.
inline std::string ramp_case(const std::string& table, int increments, const std::string& extra = "") {
  return fmt::format(
      "mesh: ramp.msh\nsolver: {{increments: {}, newton_tolerance: 1.0e-6, pcg_tolerance: 1.0e-6}}\n{}"
      "patches:\n  left: {{role: fixed}}\n  right: {{role: slip}}\n  top: {{role: sliding}}\n"
      "  bottom: {{role: sliding, deflection: {{file: {}}}}}\n",
      increments, extra, table);
}

}  // namespace hotmesh::test
