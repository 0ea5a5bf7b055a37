// hotmesh sample: a coupled FEA/CFD loop on the stator well (samples/stator_well). The rotor's
// CalculiX model is written from the same profile as the CFD sector (disc_deck.hpp); the real
// ccx solves it, and its .frd drives the sector's rotor walls directly; a second coupling
// iteration with a hotter disc restarts from the first one's state (the paper's eq. 22).
//
// Run:   build/samples/coupled_disc/make_coupled_disc [OUTPUT_FOLDER]     (default: here)
// Writes
//   disc_mesh.inp            the band's nodes, elements, wall surfaces and bore (an *INCLUDE)
//   disc_1.inp, disc_2.inp   the decks of coupling iterations 1 and 2 (temperatures differ)
//   case_1.yaml, case_2.yaml the mesh-motion cases: the stator well's small sector, its CAD
//                            file and stator tables from ../stator_well, every rotor wall
//                            from disc_<i>.frd; case_2 restarts from case_1-out/restart.hmr
// Then run_loop.sh runs ccx and hotmesh for both iterations (README.md: the recipe).
#include <algorithm>
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "disc_deck.hpp"
#include "fem_tables.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "sample_generator.hpp"

namespace {

using namespace hotmesh::samples;
using stator_well::Patch;

constexpr const char* kStatorWell = "../stator_well";  // the shared sample, relative to this folder

/// The two iterations' disc loads: the second runs 40 degrees hotter.
coupled_disc::DiscLoad iteration_load(int iteration) {
  coupled_disc::DiscLoad load;
  load.bore_temperature += 40.0 * (iteration - 1);
  load.rim_temperature += 40.0 * (iteration - 1);
  return load;
}

/// The CalculiX surface of a rotor wall, empty for the others.
std::string deck_surface(Patch patch) {
  const auto& walls = coupled_disc::kRotorWalls;
  return std::find(std::begin(walls), std::end(walls), patch) != std::end(walls) ? coupled_disc::deck_set(patch) : "";
}

std::string deflection_entry(const std::vector<stator_well::ProfileCurve>& loop, Patch patch, int iteration) {
  const std::string faces = fmt::format("faces: [{}], form: displacement", fmt::join(stator_well::cad_faces(loop, patch), ", "));
  if (const std::string set = deck_surface(patch); !set.empty()) {
    return fmt::format(", deflection: {{calculix: {{frd: disc_{0}.frd, inp: disc_{0}.inp, set: {1}}}, {2}}}", iteration,
                       set, faces);
  }
  return fmt::format(", deflection: {{file: {}/{}, {}}}", kStatorWell, stator_well::table_file(patch), faces);
}

std::string case_file(const std::vector<stator_well::ProfileCurve>& loop, int iteration) {
  std::string text = fmt::format(
      "# hotmesh sample coupled_disc, coupling iteration {0}: the stator well's small sector moved by\n"
      "# CalculiX's results for the rotor (disc_{0}.frd, from disc_{0}.inp) on every rotor wall,\n"
      "# by the stator well's tables on the stator. Written by make_coupled_disc; run\n"
      "# run_loop.sh, or: ccx -i disc_{0} && hotmesh deform case_{0}.yaml\n"
      "mesh: {1}/stator_well.msh\ncad: {1}/stator_well.step\n"
      "axis: {{origin: [0, 0, 0], direction: [0, 0, 1]}}\nsolver: {{increments: 8}}\n",
      iteration, kStatorWell);
  if (iteration > 1) {
    text += fmt::format("# the previous iteration's state: its walls' slides carry over (eq. 22)\n"
                        "restart: case_{}-out/restart.hmr\n", iteration - 1);
  }
  text += "patches:\n";
  const auto tables = stator_well::table_patches();
  for (int p = 0; p < stator_well::kPatchCount; ++p) {
    const auto patch = static_cast<Patch>(p);
    text += fmt::format("  {}: {{role: {}", stator_well::name(patch), stator_well::role(patch, true));
    if (std::find(tables.begin(), tables.end(), patch) != tables.end()) text += deflection_entry(loop, patch, iteration);
    if (patch == Patch::per_lo) text += fmt::format(", partner: per_hi, angle_deg: {}", stator_well::kSectorDegrees);
    text += "}\n";
  }
  return text;
}

void write_sample(const std::filesystem::path& folder) {
  using hotmesh::io::write_file_atomically;
  const auto loop = stator_well::profile();
  write_file_atomically(folder / "disc_mesh.inp", coupled_disc::disc_mesh_deck(loop));
  for (const int i : {1, 2}) {
    const coupled_disc::DiscLoad load = iteration_load(i);
    write_file_atomically(folder / fmt::format("disc_{}.inp", i),
                          coupled_disc::disc_deck(loop, "disc_mesh.inp", load,
                                                  fmt::format("stator well rotor band, coupling iteration {}", i)));
    write_file_atomically(folder / fmt::format("case_{}.yaml", i), case_file(loop, i));
  }
  fmt::print("coupled_disc: wrote disc_mesh.inp, disc_1.inp, disc_2.inp, case_1.yaml, case_2.yaml to {}\n",
             folder.string());
}

}  // namespace

int main(int argc, char** argv) { return run_generator("make_coupled_disc", argc, argv, write_sample); }
