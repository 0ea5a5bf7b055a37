// hotmesh benchmark: the stator-well sector solved at growing sizes with the current solver
// (matrix-free Jacobi-PCG): the sample's case with sliding on, 16 increments, as a user runs it —
// make_stator_well writes the mesh, CAD file and tables, `hotmesh deform` moves the mesh.
// Reports per size the time, the Newton and PCG iterations and the peak memory (report.json).
//
// Run:   ninja -C build bench_stator_solve && build/bench/bench_stator_solve [CELLS,...]
// (default 5000,18000,50000; each size runs in its own process; the largest takes minutes).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "hotmesh/io/atomic_file.hpp"
#include "machine_load.hpp"

namespace {

std::vector<long> sizes(int argc, char** argv) {
  std::vector<long> out;
  std::stringstream list(argc > 1 ? argv[1] : "5000,18000,50000");
  for (std::string item; std::getline(list, item, ',');) out.push_back(std::stol(item));
  return out;
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return status == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const auto folder = std::filesystem::temp_directory_path() / "hotmesh-bench-stator";
  std::printf("### Stator-well sector, sliding on, 16 increments (`case_small.yaml` at growing sizes)\n\n");
  std::printf("| target cells | hex cells | nodes | sliding nodes | Newton | PCG | wall s | solve s | ms per PCG iteration | "
              "peak memory (MB) | min scaled Jacobian | other load |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const long cells : sizes(argc, argv)) {
    std::filesystem::remove_all(folder);
    const auto dir = folder / std::to_string(cells);
    if (run(fmt::format("{} --cells {} '{}' > /dev/null", HOTMESH_MAKE_STATOR_WELL, cells, dir.string())) != 0) return 1;
    const hotmesh::bench::LoadProbe load;
    if (run(fmt::format("OMP_WAIT_POLICY=passive {} -q deform '{}'", HOTMESH_EXE, (dir / "case_small.yaml").string())) != 0) {
      return 1;
    }
    const double other = load.others();
    const auto r = nlohmann::json::parse(hotmesh::io::read_file(dir / "case_small-out" / "report.json"));
    const double solve = r["seconds"]["solve"].get<double>();
    const long pcg = r["pcg_iterations"].get<long>();
    std::printf("| %ld | %ld | %ld | %ld | %ld | %ld | %.1f | %.1f | %.2f | %.0f | %.3f | %.2f |\n", cells,
                r["mesh"]["cells"].get<long>(), r["mesh"]["nodes"].get<long>(), r["sliding_nodes"].get<long>(),
                r["newton_iterations"].get<long>(), pcg, r["wall_seconds"].get<double>(), solve,
                1e3 * solve / static_cast<double>(pcg), r["peak_memory_bytes"].get<double>() / 1e6,
                r["min_scaled_jacobian"].get<double>(), other);
    std::fflush(stdout);
  }
  std::filesystem::remove_all(folder);
  return 0;
}
