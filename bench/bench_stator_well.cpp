// hotmesh benchmark: generation of the stator-well sector mesh (samples/stator_well) at growing
// sizes, up to and beyond the paper's 2.7 million cells. For each size, in a child process of
// its own (so that its peak memory is its own): the meridional blocks, the sweep in theta, the
// validation hotmesh does on load (validate_mesh), the quality of every cell and the binary Gmsh
// file written to a temporary folder. No solver.
//
// Run:   ninja -C build bench_stator_well && build/bench/bench_stator_well [CELLS...]
// (default 20000 200000 1000000 2700000 5400000). Prints a Markdown table for docs/performance.md.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "stator_well.hpp"

namespace {

using namespace hotmesh::samples::stator_well;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Builds one size and prints its row but the memory column (the parent adds it).
void run(std::int64_t target, const std::filesystem::path& folder) {
  auto t = Clock::now();
  const auto loop = profile();
  const hotmesh::samples::BlockMesher mesher(block_layout(loop), spacing_field());
  const Size size = size_for_cells(mesher, target);
  const auto section = mesher.mesh(size.refinement);
  const double t_section = since(t);
  t = Clock::now();
  auto mesh = sector_mesh(section, loop, size.theta_cells);
  const double t_sweep = since(t);
  t = Clock::now();
  hotmesh::mesh::validate_mesh(mesh);
  const double t_validate = since(t);
  t = Clock::now();
  const auto quality = hotmesh::mesh::summarize_quality(hotmesh::mesh::scaled_jacobians(mesh.cells, mesh.points));
  const double t_quality = since(t);
  t = Clock::now();
  const auto file = folder / ("stator_well_" + std::to_string(target) + ".msh");
  hotmesh::io::write_gmsh(file, mesh, {.binary = true});
  const double t_write = since(t);
  const double megabytes = static_cast<double>(std::filesystem::file_size(file)) / 1e6;
  std::filesystem::remove(file);
  std::printf("| %lld | %.3f | %d | %lld | %lld | %lld | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %.3f |",
              static_cast<long long>(target), size.refinement, size.theta_cells, static_cast<long long>(size.quads),
              static_cast<long long>(size.cells), static_cast<long long>(mesh.node_count()), t_section, t_sweep, t_validate,
              t_quality, t_write, megabytes, quality.min_scaled_jacobian);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::int64_t> targets;
  for (int i = 1; i < argc; ++i) targets.push_back(std::atoll(argv[i]));
  if (targets.empty()) targets = {20000, 200000, 1000000, 2700000, 5400000};
  const auto folder = std::filesystem::temp_directory_path() / ("hotmesh-bench-stator-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::printf("| target cells | refinement | theta cells | quads | hex cells | nodes | blocks (s) | sweep (s) | validate (s) "
              "| quality (s) | write binary .msh (s) | file (MB) | min scaled Jacobian | peak memory (MB) |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  int status = 0;
  for (const std::int64_t target : targets) {
    const pid_t child = ::fork();
    if (child == 0) {
      run(target, folder);
      std::_Exit(0);
    }
    rusage usage{};
    int child_status = 0;
    ::wait4(child, &child_status, 0, &usage);
    if (!WIFEXITED(child_status) || WEXITSTATUS(child_status) != 0) {
      std::printf(" failed |\n");
      status = 1;
      continue;
    }
    std::printf(" %.0f |\n", static_cast<double>(usage.ru_maxrss) / 1024.0);  // ru_maxrss is in KiB
    std::fflush(stdout);
  }
  std::filesystem::remove_all(folder);
  return status;
}
