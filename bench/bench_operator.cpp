// hotmesh benchmark: the stiffness operator (K summed from the element matrices into d x d node
// blocks, stiffness_operator.hpp) against the memory bandwidth of the machine it runs on, and
// against the paper's storage of every element matrix (section 3, eqs. 9-10).
//
//   ninja -C build bench_operator && build/bench/bench_operator [--hex 20,40,60,80,100]
//       [--quad 250,1000,2000] [--triad-mib 1024] [--pcg 40]
//
// (scripts/bench.sh builds and runs it with every other benchmark.) Each number is the median
// of several runs, with 1 thread and with all of them (OpenMP). Prints Markdown tables:
//
// 1. Memory bandwidth: a STREAM triad a[i] = b[i] + s c[i] on three arrays of `--triad-mib`
//    MiB each (far larger than the caches; STREAM's count of 24 bytes per entry, no
//    write-allocate traffic), and for reference on arrays that fit in L2 and in L3.
// 2. Update: StiffnessOperator::update (every K_e at the given points, summed into the node
//    blocks), cells/s.
// 3. Product: StiffnessOperator::apply (y = K x), cells/s, GFLOP/s (2 d^2 per block) and
//    effective GB/s over the bytes a product must move at least:
//        blocks         stored blocks x (d^2 x 8 + 4)  (on and above the diagonal: the values
//                                                       and a 32-bit column, each read once)
//        row starts     nodes x 8
//        vectors        dofs x 8 x 2                   (x read, y written)
//    and that rate over the triad's with the same number of threads.
// 3b. The product per cell type (`--types N`): a hex block of N^3 cells as hexes, prisms,
//    pyramids and tetrahedra (mesh::split_cells), a quad block of (25 N)^2 as quads and
//    triangles: time per node against the hexes (quads) and the ratio of the stencils; and
//    the same product with the paper's storage, every K_e stored and y = K x an element loop
//    colour by colour (ElementStorage below), for comparison.
// 4. One Jacobi-PCG solve (the solver's inner solve, tolerance 1e-3, from p = 0) on a hex
//    block `--pcg` cells on a side, stretched towards z = 0, with a bump prescribed on z = 0
//    and every other boundary node fixed: iterations, time per iteration, the share of it
//    spent in products, and the time to build the Jacobi preconditioner (K's diagonal).
// 5. The cost of starting an OpenMP team next to the work each threshold of
//    mesh/include/hotmesh/mesh/parallel_loops.hpp keeps on one thread (estimated from the rates measured above).
//
// "other load" is the mean number of cores other processes kept busy during a measurement
// (from /proc/stat): on a shared machine, rows with all threads and other load well above 0
// are not the machine's speed.
//
// Memory: the node blocks take 1.4 kB per hex node (1.5 GB at 100^3, with the cells' block
// positions), the paper's stored K_e (part 3b only, at most 40^3 hexes) 4.6 kB per hex; the
// triad 3 x `--triad-mib` MiB. One mesh is alive at a time.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/deform/element_stiffness.hpp"
#include "hotmesh/deform/linear_algebra.hpp"
#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/pcg.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"  // the OpenMP thresholds under test in part 5
#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "machine_load.hpp"
#include "timing.hpp"

using namespace hotmesh::deform;
using namespace hotmesh::mesh;

namespace {

using hotmesh::bench::Clock;
using hotmesh::bench::seconds_since;

/// The median duration of runs, and the mean number of cores other processes kept busy
/// during them.
struct Timing {
  double seconds = 0.0;
  double others = 0.0;
};

/// Times `run` after `warmup` untimed calls: at least `min_runs` runs and, while they take
/// less than `min_total` seconds in all, more (at most 200).
template <class Run>
Timing time_runs(Run&& run, int warmup, int min_runs, double min_total) {
  for (int i = 0; i < warmup; ++i) run();
  std::vector<double> times;
  double total = 0.0;
  const hotmesh::bench::LoadProbe load;
  while (static_cast<int>(times.size()) < min_runs || (total < min_total && times.size() < 200)) {
    const auto start = Clock::now();
    run();
    times.push_back(seconds_since(start));
    total += times.back();
  }
  std::sort(times.begin(), times.end());
  return {times[times.size() / 2], load.others()};
}

std::vector<int> parse_list(std::string_view text) {
  std::vector<int> values;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string item(text.substr(begin, end - begin));
    if (!item.empty()) values.push_back(std::atoi(item.c_str()));
    begin = end + 1;
  }
  return values;
}

struct Settings {
  std::vector<int> hex = {20, 40, 60, 80, 100};
  std::vector<int> quad = {250, 1000, 2000};
  int triad_mib = 1024;
  int pcg_cells = 40;
  int types = 40;  ///< hex block of types^3 cells and quad block of (25 types)^2 split per cell type; 0: none
};

Settings parse_arguments(int argc, char** argv) {
  Settings s;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view key = argv[i];
    const std::string_view value = argv[i + 1];
    if (key == "--hex") {
      s.hex = parse_list(value);
    } else if (key == "--quad") {
      s.quad = parse_list(value);
    } else if (key == "--triad-mib") {
      s.triad_mib = std::atoi(argv[i + 1]);
    } else if (key == "--pcg") {
      s.pcg_cells = std::atoi(argv[i + 1]);
    } else if (key == "--types") {
      s.types = std::atoi(argv[i + 1]);
    } else {
      std::fprintf(stderr, "bench_operator: unknown option %s\n", argv[i]);
      std::exit(2);
    }
  }
  if (argc % 2 == 0) {
    std::fprintf(stderr, "usage: bench_operator [--hex 20,40,...] [--quad 250,...] [--triad-mib M] [--pcg N] [--types N]\n");
    std::exit(2);
  }
  return s;
}

// ---------------------------------------------------------------------------------------
// 1. Memory bandwidth

/// The triad a = b + s c over `entries` doubles per array, with the current threads.
struct Rate {
  double gbs = 0.0;
  double others = 0.0;
};
Rate triad_rate(std::size_t entries) {
  std::vector<double> a(entries), b(entries), c(entries);
  const auto n = static_cast<std::ptrdiff_t>(entries);
#pragma omp parallel for schedule(static)  // first touch by the threads that use the pages
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    a[k] = 0.0;
    b[k] = 1.0;
    c[k] = 2.0;
  }
  // Repeat small arrays so that one timed run lasts about 10 ms.
  const int repeats = std::max(1, static_cast<int>(4.0e6 / static_cast<double>(entries)));
  double s = 0.5;
  const Timing timing = time_runs(
      [&] {
        double* pa = a.data();
        const double* pb = b.data();
        const double* pc = c.data();
#pragma omp parallel
        for (int r = 0; r < repeats; ++r) {
#pragma omp for schedule(static)
          for (std::ptrdiff_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
        }
        s = -s;
      },
      1, 10, 0.5);
  if (!std::isfinite(a[entries / 2])) std::fprintf(stderr, "triad: not finite\n");
  return {24.0 * static_cast<double>(entries) * repeats / timing.seconds * 1e-9, timing.others};
}

// ---------------------------------------------------------------------------------------
// 2-3. Element matrices and products

struct ProductModel {
  double bytes = 0.0;  ///< at least moved by one product (see the file's comment)
  double flops = 0.0;
};

ProductModel product_model(const StiffnessOperator& k) {
  const auto d = static_cast<double>(k.dofs_per_node());
  const auto stored = static_cast<double>(k.block_count());
  const auto nonzero = static_cast<double>(k.nonzero_blocks());
  const double nodes = static_cast<double>(k.size()) / d;
  return {stored * (d * d * 8.0 + 4.0) + nodes * 8.0 + static_cast<double>(k.size()) * 8.0 * 2.0,
          2.0 * d * d * nonzero};
}

/// The paper's storage (section 3, eqs. 9-10), for comparison: every K_e stored, y = K x an
/// element loop, colour by colour, the cells of a colour in parallel. Meshes of one cell type.
class ElementStorage {
 public:
  ElementStorage(const StiffnessKernel& kernel, std::span<const Vec3> points) : kernel_(kernel) {
    const ElementList& cells = kernel.cells();
    const auto n = static_cast<std::size_t>(kernel.element_size(0));
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells.type(c) != cells.type(0)) throw std::invalid_argument("ElementStorage: cells of one type");
    }
    matrices_.resize(cells.size() * n * n);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      kernel.element_matrix(static_cast<CellId>(c), points, {matrices_.data() + c * n * n, n * n});
    }
  }
  double bytes() const { return static_cast<double>(matrices_.size()) * 8.0; }
  void apply(std::span<const double> x, std::span<double> y) const {
    std::fill(y.begin(), y.end(), 0.0);
    const ElementList& cells = kernel_.cells();
    const CellColoring& coloring = kernel_.coloring();
    const auto d = static_cast<std::size_t>(kernel_.dofs_per_node());
    with_element_size(cells.nodes(0).size(), d, [&](auto n, auto dofs) {
      for (std::size_t k = 0; k < coloring.colors(); ++k) {
        const auto begin = coloring.offsets[k], end = coloring.offsets[k + 1];
#pragma omp parallel for schedule(static) if ((end - begin) * static_cast<std::int64_t>(n * n) >= kParallelProduct)
        for (std::int64_t i = begin; i < end; ++i) {
          const auto c = static_cast<std::size_t>(coloring.cells[static_cast<std::size_t>(i)]);
          add_element_product<n, dofs>(cells.nodes(c), matrices_.data() + c * n * n, x, y);
        }
      }
    });
  }

 private:
  const StiffnessKernel& kernel_;
  std::vector<double> matrices_;
};

std::vector<double> random_vector(std::size_t n) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& x : v) x = uniform(random);
  return v;
}

/// Rates measured on one mesh with one number of threads.
struct OperatorRates {
  Timing update;
  Timing apply;
};

struct Row {
  std::string mesh;
  std::size_t cells = 0;
  std::size_t dofs = 0;
  double stencil = 0.0;  ///< blocks per row
  int threads = 0;
  ProductModel model;
  OperatorRates rates;
  double bytes = 0.0;  ///< held by the operator
};

OperatorRates measure_operator(StiffnessOperator& k, const Mesh& mesh, int threads) {
  omp_set_num_threads(threads);
  OperatorRates r;
  // update() recomputes every K_e into the blocks, already allocated and touched.
  r.update = time_runs([&] { k.update(mesh.points); }, 0, 3, 1.0);
  const auto x = random_vector(k.size());
  std::vector<double> y(k.size());
  r.apply = time_runs([&] { k.apply(x, y); }, 1, 5, 1.0);
  return r;
}

Mesh hex_block(int n) {
  const auto line = uniform_line(0.0, 1.0, n);
  return structured_hexes(line, line, line);
}

Mesh quad_block(int n) {
  const auto line = uniform_line(0.0, 1.0, n);
  return structured_quads(line, line);
}

/// 3b. The product on meshes of each cell type made from one hex block (and one quad block) by
/// mesh::split_cells, per node against the block of hexes (quads): the element type's cost
/// next to the ratio of the stencils (the mean blocks per row: the nodes a node shares a cell
/// with, itself included), for the node blocks and for the paper's stored K_e.
void types_section(int n, const std::vector<int>& thread_counts, const std::vector<double>& memory_rate) {
  struct TypeMesh {
    std::string label;
    Mesh mesh;
  };
  const Mesh hexes = hex_block(n);
  const Mesh quads = quad_block(25 * n);
  const auto split = [](const Mesh& m, CellSplit how) { return split_cells(m, std::vector<CellSplit>(m.cell_count(), how)); };
  std::vector<TypeMesh> meshes;
  meshes.push_back({fmt::format("hex8 ({}^3 hexes)", n), hexes});
  meshes.push_back({"wedge6 (2 per hex)", split(hexes, CellSplit::prisms)});
  meshes.push_back({"pyramid5 (6 per hex, centre node)", split(hexes, CellSplit::pyramids)});
  meshes.push_back({"tet4 (12 per hex, centre node)", split(hexes, CellSplit::tetrahedra)});
  meshes.push_back({fmt::format("quad4 ({}^2 quads)", 25 * n), quads});
  meshes.push_back({"tri3 (2 per quad)", split(quads, CellSplit::triangles)});
  fmt::print("\n### Product per cell type (StiffnessOperator::apply, and the paper's stored K_e)\n\n");
  fmt::print("| mesh | cells | nodes | stencil | row order | threads | bytes per node | ns per node | per node / hex or quad "
             "| stencil / hex or quad | GB/s | of triad | stored K_e: colours | bytes per node | ns per node "
             "| per node / hex or quad | other load |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<double> reference_ns(thread_counts.size()), reference_element_ns(thread_counts.size());
  double reference_stencil = 0.0;
  for (TypeMesh& m : meshes) {
    const bool reference = m.mesh.cells.type(0) == ElementType::hex8 || m.mesh.cells.type(0) == ElementType::quad4;
    StiffnessOperator k(m.mesh, element_lame(m.mesh, MaterialOptions{}), true);
    k.update(m.mesh.points);
    const ElementStorage stored(k.kernel(), m.mesh.points);
    const auto nodes = static_cast<double>(m.mesh.node_count());
    const double stencil = static_cast<double>(k.nonzero_blocks()) / nodes;
    if (reference) reference_stencil = stencil;
    const ProductModel model = product_model(k);
    const auto x = random_vector(k.size());
    std::vector<double> y(k.size());
    for (std::size_t t = 0; t < thread_counts.size(); ++t) {
      omp_set_num_threads(thread_counts[t]);
      const Timing apply = time_runs([&] { k.apply(x, y); }, 1, 5, 1.0);
      const Timing element = time_runs([&] { stored.apply(x, y); }, 1, 5, 1.0);
      const double ns = 1e9 * apply.seconds / nodes, element_ns = 1e9 * element.seconds / nodes;
      if (reference) {
        reference_ns[t] = ns;
        reference_element_ns[t] = element_ns;
      }
      const double gbs = model.bytes / apply.seconds * 1e-9;
      fmt::print("| {} | {} | {} | {:.1f} | {} | {} | {:.0f} | {:.1f} | {:.2f} | {:.2f} | {:.2f} | {:.0f} % | {} | {:.0f} | {:.1f} "
                 "| {:.2f} | {:.2f} |\n",
                 m.label, m.mesh.cell_count(), m.mesh.node_count(), stencil, k.renumbered() ? "RCM" : "own", thread_counts[t],
                 static_cast<double>(k.bytes()) / nodes, ns, ns / reference_ns[t], stencil / reference_stencil, gbs,
                 100.0 * gbs / memory_rate[t], k.kernel().coloring().colors(), stored.bytes() / nodes, element_ns,
                 element_ns / reference_element_ns[t], std::max(apply.others, element.others));
      std::fflush(stdout);
    }
  }
}

// ---------------------------------------------------------------------------------------
// 4. One Jacobi-PCG solve

/// K with the rows and columns of fixed dofs removed (their entries of y set to 0), as the
/// solver's constrained operator does for fixed and prescribed nodes.
class MaskedOperator final : public LinearOperator {
 public:
  MaskedOperator(const StiffnessOperator& k, std::span<const std::size_t> fixed) : k_(k), fixed_(fixed) {}
  std::size_t size() const override { return k_.size(); }
  void apply(std::span<const double> x, std::span<double> y) const override {
    k_.apply(x, y);
    for (std::size_t i : fixed_) y[i] = 0.0;
  }

 private:
  const StiffnessOperator& k_;
  std::span<const std::size_t> fixed_;
};

class JacobiOperator final : public LinearOperator {
 public:
  JacobiOperator(const StiffnessOperator& k, std::span<const std::size_t> fixed) : inverse_(k.size()) {
    k.diagonal(inverse_);
    for (double& d : inverse_) d = d > 0.0 ? 1.0 / d : 0.0;
    for (std::size_t i : fixed) inverse_[i] = 0.0;
  }
  std::size_t size() const override { return inverse_.size(); }
  void apply(std::span<const double> x, std::span<double> y) const override {
    const auto n = static_cast<std::ptrdiff_t>(x.size());
#pragma omp parallel for schedule(static) if (n >= hotmesh::mesh::kParallelVector)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      y[k] = inverse_[k] * x[k];
    }
  }

 private:
  std::vector<double> inverse_;
};

void pcg_section(int n, const std::vector<int>& thread_counts) {
  const auto line = uniform_line(0.0, 1.0, n);
  const auto zs = stretched_line(0.0, 1.0, n, 0.2 / n);  // first cell 1/5 of a uniform one
  const Mesh mesh = structured_hexes(line, line, zs);
  StiffnessOperator k(mesh, element_lame(mesh, MaterialOptions{}), true);
  k.update(mesh.points);

  // A bump on z = 0, every other boundary node fixed.
  std::vector<std::size_t> fixed;
  std::vector<double> u(k.size(), 0.0);
  for (const Patch& patch : mesh.patches) {
    for (NodeId node : patch.nodes) {
      const auto i = static_cast<std::size_t>(node);
      for (std::size_t c = 0; c < 3; ++c) fixed.push_back(3 * i + c);
      if (patch.name == "zmin") {
        const Vec3& p = mesh.points[i];
        u[3 * i + 2] = 0.05 * std::sin(std::numbers::pi * p[0]) * std::sin(std::numbers::pi * p[1]);
      }
    }
  }
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  std::vector<double> rhs(k.size());
  k.apply(u, rhs);
  for (double& v : rhs) v = -v;
  for (std::size_t i : fixed) rhs[i] = 0.0;

  const MaskedOperator a(k, fixed);
  fmt::print("\n### Jacobi-PCG solve\n\n");
  fmt::print("Hex block {0}^3 ({1} cells, {2} dofs, {3} fixed), stretched towards z = 0; tolerance 1e-3 "
             "(the solver's), from p = 0. Median of 3 solves.\n\n",
             n, mesh.cell_count(), k.size(), fixed.size());
  fmt::print("| threads | PCG iterations | solve s | ms per iteration | products (share of the solve) | "
             "Jacobi set-up ms (K's diagonal) | one product ms | other load |\n"
             "|---|---|---|---|---|---|---|---|\n");
  for (int t : thread_counts) {
    omp_set_num_threads(t);
    PcgResult result;
    std::vector<double> p(k.size());
    const Timing solve = time_runs(
        [&] {
          const JacobiOperator m(k, fixed);
          std::fill(p.begin(), p.end(), 0.0);
          result = pcg(a, m, rhs, p, {.relative_tolerance = 1e-3, .max_iterations = 5000, .record_history = false});
        },
        0, 3, 0.0);
    const double diagonal = time_runs([&] { const JacobiOperator m(k, fixed); }, 1, 5, 0.2).seconds;
    std::vector<double> y(k.size());
    const double product = time_runs([&] { k.apply(p, y); }, 1, 5, 0.5).seconds;
    const double products = (result.iterations + 1) * product;  // one for r0, one per iteration
    fmt::print("| {} | {}{} | {:.3f} | {:.2f} | {:.0f} % | {:.1f} | {:.2f} | {:.2f} |\n", t, result.iterations,
               result.converged ? "" : " (not converged)", solve.seconds,
               1e3 * solve.seconds / std::max(1, result.iterations), 100.0 * products / solve.seconds, 1e3 * diagonal,
               1e3 * product, solve.others);
  }
}

// ---------------------------------------------------------------------------------------
// 5. OpenMP team start-up against the thresholds

/// Cost of starting and joining a team of `threads` for a loop of `threads` trivial
/// iterations, timed region by region: on a loaded machine the mean is far above the median
/// (now and then a thread waits for a time slice).
struct ForkJoin {
  double median = 0.0;
  double mean = 0.0;
  double p999 = 0.0;  ///< 99.9th percentile
  double max = 0.0;
  double others = 0.0;  ///< cores busy with other processes meanwhile
};
ForkJoin fork_join_seconds(int threads) {
  omp_set_num_threads(threads);
  std::vector<double> sink(static_cast<std::size_t>(threads) * 8, 0.0);
  constexpr std::size_t kRegions = 20000;
  std::vector<double> times(kRegions);
  for (std::size_t r = 0; r < kRegions / 10; ++r) {  // warm-up: the team is created once
#pragma omp parallel for schedule(static)
    for (int i = 0; i < threads; ++i) sink[static_cast<std::size_t>(i) * 8] += 1.0;
  }
  const hotmesh::bench::LoadProbe load;
  for (std::size_t r = 0; r < kRegions; ++r) {
    const auto start = Clock::now();
#pragma omp parallel for schedule(static)
    for (int i = 0; i < threads; ++i) sink[static_cast<std::size_t>(i) * 8] += 1.0;
    times[r] = seconds_since(start);
  }
  ForkJoin f;
  f.others = load.others();
  for (double t : times) f.mean += t;
  f.mean /= static_cast<double>(kRegions);
  std::sort(times.begin(), times.end());
  f.median = times[kRegions / 2];
  f.p999 = times[kRegions * 999 / 1000];
  f.max = times.back();
  return f;
}

/// One-thread seconds per entry of deform::axpy on vectors that fit in L1/L2.
double axpy_seconds_per_entry() {
  omp_set_num_threads(1);
  const std::size_t n = static_cast<std::size_t>(hotmesh::mesh::kParallelVector);
  std::vector<double> x(n, 1.0), y(n, 0.0);
  constexpr int kCalls = 1000;
  const double seconds = time_runs(
      [&] {
        for (int r = 0; r < kCalls; ++r) axpy(1e-9, x, y);
      },
      1, 5, 0.1).seconds;
  return seconds / kCalls / static_cast<double>(n);
}

}  // namespace

int main(int argc, char** argv) {
  const Settings settings = parse_arguments(argc, argv);
  std::vector<int> thread_counts = {1};
  if (omp_get_max_threads() > 1) thread_counts.push_back(omp_get_max_threads());

  // 1. Memory bandwidth.
  fmt::print("### Memory bandwidth (STREAM triad)\n\n");
  fmt::print("| arrays | threads | GB/s | other load |\n|---|---|---|---|\n");
  struct Triad {
    std::string label;
    std::size_t entries;
  };
  const std::size_t big = static_cast<std::size_t>(settings.triad_mib) * 1024 * 1024 / 8;
  const std::vector<Triad> triads = {{"3 x 0.5 MiB (L2)", 65536},
                                     {"3 x 16 MiB (L3)", 16 * 131072},
                                     {fmt::format("3 x {} MiB (memory)", settings.triad_mib), big}};
  std::vector<double> memory_rate(thread_counts.size());
  for (const Triad& triad : triads) {
    for (std::size_t t = 0; t < thread_counts.size(); ++t) {
      omp_set_num_threads(thread_counts[t]);
      const Rate rate = triad_rate(triad.entries);
      if (triad.entries == big) memory_rate[t] = rate.gbs;
      fmt::print("| {} | {} | {:.1f} | {:.2f} |\n", triad.label, thread_counts[t], rate.gbs, rate.others);
      std::fflush(stdout);
    }
  }

  // 2-3. Element matrices and products, hex then quad meshes.
  std::vector<Row> rows;
  double product_ns_per_madd = 0.0;  // one thread, smallest hex mesh (for part 5)
  double update_hex_seconds = 0.0;   // one thread, per cell
  double update_quad_seconds = 0.0;
  auto run_mesh = [&](const std::string& label, const Mesh& mesh) {
    StiffnessOperator k(mesh, element_lame(mesh, MaterialOptions{}), true);
    k.update(mesh.points);  // touch the matrices once before timing
    const ProductModel model = product_model(k);
    for (int t : thread_counts) {
      Row row{label, mesh.cell_count(), k.size(), static_cast<double>(k.nonzero_blocks()) * k.dofs_per_node() / static_cast<double>(k.size()), t, model, measure_operator(k, mesh, t),
              static_cast<double>(k.bytes())};
      std::fprintf(stderr, "%s, %d threads: update %.3f s, apply %.4f s\n", label.c_str(), t,
                   row.rates.update.seconds, row.rates.apply.seconds);
      if (t == 1) {
        const double cells = static_cast<double>(mesh.cell_count());
        if (mesh.dimension == 3 && product_ns_per_madd == 0.0) {
          product_ns_per_madd = 1e9 * row.rates.apply.seconds / (0.5 * model.flops);
          update_hex_seconds = row.rates.update.seconds / cells;
        }
        if (mesh.dimension == 2 && update_quad_seconds == 0.0) update_quad_seconds = row.rates.update.seconds / cells;
      }
      rows.push_back(row);
    }
  };
  for (int n : settings.hex) run_mesh(fmt::format("hex {}^3", n), hex_block(n));
  for (int n : settings.quad) run_mesh(fmt::format("quad {}^2", n), quad_block(n));

  fmt::print("\n### Update: every K_e into the node blocks (StiffnessOperator::update)\n\n");
  fmt::print("| mesh | cells | MB held | threads | s | cells/s | other load |\n"
             "|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    const Timing& u = r.rates.update;
    fmt::print("| {} | {} | {:.0f} | {} | {:.3f} | {:.3g} | {:.2f} |\n", r.mesh, r.cells, r.bytes * 1e-6, r.threads,
               u.seconds, static_cast<double>(r.cells) / u.seconds, u.others);
  }

  fmt::print("\n### Product y = K x (StiffnessOperator::apply)\n\n");
  fmt::print("| mesh | cells | dofs | blocks per row | MB moved | threads | ms | cells/s | GFLOP/s | GB/s | of triad | "
             "other load |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    const double s = r.rates.apply.seconds;
    const double gbs = r.model.bytes / s * 1e-9;
    const auto t = static_cast<std::size_t>(std::find(thread_counts.begin(), thread_counts.end(), r.threads) -
                                            thread_counts.begin());
    fmt::print("| {} | {} | {} | {:.1f} | {:.0f} | {} | {:.2f} | {:.3g} | {:.2f} | {:.2f} | {:.0f} % | {:.2f} |\n",
               r.mesh, r.cells, r.dofs, r.stencil, r.model.bytes * 1e-6, r.threads, 1e3 * s,
               static_cast<double>(r.cells) / s, r.model.flops / s * 1e-9, gbs, 100.0 * gbs / memory_rate[t],
               r.rates.apply.others);
  }

  if (settings.types > 0) types_section(settings.types, thread_counts, memory_rate);

  // 4. A Jacobi-PCG solve.
  if (settings.pcg_cells > 0) pcg_section(settings.pcg_cells, thread_counts);

  // 5. Thresholds.
  if (thread_counts.size() > 1) {
    const int all = thread_counts.back();
    const ForkJoin fork = fork_join_seconds(all);
    const double axpy_entry = axpy_seconds_per_entry();
    fmt::print("\n### OpenMP thresholds (mesh/include/hotmesh/mesh/parallel_loops.hpp)\n\n");
    fmt::print("Starting and joining a team of {} threads, over 20000 regions (other load {:.2f}): median "
               "{:.2f} us, mean {:.2f} us, 99.9th percentile {:.1f} us, longest {:.0f} us. One-thread work each "
               "threshold keeps sequential, from the rates above, and its ratio to the mean start-up cost:\n\n",
               all, fork.others, 1e6 * fork.median, 1e6 * fork.mean, 1e6 * fork.p999, 1e6 * fork.max);
    fmt::print("| threshold | value | one-thread work at the threshold | work / mean team start-up |\n"
               "|---|---|---|---|\n");
    auto line = [&](const char* name, std::ptrdiff_t value, double seconds) {
      fmt::print("| {} | {} | {:.1f} us | {:.0f} |\n", name, value, 1e6 * seconds, seconds / fork.mean);
    };
    using namespace hotmesh::mesh;
    if (product_ns_per_madd > 0.0) {
      line("kParallelProduct (multiply-adds of a product)", kParallelProduct,
           static_cast<double>(kParallelProduct) * product_ns_per_madd * 1e-9);
    }
    if (update_hex_seconds > 0.0) {
      line("kParallelCells (hex8 K_e)", kParallelCells, static_cast<double>(kParallelCells) * update_hex_seconds);
    }
    if (update_quad_seconds > 0.0) {
      line("kParallelCells (quad4 K_e)", kParallelCells, static_cast<double>(kParallelCells) * update_quad_seconds);
    }
    line("kParallelVector (axpy entries)", kParallelVector, static_cast<double>(kParallelVector) * axpy_entry);
    line("kParallelNodes (nodal update, as 3 axpy entries a node)", kParallelNodes,
         3.0 * static_cast<double>(kParallelNodes) * axpy_entry);
  }
  return 0;
}
