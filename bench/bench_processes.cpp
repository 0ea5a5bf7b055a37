// hotmesh benchmark: one process against two under mpirun, with the amg solver. Each case is
// run as a user runs it — `hotmesh deform`, then `mpirun -n 2 hotmesh deform` — one thread
// per process, so that one process uses one core and two processes both cores; one process
// with two OpenMP threads is the comparison. Reports per run the wall time, the motion's
// phases (assembly: element matrices into the PETSc matrix and the residual; set-up: the
// multigrid hierarchy; solve: CG; projection: sliding nodes onto the CAD) and rank 0's peak
// memory (report.json).
//
// Run:   ninja -C build bench_processes hotmesh make_stator_well && build/bench/bench_processes [CELLS,...]
// Cases: the sliding ramp (7 000 quads), and the stator-well sector (sliding, periodic,
// passive) generated at each size in CELLS (default 18000,60000).
//
// Weak scaling (issue 25): build/bench/bench_processes --weak [CELLS [RANKS,...]] runs the
// sector with CELLS (default 50000) cells per rank on each number of ranks in RANKS (default
// 1,2,4,8; `--oversubscribe` where the machine has fewer cores), as the paper's size runs: `linear: amg`, Eisenstat-Walker forcing.
// On fewer cores than ranks the times say little; the CG iterations per linear solve are the
// measure: they stay flat when the multigrid scales.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "hotmesh/io/atomic_file.hpp"
#include "machine_load.hpp"

namespace {

namespace fs = std::filesystem;

/// A comma-separated list of numbers.
std::vector<long> numbers(const std::string& text) {
  std::vector<long> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) out.push_back(std::stol(item));
  return out;
}

bool run(const std::string& command) { return std::system(command.c_str()) == 0; }

/// A copy of the case with the amg solver (the samples write `solver: {increments: 16}` or a
/// block `solver:`), and with `forcing`, if given.
fs::path amg_case(const fs::path& original, const std::string& forcing = "") {
  std::string text = hotmesh::io::read_file(original);
  const std::string keys = forcing.empty() ? "linear: amg" : "linear: amg, forcing: " + forcing;
  const std::string lines = forcing.empty() ? "  linear: amg\n" : "  linear: amg\n  forcing: " + forcing + "\n";
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"solver: {increments: 16}", "solver: {increments: 16, " + keys + "}"},
                                 {"\nsolver:\n", "\nsolver:\n" + lines}}) {
    if (const auto at = text.find(from); at != std::string::npos) {
      text.replace(at, from.size(), to);
      break;
    }
  }
  const fs::path copy = original.parent_path() / "amg.yaml";
  hotmesh::io::write_file_atomically(copy, text);
  return copy;
}

struct Layout {
  const char* name;
  int processes;
  int threads;
};

void time_case(const std::string& label, const fs::path& case_file) {
  for (const Layout layout : {Layout{"1 process, 1 thread", 1, 1}, Layout{"1 process, 2 threads", 1, 2},
                              Layout{"2 processes, 1 thread each", 2, 1}}) {
    const fs::path out = case_file.parent_path() / "out";
    const std::string launcher =
        layout.processes > 1 ? fmt::format("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 {} -n {} ",
                                           HOTMESH_MPIEXEC, layout.processes)
                             : std::string();
    const hotmesh::bench::LoadProbe load;
    if (!run(fmt::format("OMP_WAIT_POLICY=passive OMP_NUM_THREADS={} {}{} -q deform --force '{}' -o '{}'", layout.threads,
                         launcher, HOTMESH_EXE, case_file.string(), out.string()))) {
      std::printf("| %s | %s | failed |\n", label.c_str(), layout.name);
      continue;
    }
    const double other = load.others();
    const auto r = nlohmann::json::parse(hotmesh::io::read_file(out / "report.json"));
    const auto& s = r["seconds"];
    std::printf("| %s | %s | %ld | %ld | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f | %.2f |\n", label.c_str(),
                layout.name, r["newton_iterations"].get<long>(), r["pcg_iterations"].get<long>(),
                r["wall_seconds"].get<double>(), s["motion"].get<double>(), s["assembly"].get<double>(),
                s["preconditioner"].get<double>(), s["solve"].get<double>(), s["projection"].get<double>(),
                r["peak_memory_bytes"].get<double>() / 1e6, other);
    std::fflush(stdout);
  }
}

/// Weak scaling: `per_rank` cells per rank on each number of ranks in `rank_counts`, the first
/// the reference.
int weak_scaling(long per_rank, const std::vector<long>& rank_counts) {
  const fs::path folder = fs::temp_directory_path() / "hotmesh-bench-weak-scaling";
  fs::remove_all(folder);
  std::printf("### Weak scaling: the sector at %ld cells per rank (`linear: amg`, Eisenstat-Walker, 16 increments)\n\n",
              per_rank);
  std::printf("| ranks | cells | Newton steps | CG iterations | CG per solve | CG per solve vs 1 rank | wall s | "
              "peak memory rank 0 (MB) | other load |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  double first = 0.0;
  for (const long ranks : rank_counts) {
    const long cells = per_rank * ranks;
    const fs::path dir = folder / fmt::format("stator-{}", cells);
    if (!run(fmt::format("{} --cells {} '{}' > /dev/null", HOTMESH_MAKE_STATOR_WELL, cells, dir.string()))) return 1;
    const fs::path case_file = amg_case(dir / "case_small.yaml", "eisenstat-walker");
    const fs::path out = dir / "out";
    const std::string launcher =
        ranks > 1 ? fmt::format("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 {} -n {} --oversubscribe "
                                "--mca mpi_yield_when_idle 1 ",
                                HOTMESH_MPIEXEC, ranks)
                  : std::string();
    const hotmesh::bench::LoadProbe load;
    if (!run(fmt::format("OMP_WAIT_POLICY=passive OMP_NUM_THREADS=1 {}{} -q deform --threads 1 --force '{}' -o '{}'",
                         launcher, HOTMESH_EXE, case_file.string(), out.string()))) {
      std::printf("| %ld | %ld | failed |\n", ranks, cells);
      continue;
    }
    const double other = load.others();
    const auto r = nlohmann::json::parse(hotmesh::io::read_file(out / "report.json"));
    const long newton = r["newton_iterations"].get<long>(), cg = r["pcg_iterations"].get<long>();
    const double per_solve = static_cast<double>(cg) / static_cast<double>(newton);
    if (ranks == rank_counts.front()) first = per_solve;
    std::printf("| %ld | %ld | %ld | %ld | %.1f | %+.0f %% | %.0f | %.0f | %.2f |\n", ranks, cells, newton, cg, per_solve,
                100.0 * (per_solve / first - 1.0), r["wall_seconds"].get<double>(),
                r["peak_memory_bytes"].get<double>() / 1e6, other);
    std::fflush(stdout);
  }
  fs::remove_all(folder);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--weak") {
    return weak_scaling(argc > 2 ? std::stol(argv[2]) : 50000, numbers(argc > 3 ? argv[3] : "1,2,4,8"));
  }
  const fs::path folder = fs::temp_directory_path() / "hotmesh-bench-processes";
  fs::remove_all(folder);
  std::printf("### One process against two (`linear: amg`, 16 increments)\n\n");
  std::printf("| case | layout | Newton | CG | wall s | motion s | assembly s | set-up s | solve s | projection s | "
              "peak memory rank 0 (MB) | other load |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const fs::path ramp = folder / "ramp2d";
  fs::create_directories(ramp);
  for (const char* name : {"ramp2d.msh", "ramp.csv", "ramp2d-sliding.yaml"}) {
    fs::copy_file(fs::path(HOTMESH_SAMPLES) / "ramp2d" / name, ramp / name);
  }
  time_case("ramp2d-sliding", amg_case(ramp / "ramp2d-sliding.yaml"));
  for (const long cells : numbers(argc > 1 ? argv[1] : "18000,60000")) {
    const fs::path dir = folder / fmt::format("stator-{}", cells);
    if (!run(fmt::format("{} --cells {} '{}' > /dev/null", HOTMESH_MAKE_STATOR_WELL, cells, dir.string()))) return 1;
    time_case(fmt::format("stator well {} cells", cells), amg_case(dir / "case_small.yaml"));
  }
  fs::remove_all(folder);
  return 0;
}
