// hotmesh benchmark: projections per second onto a deflected surface of revolution, the call
// the solver makes for every sliding node after every Newton step (section 4.2, Fig. 4).
//
//   ninja -C build bench_projection && build/bench/bench_projection [points]
//
// The boundary is a wavy cubic meridional curve (60 spans) deflected through 400 FEM nodes
// (eq. 21, q = 1 and q = 3), projected at the half-way stage lambda = 0.5. Points lie near the
// surface at random angles. "cold" projects without a hint (global search + Newton); "warm"
// projects points moved by 0.1 % of the boundary's size from a previous projection, with its
// parameter as hint, as the solver does between Newton steps; "warm, N threads" runs the warm
// loop under OpenMP. Prints a Markdown table.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "hotmesh/core/clock.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/interpolation.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

using namespace hotmesh::geometry;
using hotmesh::seconds_since;

namespace {

/// A wavy profile in (r, z): 63 poles, cubic, uniform knots.
BSplineCurve2d profile() {
  std::vector<Vec2> poles;
  for (int i = 0; i < 63; ++i) poles.push_back({0.5 + 0.05 * std::sin(0.7 * i), 0.02 * i});
  std::vector<double> knots(4, 0.0);
  for (int i = 1; i < 60; ++i) knots.push_back(i / 60.0);
  knots.insert(knots.end(), 4, 1.0);
  return BSplineCurve2d(3, std::move(knots), std::move(poles));
}

CurveSamples fem_nodes(const BSplineCurve2d& r) {
  CurveSamples s;
  for (int j = 0; j < 400; ++j) {
    const double t = j / 399.0;
    s.points.push_back(r.point(t));
    s.deflections.push_back({0.01 * std::sin(9.0 * t), 0.005 * std::cos(5.0 * t)});
  }
  return s;
}

/// Median rate of `repeats` runs of `run` (which projects `count` points).
template <class Run>
double rate(std::size_t count, int repeats, Run run) {
  std::vector<double> rates;
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    run();
    rates.push_back(static_cast<double>(count) / seconds_since(start));
  }
  std::sort(rates.begin(), rates.end());
  return rates[rates.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t count = argc > 1 ? static_cast<std::size_t>(std::atol(argv[1])) : 200000;
  const Axis axis({0, 0, 0}, {0, 0, 1});
  const BSplineCurve2d r = profile();
  std::printf("| degree q | mode | projections/s | mean Newton iterations |\n|---|---|---|---|\n");
  for (const int q : {1, 3}) {
    ReconstructionOptions options;
    options.degree = q;
    const RevolvedShape shape(reconstruct(r, fem_nodes(r), options).curve, axis);

    std::mt19937 random(42);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<Vec3> points(count);
    std::vector<Vec3> moved(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double t = uniform(random);
      const Vec2 q2 = shape.projector().curve().point(t, 0.5);
      const double theta = 6.283185307179586 * uniform(random);
      points[i] = axis.to_cartesian({q2.x + 0.01 * (uniform(random) - 0.5), theta, q2.y + 0.01 * (uniform(random) - 0.5)});
      moved[i] = points[i] + Vec3{0.0012 * (uniform(random) - 0.5), 0.0012 * (uniform(random) - 0.5),
                                  0.0012 * (uniform(random) - 0.5)};
    }
    std::vector<ShapeParameter> hints(count);
    std::vector<ShapePoint> result(count);
    const double cold = rate(count, 3, [&] {
      for (std::size_t i = 0; i < count; ++i) result[i] = shape.project(points[i], 0.5);
    });
    for (std::size_t i = 0; i < count; ++i) hints[i] = result[i].parameter;
    const double warm = rate(count, 5, [&] {
      for (std::size_t i = 0; i < count; ++i) result[i] = shape.project(moved[i], 0.5, hints[i]);
    });
    const auto n = static_cast<std::ptrdiff_t>(count);
    const double parallel = rate(count, 5, [&] {
#pragma omp parallel for schedule(static)
      for (std::ptrdiff_t i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        result[k] = shape.project(moved[k], 0.5, hints[k]);
      }
    });
    // Warm starts must land where cold ones do.
    double worst = 0.0;
    double iterations = 0.0;
    for (std::size_t i = 0; i < count; i += 97) {
      const Cylindrical c = axis.to_cylindrical(moved[i]);
      const CurveProjection w = shape.projector().project({c.r, c.z}, 0.5, hints[i].t);
      const CurveProjection g = shape.projector().project({c.r, c.z}, 0.5);
      worst = std::max(worst, std::abs(w.distance - g.distance));
      iterations += w.iterations;
    }
    iterations /= static_cast<double>((count + 96) / 97);
    std::printf("| %d | cold (global search + Newton) | %.3g | |\n", q, cold);
    std::printf("| %d | warm (hint, point moved 0.1 %%) | %.3g | %.2f |\n", q, warm, iterations);
    std::printf("| %d | warm, %d threads (OpenMP) | %.3g | |\n", q, omp_get_max_threads(), parallel);
    std::fprintf(stderr, "q = %d: %zu samples in the search tree; largest |warm - cold| distance %.2g\n", q,
                 shape.projector().sample_count(), worst);
  }
  return 0;
}
