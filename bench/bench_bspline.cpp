// hotmesh benchmark: evaluating a planar B-spline curve, hotmesh's own de Boor evaluation
// (geometry::BSplineCurve2d, the inner loop of every projection onto a deflected curve) against
// OpenCASCADE's (Geom2d_BSplineCurve::D2, and BSplCLib::D2 on plain arrays, what it calls),
// point and first two derivatives at random parameters. It answers whether hotmesh should
// evaluate its curves with OpenCASCADE (issue: libraries where a well-kept one does the job):
// the time per evaluation, and how far the two results differ (relative to the curve's size).
//
//   ninja -C build bench_bspline && build/bench/bench_bspline
#include <Geom2d_BSplineCurve.hxx>
#include <BSplCLib.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec2d.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/geometry/bspline_curve.hpp"
#include "machine_load.hpp"
#include "timing.hpp"

namespace {

using hotmesh::bench::Clock;
using hotmesh::bench::median;
using hotmesh::bench::seconds_since;
using hotmesh::geometry::BSplineCurve2d;
using hotmesh::geometry::Vec2;

/// A wavy clamped curve of `poles` poles with uniform interior knots (multiplicity 1).
BSplineCurve2d wavy_curve(int degree, int poles) {
  std::vector<double> knots;
  const int interior = poles - degree - 1;
  for (int i = 0; i <= degree; ++i) knots.push_back(0.0);
  for (int i = 1; i <= interior; ++i) knots.push_back(static_cast<double>(i) / (interior + 1));
  for (int i = 0; i <= degree; ++i) knots.push_back(1.0);
  std::vector<Vec2> points;
  for (int i = 0; i < poles; ++i) {
    const double x = static_cast<double>(i) / (poles - 1);
    points.push_back({x, 0.05 * std::sin(17.0 * x) + 0.01 * std::cos(91.0 * x)});
  }
  return BSplineCurve2d(degree, std::move(knots), std::move(points));
}

struct Row {
  int degree = 0, poles = 0;
  double hotmesh_ns = 0, geom2d_ns = 0, bsplclib_ns = 0;
  double max_difference = 0;  ///< largest |difference| of point, first and second derivative, relative to each's largest size
};

template <class Evaluate>
double nanoseconds_per_call(const std::vector<double>& ts, Evaluate&& evaluate) {
  std::vector<double> runs;
  double sink = 0.0;
  for (int run = 0; run < 5; ++run) {
    const auto start = Clock::now();
    for (const double t : ts) sink += evaluate(t);
    runs.push_back(1e9 * seconds_since(start) / static_cast<double>(ts.size()));
  }
  if (sink == 42.0) std::puts("");  // keeps the calls
  return median(runs);
}

Row measure(int degree, int poles, int evaluations) {
  const BSplineCurve2d ours = wavy_curve(degree, poles);
  // The same curve for OpenCASCADE: distinct knots with multiplicities.
  std::vector<double> distinct;
  std::vector<int> multiplicity;
  for (const double k : ours.knots()) {
    if (!distinct.empty() && k == distinct.back()) {
      ++multiplicity.back();
    } else {
      distinct.push_back(k);
      multiplicity.push_back(1);
    }
  }
  TColgp_Array1OfPnt2d occt_poles(1, poles);
  for (int i = 0; i < poles; ++i) occt_poles(i + 1) = gp_Pnt2d(ours.poles()[static_cast<std::size_t>(i)].x, ours.poles()[static_cast<std::size_t>(i)].y);
  TColStd_Array1OfReal occt_knots(1, static_cast<int>(distinct.size()));
  TColStd_Array1OfInteger occt_mults(1, static_cast<int>(distinct.size()));
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    occt_knots(static_cast<int>(i) + 1) = distinct[i];
    occt_mults(static_cast<int>(i) + 1) = multiplicity[i];
  }
  const Geom2d_BSplineCurve geom2d(occt_poles, occt_knots, occt_mults, degree);

  std::mt19937 random(11);
  std::uniform_real_distribution<double> parameter(0.0, 1.0);
  std::vector<double> ts(static_cast<std::size_t>(evaluations));
  for (double& t : ts) t = parameter(random);

  Row row{degree, poles, 0, 0, 0, 0};
  row.hotmesh_ns = nanoseconds_per_call(ts, [&](double t) {
    const auto d = ours.derivatives(t);
    return d.point.x + d.first.y + d.second.x;
  });
  row.geom2d_ns = nanoseconds_per_call(ts, [&](double t) {
    gp_Pnt2d p;
    gp_Vec2d v1, v2;
    geom2d.D2(t, p, v1, v2);
    return p.X() + v1.Y() + v2.X();
  });
  row.bsplclib_ns = nanoseconds_per_call(ts, [&](double t) {
    gp_Pnt2d p;
    gp_Vec2d v1, v2;
    BSplCLib::D2(t, 0, degree, false, occt_poles, nullptr, occt_knots, &occt_mults, p, v1, v2);
    return p.X() + v1.Y() + v2.X();
  });
  std::array<double, 3> largest{}, difference{};
  for (const double t : ts) {
    const auto d = ours.derivatives(t);
    gp_Pnt2d p;
    gp_Vec2d v1, v2;
    geom2d.D2(t, p, v1, v2);
    const std::array<Vec2, 3> a{d.point, d.first, d.second};
    const std::array<Vec2, 3> b{Vec2{p.X(), p.Y()}, Vec2{v1.X(), v1.Y()}, Vec2{v2.X(), v2.Y()}};
    for (std::size_t k = 0; k < 3; ++k) {
      largest[k] = std::max(largest[k], std::hypot(b[k].x, b[k].y));
      difference[k] = std::max(difference[k], std::hypot(a[k].x - b[k].x, a[k].y - b[k].y));
    }
  }
  for (std::size_t k = 0; k < 3; ++k) row.max_difference = std::max(row.max_difference, difference[k] / largest[k]);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string_view(argv[1]) == "--quick";
  const int evaluations = quick ? 20'000 : 400'000;
  const hotmesh::bench::LoadProbe load;
  fmt::print("### B-spline curve: point and two derivatives (hotmesh vs OpenCASCADE)\n\n");
  fmt::print("| degree | poles | hotmesh ns | Geom2d_BSplineCurve::D2 ns | BSplCLib::D2 ns | largest relative difference |\n");
  fmt::print("|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [degree, poles] : std::vector<std::pair<int, int>>{{1, 200}, {3, 40}, {3, 400}, {5, 400}}) {
    const Row r = measure(degree, poles, evaluations);
    fmt::print("| {} | {} | {:.0f} | {:.0f} | {:.0f} | {:.1e} |\n", r.degree, r.poles, r.hotmesh_ns, r.geom2d_ns, r.bsplclib_ns,
               r.max_difference);
  }
  fmt::print("\nOne thread, {} random parameters per row, median of 5 runs; other load {:.2f} cores.\n", evaluations,
             load.others());
  return 0;
}
