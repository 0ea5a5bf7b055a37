// hotmesh benchmark: the stator-well sector solved at growing sizes: the sample's case with
// sliding on, 16 increments, as a user runs it — make_stator_well writes the mesh, CAD file and
// tables, `hotmesh deform --binary` moves the mesh. Reports per size the time and its phases
// (assembly, preconditioner, solve, projection), the Newton and linear iterations and the peak
// memory, all from report.json.
//
// Run:   ninja -C build bench_stator_solve && build/bench/bench_stator_solve [CELLS,...]
//            [--linear auto|jacobi-pcg|amg] [--forcing fixed|eisenstat-walker] [--ranks N]
// Default 5000,18000,50000 with the case's solver (`linear: auto`, fixed inner tolerance);
// each size runs in its own process, or with `--ranks N` in N processes of one thread under
// mpirun (peak memory: the processes' peaks summed, report.json's
// peak_memory_bytes_all_ranks). The paper's size on two ranks (`2700000 --forcing
// eisenstat-walker --ranks 2`, with PETSc's lean triple products, docs/parallel-runs.md) takes
// 15 to 18 minutes and 12.5 GiB: `scripts/bench.sh --paper-size`.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "hotmesh/io/atomic_file.hpp"
#include "machine_load.hpp"

namespace {

struct Options {
  std::vector<long> sizes;
  std::string linear, forcing;  ///< empty: the case's own (auto, fixed)
  int ranks = 1;                 ///< processes under mpirun (1: hotmesh alone)
};

[[noreturn]] void usage() {
  std::fprintf(stderr,
               "usage: bench_stator_solve [CELLS,...] [--linear auto|jacobi-pcg|amg] [--forcing fixed|eisenstat-walker] "
               "[--ranks N]\n");
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  std::string list = "5000,18000,50000";
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if ((a == "--linear" || a == "--forcing") && i + 1 < argc) {
      (a == "--linear" ? o.linear : o.forcing) = argv[++i];
    } else if (a == "--ranks" && i + 1 < argc) {
      o.ranks = std::atoi(argv[++i]);
      if (o.ranks < 1) usage();
    } else if (!a.empty() && a.find_first_not_of("0123456789,") == std::string_view::npos) {
      list = a;
    } else {
      usage();
    }
  }
  if (!o.linear.empty() && o.linear != "auto" && o.linear != "jacobi-pcg" && o.linear != "amg") usage();
  if (!o.forcing.empty() && o.forcing != "fixed" && o.forcing != "eisenstat-walker") usage();
  std::stringstream items(list);
  for (std::string item; std::getline(items, item, ',');) o.sizes.push_back(std::stol(item));
  return o;
}

/// The generated case with the chosen solver: its flow-style `solver: {...}` map gains the keys.
void choose_solver(const std::filesystem::path& file, const Options& o) {
  std::string extra;
  if (!o.linear.empty()) extra += ", linear: " + o.linear;
  if (!o.forcing.empty()) extra += ", forcing: " + o.forcing;
  if (extra.empty()) return;
  std::string text = hotmesh::io::read_file(file);
  const auto line = text.find("\nsolver: {");
  const auto end = line == std::string::npos ? line : text.find('}', line);
  if (end == std::string::npos || text.find('\n', line + 1) < end) {
    std::fprintf(stderr, "bench_stator_solve: no `solver: {...}` line in %s\n", file.c_str());
    std::exit(1);
  }
  text.insert(end, extra);
  hotmesh::io::write_file_atomically(file, text);
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return status == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  const auto folder = std::filesystem::temp_directory_path() / "hotmesh-bench-stator";
  std::printf("### Stator-well sector, sliding on, 16 increments (`case_small.yaml` at growing sizes), linear %s, forcing %s, "
              "%d process%s\n\n",
              options.linear.empty() ? "auto" : options.linear.c_str(),
              options.forcing.empty() ? "fixed" : options.forcing.c_str(), options.ranks, options.ranks > 1 ? "es" : "");
  std::printf("| target cells | hex cells | nodes | sliding nodes | solver | Newton | CG | wall s | assembly s | "
              "preconditioner s | solve s | projection s | ms per CG iteration | peak memory (MB) | min scaled Jacobian | "
              "other load |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const long cells : options.sizes) {
    std::filesystem::remove_all(folder);
    const auto dir = folder / std::to_string(cells);
    if (run(fmt::format("{} --cells {} --binary '{}' > /dev/null", HOTMESH_MAKE_STATOR_WELL, cells, dir.string())) != 0) {
      return 1;
    }
    choose_solver(dir / "case_small.yaml", options);
    const hotmesh::bench::LoadProbe load;
    const std::string launcher =
        options.ranks > 1 ? fmt::format("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 {} -n {} ",
                                         HOTMESH_MPIEXEC, options.ranks)
                          : std::string();
    if (run(fmt::format("OMP_WAIT_POLICY=passive {}{} -q deform --binary{} '{}'", launcher, HOTMESH_EXE,
                        options.ranks > 1 ? " --threads 1" : "", (dir / "case_small.yaml").string())) != 0) {
      return 1;
    }
    const double other = load.others();
    const auto r = nlohmann::json::parse(hotmesh::io::read_file(dir / "case_small-out" / "report.json"));
    const auto& seconds = r["seconds"];
    const double solve = seconds["solve"].get<double>();
    const long pcg = r["pcg_iterations"].get<long>();
    std::printf("| %ld | %ld | %ld | %ld | %s | %ld | %ld | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.0f | %.3f | %.2f |\n",
                cells, r["mesh"]["cells"].get<long>(), r["mesh"]["nodes"].get<long>(), r["sliding_nodes"].get<long>(),
                r["solver"]["linear"].get<std::string>().c_str(), r["newton_iterations"].get<long>(), pcg, r["wall_seconds"].get<double>(), seconds["assembly"].get<double>(),
                seconds["preconditioner"].get<double>(), solve, seconds["projection"].get<double>(),
                1e3 * solve / static_cast<double>(pcg), r["peak_memory_bytes_all_ranks"].get<double>() / 1e6,
                r["min_scaled_jacobian"].get<double>(), other);
    std::fflush(stdout);
  }
  std::filesystem::remove_all(folder);
  return 0;
}
