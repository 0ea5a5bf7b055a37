// hotmesh tests: a coarse ramp channel built in code (fast, with sliding walls) and its case
// file, for tests that run `hotmesh deform` (tests/app, tests/samples).
#pragma once

#include <filesystem>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "test_support.hpp"

namespace hotmesh::test {

/// A coarse ramp channel written to `dir` (ramp.msh: 20 x 11 quads on 2 x 1, stretched
/// towards the floor), with tables for the half and the full ramp (half.csv, full.csv).
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

/// The coarse ramp's case without sliding: the floor prescribed over `table`, the top fixed;
/// `solver` is the inside of the case's solver map.
inline std::string prescribed_ramp_case(const std::string& table, const std::string& solver) {
  return fmt::format(
      "mesh: ramp.msh\nsolver: {{{}}}\n"
      "patches:\n  left: {{role: fixed}}\n  right: {{role: slip}}\n  top: {{role: fixed}}\n"
      "  bottom: {{role: prescribed, deflection: {{file: {}}}}}\n",
      solver, table);
}

}  // namespace hotmesh::test
