// hotmesh tests: CalculiX models built in code and solved by the real ccx (Debian's
// calculix-ccx, installed by scripts/install-deps.sh), and the reference its .dat printout
// gives (`*NODE PRINT, NSET=..., U`: the displacements with seven digits).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/core/vec3.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::test {

inline bool have_ccx() { return run_command("command -v ccx >/dev/null 2>&1").exit_code == 0; }

/// Runs `ccx -i <job>` in `folder` (ccx writes <job>.frd and <job>.dat beside the deck).
inline CommandResult run_ccx(const std::filesystem::path& folder, const std::string& job) {
  return run_command("cd " + shell_quote(folder.string()) + " && ccx -i " + shell_quote(job) + " 2>&1");
}

/// The displacement tables of a .dat file, one per `*NODE PRINT` output, in file order.
inline std::vector<std::map<std::int64_t, geometry::Vec3>> dat_displacements(const std::string& dat) {
  std::vector<std::map<std::int64_t, geometry::Vec3>> tables;
  std::istringstream in(dat);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      tables.emplace_back();
      inside = true;
      continue;
    }
    std::istringstream fields(line);
    std::int64_t node = 0;
    geometry::Vec3 u;
    if (inside && (fields >> node >> u.x >> u.y >> u.z)) {
      tables.back()[node] = u;
    } else if (inside && !tables.back().empty()) {
      inside = false;
    }
  }
  return tables;
}

/// A ring of CAX4 elements, r in [0.1, 0.2] m, z in [0, 0.05] m, nr x nz elements, as the
/// deck `ring.inp` with its nodes in `ring_nodes.inp` and its sets in `ring_sets.inp`
/// (*INCLUDEs). Sets: BORE and OUTER (GENERATE), NALL; surfaces TOP (faces S3 of the top row)
/// and BOTTOM (faces S1 of the bottom row).
/// Step 1 heats it to 400 and spins it (CENTRIF, omega^2 = 1e6), step 2 cools it to 200.
/// `output` is "*NODE FILE" (ASCII .frd) or "*NODE OUTPUT" (binary .frd).
struct RingDeck {
  int nr = 8;
  int nz = 2;
  double r0 = 0.1, r1 = 0.2, height = 0.05;

  std::int64_t node(int i, int j) const { return 1 + i + static_cast<std::int64_t>(j) * (nr + 1); }
  geometry::Vec3 position(int i, int j) const { return {r0 + (r1 - r0) * i / nr, height * j / nz, 0.0}; }

  void write(const std::filesystem::path& folder, const std::string& output, const std::string& job = "ring") const {
    std::string nodes = "*NODE, NSET=NALL\n";
    for (int j = 0; j <= nz; ++j) {
      for (int i = 0; i <= nr; ++i) {
        const geometry::Vec3 x = position(i, j);
        nodes += fmt::format("{}, {:.17g}, {:.17g}\n", node(i, j), x.x, x.y);
      }
    }
    write_text(folder / "ring_nodes.inp", nodes);
    write_text(folder / "ring_sets.inp",
               fmt::format("** the bore and the rim, every (nr+1)-th node\n*NSET, NSET=bore, GENERATE\n1, {}, {}\n"
                           "*NSET, NSET=Outer, GENERATE\n{}, {}, {}\n",
                           node(0, nz), nr + 1, node(nr, 0), node(nr, nz), nr + 1));
    std::string elements = "*ELEMENT, TYPE=CAX4, ELSET=EALL\n";
    std::string top = "*ELSET, ELSET=ETOP\n";
    std::string bottom = "*ELSET, ELSET=EBOTTOM\n";
    for (int j = 0; j < nz; ++j) {
      for (int i = 0; i < nr; ++i) {
        const std::int64_t e = 1 + i + static_cast<std::int64_t>(j) * nr;
        elements += fmt::format("{}, {}, {}, {}, {}\n", e, node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1));
        if (j == nz - 1) top += fmt::format("{},\n", e);
        if (j == 0) bottom += fmt::format("{},\n", e);
      }
    }
    const auto step = [&](int temperature, const std::string& load) {
      return fmt::format("*STEP\n*STATIC\n*BOUNDARY\n1, 2, 2\n*TEMPERATURE\nNALL, {}\n{}{}\nU, NT\n"
                         "*NODE PRINT, NSET=NALL\nU\n*END STEP\n",
                         temperature, load, output);
    };
    write_text(folder / (job + ".inp"),
               "*HEADING\nhotmesh test ring\n*INCLUDE, INPUT=ring_nodes.inp\n" + elements + top + bottom +
                   "*INCLUDE, INPUT=ring_sets.inp\n*SURFACE, NAME=TOP, TYPE=ELEMENT\nETOP, S3\n"
                   "*SURFACE, NAME=BOTTOM\nEBOTTOM, S1\n"
                   "*MATERIAL, NAME=STEEL\n*ELASTIC\n200e9, 0.3\n*EXPANSION\n1.2e-5\n*DENSITY\n7800\n"
                   "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 20\n" +
                   step(400, "*DLOAD\nEALL, CENTRIF, 1e6, 0, 0, 0, 0, 1, 0\n") + step(200, ""));
  }
};

}  // namespace hotmesh::test
