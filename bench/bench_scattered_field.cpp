// hotmesh benchmark: geometry::ScatteredField, the partition-of-unity RBF interpolation that
// gives a prescribed 3D wall without CAD its deflections from an x, y, z FEM table (issue 23,
// item 0). Set-up time (octree of patches and their dense solves) and evaluations per second
// for FEM tables of 10^4 and 10^5 random points on a wavy surface, and the largest error off
// the points for a smooth field (relative to its largest value). The evaluations are at the
// 2 * 10^5 nodes of a structured CFD wall grid: in mesh order (neighbours one after another,
// as a mesh numbers its wall), serial and under OpenMP as the callers' loops run it, and
// shuffled (each evaluation in another part of the table: cache misses). Prints a Markdown table.
//
//   ninja -C build bench_scattered_field && build/bench/bench_scattered_field [POINTS,...]
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hotmesh/geometry/scattered_field.hpp"
#include "machine_load.hpp"
#include "timing.hpp"

namespace {

using hotmesh::bench::Clock;
using hotmesh::bench::median;
using hotmesh::bench::seconds_since;
using hotmesh::geometry::ScatteredField;
using hotmesh::geometry::Vec3;

/// A wavy wall, 1 by 0.6 with bumps of 0.05.
Vec3 wall(double u, double v) { return {u, 0.6 * v, 0.05 * std::sin(12.0 * u) * std::cos(9.0 * v)}; }

Vec3 deflection(const Vec3& x) {
  return {1e-3 * std::sin(3.0 * x.x + x.y), 2e-3 * x.x * std::cos(4.0 * x.y), 1e-3 * std::exp(x.x) * (1.0 + x.z)};
}

std::vector<Vec3> random_wall_points(std::size_t count) {
  std::mt19937 random(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points(count);
  for (Vec3& p : points) {
    const double u = unit(random);
    p = wall(u, unit(random));
  }
  return points;
}

/// Nodes of a k by k structured grid on the wall, row by row.
std::vector<Vec3> wall_grid(int k) {
  std::vector<Vec3> nodes;
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) nodes.push_back(wall((i + 0.5) / k, (j + 0.5) / k));
  }
  return nodes;
}

/// Evaluations per second of `field` at `nodes` (median of 3 runs), the loop under OpenMP if
/// `threads`.
double rate(const ScatteredField& field, const std::vector<Vec3>& nodes, std::vector<Vec3>& result, bool threads) {
  const auto n = static_cast<std::ptrdiff_t>(nodes.size());
  std::vector<double> rates;
  for (int k = 0; k < 3; ++k) {
    const Clock::time_point start = Clock::now();
#pragma omp parallel for schedule(static) if (threads)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>(i);
      result[j] = field(nodes[j]);
    }
    rates.push_back(static_cast<double>(nodes.size()) / seconds_since(start));
  }
  return median(rates);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes{10000, 100000};
  if (argc > 1) {
    sizes.clear();
    std::istringstream list(argv[1]);
    for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::stoul(item));
  }
  const std::vector<Vec3> nodes = wall_grid(450);  // CFD wall nodes
  std::vector<Vec3> shuffled = nodes;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(3));
  std::vector<Vec3> result(nodes.size());

  std::printf("| FEM points | patches (mean / largest points) | set-up s | evaluations/s, mesh order | "
              "same, %d threads | same, shuffled | max error off the points | other load (cores) |\n",
              omp_get_max_threads());
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const std::size_t size : sizes) {
    const hotmesh::bench::LoadProbe load;
    const std::vector<Vec3> points = random_wall_points(size);
    std::vector<Vec3> values;
    for (const Vec3& p : points) values.push_back(deflection(p));

    std::vector<double> setup;
    for (int k = 0; k < 3; ++k) {
      const Clock::time_point start = Clock::now();
      const ScatteredField field(points, values);
      setup.push_back(seconds_since(start));
    }
    const ScatteredField field(points, values);

    const double shuffled_rate = rate(field, shuffled, result, false);
    const double parallel = rate(field, nodes, result, true);
    const double serial = rate(field, nodes, result, false);
    double error = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      error = std::max(error, distance(result[i], deflection(nodes[i])));
      largest = std::max(largest, norm(deflection(nodes[i])));
    }
    const auto& report = field.report();
    std::printf("| %zu | %zu (%.0f / %zu) | %.3f | %.3g | %.3g | %.3g | %.2g | %.2f |\n", size, report.patches,
                report.mean_patch, report.largest_patch, median(setup), serial, parallel, shuffled_rate,
                error / largest, load.others());
  }
  return 0;
}
