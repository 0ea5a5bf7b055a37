// hotmesh benchmark: the linear solvers of the Newton steps on whole motions — the paper's
// Jacobi-PCG against the system assembled in nodal frames and solved with algebraic multigrid
// (PETSc's GAMG) or with its sparse Cholesky factors (`direct`), each with the fixed inner
// tolerance and with the Eisenstat-Walker forcing term (inexact Newton).
//
//   ninja -C build bench_linear_solvers && build/bench/bench_linear_solvers [CASE.yaml ...] [--runs 3]
//       [--threads 1] [--hypre] [--linear jacobi-pcg,amg,direct,icc] [--forcing fixed,eisenstat-walker]
//
// Without cases: the samples ramp2d and shear2d, with and without sliding. scripts/bench.sh adds
// the stator-well sample and the sliding ramp refined by make_ramp2d --refine. --linear and
// --forcing keep the solvers and forcing terms named (default: all of them). Each case runs as `hotmesh deform` would
// (read and check the case, rebuild the deflected walls, deform::move_mesh) without writing the
// outputs, with every solver and forcing; prints a Markdown table of medians over the runs:
// the motion's time split into assembly (element matrices, and for amg and direct the matrix in
// frames), preconditioner (Jacobi blocks, the multigrid hierarchy, or the factorization), solve (the CG iterations) and
// projection (sliding nodes), the Newton and linear iteration totals, the time per linear
// iteration, and the other load (the mean number of cores other processes kept busy).
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "machine_load.hpp"

using namespace hotmesh;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Solver {
  deform::LinearSolverKind linear;
  deform::AmgPackage amg;
  deform::ForcingTerm forcing;
  std::string name() const {
    return linear == deform::LinearSolverKind::amg ? fmt::format("amg ({})", deform::to_string(amg))
                                                   : std::string(deform::to_string(linear));
  }
};

struct Run {
  deform::MotionTimings motion;
  std::size_t newton = 0;
  std::size_t linear = 0;
  double others = 0.0;
  bool success = false;
  std::vector<std::string> notes;  ///< the motion's (icc going over to direct, ...)
};

Run run_case(const io::Case& base, const io::LoadedMesh& loaded, const setup::CaseSetup& setup, const Solver& s) {
  io::Case c = base;
  c.solver.linear = s.linear;
  c.solver.amg = s.amg;
  c.solver.forcing = s.forcing;
  Run r;
  const bench::LoadProbe load;
  const deform::MotionResult result = deform::move_mesh(loaded.mesh, setup.motions, c.material, c.solver);
  r.others = load.others();
  r.motion = result.timings;
  r.success = result.success;
  r.notes = result.notes;
  for (const auto& increment : result.increments) {
    if (!increment.newton.empty()) r.newton += increment.newton.size() - 1;
    for (const auto& step : increment.newton) r.linear += static_cast<std::size_t>(step.pcg_iterations);
  }
  return r;
}

}  // namespace

/// Whether `list` (comma-separated) names `name`; an empty list names everything.
bool named(const std::string& list, std::string_view name) {
  if (list.empty()) return true;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = list.find(',', start);
    if (std::string_view(list).substr(start, end - start) == name) return true;
    if (end == std::string::npos) return false;
    start = end + 1;
  }
}

int main(int argc, char** argv) {
  std::vector<std::string> files;
  int runs = 3, threads = 1;
  bool hypre = false;
  std::string linear_list, forcing_list;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--threads" && i + 1 < argc) {
      threads = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--hypre") {
      hypre = true;
    } else if (arg == "--linear" && i + 1 < argc) {
      linear_list = argv[++i];
    } else if (arg == "--forcing" && i + 1 < argc) {
      forcing_list = argv[++i];
    } else if (!arg.starts_with("-")) {
      files.emplace_back(arg);
    } else {
      std::fprintf(stderr,
                   "usage: bench_linear_solvers [CASE.yaml ...] [--runs N] [--threads N] [--hypre] "
                   "[--linear jacobi-pcg,amg,direct,icc] [--forcing fixed,eisenstat-walker]\n");
      return 2;
    }
  }
  if (files.empty()) {
    for (const char* name : {"ramp2d/ramp2d.yaml", "ramp2d/ramp2d-sliding.yaml", "shear2d/shear2d.yaml",
                             "shear2d/shear2d-sliding.yaml"}) {
      files.push_back(std::string(HOTMESH_SAMPLES) + "/" + name);
    }
  }
  std::vector<Solver> solvers;
  for (const auto forcing : {deform::ForcingTerm::fixed, deform::ForcingTerm::eisenstat_walker}) {
    if (!named(forcing_list, deform::to_string(forcing))) continue;
    for (const auto linear : {deform::LinearSolverKind::jacobi_pcg, deform::LinearSolverKind::amg,
                              deform::LinearSolverKind::direct, deform::LinearSolverKind::icc}) {
      if (!named(linear_list, deform::to_string(linear))) continue;
      solvers.push_back({linear, deform::AmgPackage::gamg, forcing});
      if (linear == deform::LinearSolverKind::amg && hypre) solvers.push_back({linear, deform::AmgPackage::hypre, forcing});
    }
  }
  if (solvers.empty()) {
    std::fprintf(stderr, "bench_linear_solvers: --linear and --forcing leave no solver to run\n");
    return 2;
  }
  try {
    omp_set_num_threads(threads);
    fmt::print("{} thread{}, median of {} runs.\n\n", threads, threads > 1 ? "s" : "", runs);
    fmt::print("| case | cells | solver | forcing | motion s | assembly s | preconditioner s | solve s | projection s | "
               "Newton iterations | linear iterations | ms per linear iteration | other load |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& file : files) {
      const io::Case c = io::read_case(file);
      const io::LoadedMesh loaded = io::read_mesh(c.mesh);
      io::check_case_against_mesh(c, loaded.mesh);
      const setup::CaseSetup setup = setup::set_up_case(c, loaded.mesh);
      for (const Solver& s : solvers) {
        std::vector<Run> all;
        for (int k = 0; k < runs; ++k) {
          all.push_back(run_case(c, loaded, setup, s));
          std::fprintf(stderr, "%s, %s, %s, run %d: %.3f s, %zu Newton, %zu linear iterations%s\n", file.c_str(),
                       s.name().c_str(), std::string(deform::to_string(s.forcing)).c_str(), k + 1, all.back().motion.total,
                       all.back().newton, all.back().linear, all.back().success ? "" : " (the motion failed)");
        }
        const auto column = [&all](auto field) {
          std::vector<double> v;
          for (const Run& r : all) v.push_back(field(r));
          return median(v);
        };
        const Run& first = all.front();
        const double solve = column([](const Run& r) { return r.motion.solve; });
        const std::string name = std::filesystem::path(file).filename().string();
        fmt::print("| {} | {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.3f} | {} | {} | {:.3f} | {:.2f} |\n", name,
                   loaded.mesh.cell_count(), s.name(), deform::to_string(s.forcing),
                   column([](const Run& r) { return r.motion.total; }),
                   column([](const Run& r) { return r.motion.assembly; }),
                   column([](const Run& r) { return r.motion.preconditioner; }), solve,
                   column([](const Run& r) { return r.motion.projection; }), first.newton, first.linear,
                   1e3 * solve / static_cast<double>(std::max<std::size_t>(1, first.linear)),
                   column([](const Run& r) { return r.others; }));
        if (!first.success) fmt::print("\nThe motion of {} failed with {}.\n\n", name, s.name());
        for (const std::string& note : first.notes) fmt::print("\nNote from {} with {}: {}\n\n", name, s.name(), note);
        std::fflush(stdout);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_linear_solvers: %s\n", e.what());
    return 1;
  }
}
