// hotmesh benchmark: the full solve of the paper's 2D ramp (samples/ramp2d, section 5), as
// `hotmesh deform samples/ramp2d/ramp2d.yaml` runs it, without writing the outputs.
//
//   ninja -C build bench_ramp && build/bench/bench_ramp [CASE.yaml] [--runs 5]
//
// (scripts/bench.sh builds and runs it with every other benchmark.) Each run reads and checks
// the case and its mesh, reconstructs the deflected wall from the FEM table and moves the mesh
// through all the case's increments (deform::move_mesh: Newton-Raphson, the paper's Jacobi-PCG
// unless the case names another solver (`linear: auto` would take icc for this 2D mesh: see
// bench_linear_solvers), quality checks), with 1 thread and with all of them. Prints a Markdown table of medians over the
// runs (each column its own median): wall time; the phases from MotionResult::timings (set-up,
// element matrices, PCG, quality, and the rest of the motion: residual products, updates of
// the points); Newton and PCG iteration totals and the time per PCG iteration, next to one
// product y = K x on the same mesh, and the other load: the mean number of cores other
// processes kept busy during the runs (rows with all threads and other load well above 0 are
// not the machine's speed).
// The iteration counts are the same in every run (the solver is deterministic); a run that
// differs is reported.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "machine_load.hpp"
#include "timing.hpp"

using namespace hotmesh;

namespace {

using bench::Clock;
using bench::seconds_since;
using bench::median;

/// One run of the whole job, timed.
struct Run {
  double wall = 0.0;
  double read = 0.0;    ///< case file, deflection table, mesh, checks
  double shapes = 0.0;  ///< deflected boundary shapes
  deform::MotionTimings motion;
  std::size_t newton = 0;
  std::size_t pcg = 0;
  std::size_t attempts = 0;  ///< increments tried, split pieces and rejected ones included
  double others = 0.0;       ///< mean number of cores busy with other processes
  bool success = false;
};

Run run_case(const std::string& file) {
  Run r;
  const bench::LoadProbe load;
  const auto start = Clock::now();
  io::Case c = io::read_case(file);
  if (c.solver.linear == deform::LinearSolverKind::automatic) c.solver.linear = deform::LinearSolverKind::jacobi_pcg;
  const io::LoadedMesh loaded = io::read_mesh(c.mesh);
  io::check_case_against_mesh(c, loaded.mesh);
  r.read = seconds_since(start);
  auto t = Clock::now();
  const setup::CaseSetup setup = setup::set_up_case(c, loaded.mesh);
  r.shapes = seconds_since(t);
  const deform::MotionResult result = deform::move_mesh(loaded.mesh, setup.motions, c.material, c.solver);
  r.wall = seconds_since(start);
  r.others = load.others();
  r.motion = result.timings;
  r.success = result.success;
  r.attempts = result.increments.size();
  for (const auto& increment : result.increments) {
    if (!increment.newton.empty()) r.newton += increment.newton.size() - 1;
    for (const auto& step : increment.newton) r.pcg += static_cast<std::size_t>(step.pcg_iterations);
  }
  return r;
}

/// Median seconds of one product y = K x on the case's mesh (K at the original points).
double product_seconds(const std::string& file) {
  const io::Case c = io::read_case(file);
  const io::LoadedMesh loaded = io::read_mesh(c.mesh);
  deform::StiffnessOperator k(loaded.mesh, deform::element_lame(loaded.mesh, c.material), c.material.drop_jacobian);
  k.update(loaded.mesh.points);
  std::vector<double> x(k.size(), 1e-3), y(k.size());
  constexpr int kProducts = 200;
  std::vector<double> times;
  for (int repeat = 0; repeat < 7; ++repeat) {
    const auto start = Clock::now();
    for (int i = 0; i < kProducts; ++i) k.apply(x, y);
    times.push_back(seconds_since(start) / kProducts);
  }
  return median(times);
}

}  // namespace

int main(int argc, char** argv) {
  std::string file = HOTMESH_RAMP_CASE;
  int runs = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (!arg.starts_with("-")) {
      file = arg;
    } else {
      std::fprintf(stderr, "usage: bench_ramp [CASE.yaml] [--runs N]\n");
      return 2;
    }
  }
  try {
    std::vector<int> thread_counts = {1};
    if (omp_get_max_threads() > 1) thread_counts.push_back(omp_get_max_threads());
    {
      const io::Case c = io::read_case(file);
      const io::LoadedMesh loaded = io::read_mesh(c.mesh);
      fmt::print("Case {}: {} cells, {} nodes, {} increments; median of {} runs.\n\n", file,
                 loaded.mesh.cell_count(), loaded.mesh.node_count(), c.solver.increments, runs);
    }
    fmt::print("| threads | wall s (min-max) | read + shapes s | set-up s | element matrices s | PCG s | quality s | "
               "rest of the motion s | Newton iterations | PCG iterations | us per PCG iteration | us per product | "
               "other load |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int threads : thread_counts) {
      omp_set_num_threads(threads);
      std::vector<Run> all;
      for (int k = 0; k < runs; ++k) {
        all.push_back(run_case(file));
        const Run& r = all.back();
        std::fprintf(stderr, "%d threads, run %d: %.3f s, %zu Newton, %zu PCG iterations%s\n", threads, k + 1, r.wall,
                     r.newton, r.pcg, r.success ? "" : " (the motion failed)");
        if (r.newton != all.front().newton || r.pcg != all.front().pcg || r.attempts != all.front().attempts) {
          std::fprintf(stderr, "bench_ramp: run %d took other iterations than run 1\n", k + 1);
        }
      }
      auto column = [&all](auto field) {
        std::vector<double> v;
        for (const Run& r : all) v.push_back(field(r));
        return median(v);
      };
      const double wall = column([](const Run& r) { return r.wall; });
      auto by_wall = [](const Run& a, const Run& b) { return a.wall < b.wall; };
      const double lowest = std::min_element(all.begin(), all.end(), by_wall)->wall;
      const double highest = std::max_element(all.begin(), all.end(), by_wall)->wall;
      const double solve = column([](const Run& r) { return r.motion.solve; });
      const double rest = column([](const Run& r) {
        const auto& m = r.motion;
        return m.total - m.setup - m.assembly - m.solve - m.quality;
      });
      const double product = product_seconds(file);
      const Run& first = all.front();
      fmt::print("| {} | {:.3f} ({:.3f}-{:.3f}) | {:.3f} | {:.4f} | {:.3f} | {:.3f} | {:.4f} | {:.3f} | {} | {} | "
                 "{:.1f} | {:.1f} | {:.2f} |\n",
                 threads, wall, lowest, highest, column([](const Run& r) { return r.read + r.shapes; }),
                 column([](const Run& r) { return r.motion.setup; }),
                 column([](const Run& r) { return r.motion.assembly; }), solve,
                 column([](const Run& r) { return r.motion.quality; }), rest, first.newton, first.pcg,
                 1e6 * solve / static_cast<double>(std::max<std::size_t>(1, first.pcg)), 1e6 * product,
                 column([](const Run& r) { return r.others; }));
      std::fflush(stdout);
      if (!first.success) fmt::print("\nThe motion failed with {} threads.\n", threads);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_ramp: %s\n", e.what());
    return 1;
  }
}
