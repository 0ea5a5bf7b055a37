// hotmesh benchmark: projections per second onto deformed B-spline faces, the call the solver
// makes for every sliding node after every Newton step when it slides over general CAD surfaces
// (issue 23; section 4.2).
//
//   ninja -C build bench_surface_projection && build/bench/bench_surface_projection [points [deviation]]
//
// (deviation: SurfaceProjectorOptions::sampling_deviation, default 2e-3.)
// Four bicubic faces of 20 x 20 poles tile a wavy surface over [0, 2]^2 (2 x 2, sharing edges),
// each deformed by a bicubic displacement field of 8 x 8 poles: patches S + d. Points lie within
// 0.01 of the deformed faces (the faces span 2 x 2, waves of amplitude 0.1). Single thread:
//  - cold: no hint (global search + Newton);
//  - warm: each point moved by up to 0.002 per coordinate, as by a Newton step of the mesh
//    motion, with the previous projection as hint; checked by a global search that has to beat it
//    (the default), and unchecked (verify_warm_starts = false);
//  - trimmed: the same faces, each with a round hole of radius 0.3 (in its parameters, a loop of
//    1 024 segments that binds, as where the wall goes on into the hole's wall), cold and warm:
//    the points over a hole (about 28 %) are moved onto its rim;
//  - OpenCASCADE, for reference, on the undeformed faces (OpenCASCADE has no S + d surface):
//    GeomAPI_ProjectPointOnSurf on each face, nearest kept (cold), and ShapeAnalysis_Surface's
//    NextValueOfUV from the previous parameters (warm) on the known face.
// Prints a Markdown table; set-up time and agreement checks go to stderr.
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "hotmesh/geometry/surface_projector.hpp"
#include "machine_load.hpp"
#include "timing.hpp"

using namespace hotmesh::geometry;
using hotmesh::bench::Clock;
using hotmesh::bench::seconds_since;

namespace {

double height(double x, double y) { return 0.1 * std::sin(3.0 * x + 0.5) * std::cos(2.5 * y) + 0.05 * x * y; }

Vec3 displacement(double x, double y) {
  return {0.01 * std::sin(2.0 * y), -0.008 * std::cos(1.5 * x), 0.03 * std::sin(1.7 * x + 0.3) * std::sin(1.9 * y + 0.2)};
}

std::vector<double> clamped_uniform_knots(int poles, int degree) {
  std::vector<double> knots(static_cast<std::size_t>(degree) + 1, 0.0);
  const int spans = poles - degree;
  for (int i = 1; i < spans; ++i) knots.push_back(static_cast<double>(i) / spans);
  knots.insert(knots.end(), static_cast<std::size_t>(degree) + 1, 1.0);
  return knots;
}

/// A bicubic B-spline over [0, 1]^2 with n x n poles f(x0 + i/(n-1), y0 + j/(n-1)): tiles with
/// the same n and f share their edges exactly.
BSplineSurface tile(int n, double x0, double y0, const std::function<Vec3(double, double)>& f) {
  std::vector<Vec3> poles;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) poles.push_back(f(x0 + static_cast<double>(i) / (n - 1), y0 + static_cast<double>(j) / (n - 1)));
  }
  return BSplineSurface(3, 3, clamped_uniform_knots(n, 3), clamped_uniform_knots(n, 3), std::move(poles));
}

Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) {
  const auto n = static_cast<int>(s.u_count());
  TColgp_Array2OfPnt poles(1, n, 1, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Vec3& p = s.poles()[static_cast<std::size_t>(i * n + j)];
      poles(i + 1, j + 1) = gp_Pnt(p.x, p.y, p.z);
    }
  }
  const std::vector<double> b = s.u_breakpoints();
  TColStd_Array1OfReal knots(1, static_cast<int>(b.size()));
  TColStd_Array1OfInteger mults(1, static_cast<int>(b.size()));
  for (int i = 1; i <= knots.Upper(); ++i) {
    knots(i) = b[static_cast<std::size_t>(i - 1)];
    mults(i) = (i == 1 || i == knots.Upper()) ? 4 : 1;
  }
  return new Geom_BSplineSurface(poles, knots, knots, mults, mults, 3, 3);
}

/// Median rate of `repeats` runs of `run`, which projects `count` points.
template <class Run>
double rate(std::size_t count, int repeats, Run run) {
  std::vector<double> rates;
  for (int k = 0; k < repeats; ++k) {
    const auto start = Clock::now();
    run();
    rates.push_back(static_cast<double>(count) / seconds_since(start));
  }
  return hotmesh::bench::median(rates);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t count = argc > 1 ? static_cast<std::size_t>(std::atol(argv[1])) : 100000;
  std::vector<BSplineSurface> faces;
  std::vector<SurfacePatch> patches;
  for (int k = 0; k < 4; ++k) {
    const double x0 = k % 2, y0 = k / 2;
    faces.push_back(tile(20, x0, y0, [](double x, double y) { return Vec3{x, y, height(x, y)}; }));
    patches.push_back(displaced_patch(faces.back(), tile(8, x0, y0, displacement)));
  }
  SurfaceProjectorOptions options;
  if (argc > 2) options.sampling_deviation = std::atof(argv[2]);
  const auto setup_start = Clock::now();
  const SurfaceProjector projector(patches, options);
  const double setup = seconds_since(setup_start);
  SurfaceProjectorOptions unchecked_options = options;
  unchecked_options.verify_warm_starts = false;
  const SurfaceProjector unchecked(patches, unchecked_options);

  // Points within 0.01 of the deformed faces, and the same moved by a Newton step.
  std::mt19937 random(42);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vec3> points(count);
  std::vector<Vec3> moved(count);
  std::vector<int> face_of(count);
  for (std::size_t i = 0; i < count; ++i) {
    face_of[i] = static_cast<int>(i % 4);
    const SurfaceProjection on = projector.at({face_of[i], 0.5 + 0.5 * unit(random), 0.5 + 0.5 * unit(random)});
    points[i] = on.point + 0.01 * unit(random) * on.normal;
    moved[i] = points[i] + 0.002 * Vec3{unit(random), unit(random), unit(random)};
  }

  const hotmesh::bench::LoadProbe load;
  std::vector<SurfaceProjection> before(count);
  std::vector<SurfaceProjection> after(count);
  const double cold = rate(count, 3, [&] {
    for (std::size_t i = 0; i < count; ++i) before[i] = projector.project(points[i]);
  });
  double cold_iterations = 0.0;
  for (const SurfaceProjection& q : before) cold_iterations += q.iterations;
  const double warm = rate(count, 5, [&] {
    for (std::size_t i = 0; i < count; ++i) after[i] = projector.project(moved[i], before[i].where);
  });
  double warm_iterations = 0.0;
  std::size_t accepted = 0;
  for (const SurfaceProjection& q : after) {
    warm_iterations += q.iterations;
    accepted += q.from_hint ? 1 : 0;
  }
  std::vector<SurfaceProjection> fast(count);
  const double warm_unchecked = rate(count, 5, [&] {
    for (std::size_t i = 0; i < count; ++i) fast[i] = unchecked.project(moved[i], before[i].where);
  });
  double unchecked_iterations = 0.0;
  for (const SurfaceProjection& q : fast) unchecked_iterations += q.iterations;
  // The same faces with a hole each.
  std::vector<SurfacePatch> holed = patches;
  for (SurfacePatch& patch : holed) {
    std::vector<Vec2> circle;
    for (int k = 0; k <= 1024; ++k) {
      const double a = 2.0 * M_PI * k / 1024.0;
      circle.push_back({0.5 + 0.3 * std::cos(a), 0.5 + 0.3 * std::sin(a)});
    }
    patch.region = std::make_shared<const TrimRegion>(
        std::vector<TrimRegion::Curve>{{{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}, false}, {circle, true}}, patch.domain);
  }
  const SurfaceProjector trimmed(holed, options);
  std::vector<SurfaceProjection> trimmed_before(count), trimmed_after(count);
  const double trimmed_cold = rate(count, 3, [&] {
    for (std::size_t i = 0; i < count; ++i) trimmed_before[i] = trimmed.project(points[i]);
  });
  const double trimmed_warm = rate(count, 5, [&] {
    for (std::size_t i = 0; i < count; ++i) trimmed_after[i] = trimmed.project(moved[i], trimmed_before[i].where);
  });
  std::size_t on_rims = 0;
  double trimmed_iterations = 0.0;
  for (const SurfaceProjection& q : trimmed_after) {
    trimmed_iterations += q.iterations;
    on_rims += q.on_boundary ? 1 : 0;
  }
  const double others = load.others();

  // Warm starts must land where cold ones do.
  double worst = 0.0;
  double worst_unchecked = 0.0;
  for (std::size_t i = 0; i < count; i += 37) {
    const SurfaceProjection c = projector.project(moved[i]);
    worst = std::max(worst, std::abs(after[i].distance - c.distance));
    worst_unchecked = std::max(worst_unchecked, std::abs(fast[i].distance - c.distance));
  }

  // OpenCASCADE on the undeformed faces, on subsets (its cold projection is slow).
  const std::size_t occt_count = std::min<std::size_t>(count, 5000);
  const std::size_t occt_cold_count = std::min<std::size_t>(count, 500);
  std::vector<Handle(Geom_BSplineSurface)> occt_faces;
  std::vector<Handle(ShapeAnalysis_Surface)> analysis;
  for (const BSplineSurface& f : faces) {
    occt_faces.push_back(to_occt(f));
    analysis.push_back(new ShapeAnalysis_Surface(occt_faces.back()));
  }
  std::vector<gp_Pnt2d> uv(occt_count);
  const double occt_cold = rate(occt_cold_count, 1, [&] {
    for (std::size_t i = 0; i < occt_cold_count; ++i) {
      double best = 1e300;
      for (std::size_t k = 0; k < occt_faces.size(); ++k) {
        GeomAPI_ProjectPointOnSurf extrema(gp_Pnt(points[i].x, points[i].y, points[i].z), occt_faces[k]);
        if (extrema.NbPoints() > 0 && extrema.LowerDistance() < best) {
          best = extrema.LowerDistance();
          double u = 0.0, v = 0.0;
          extrema.LowerDistanceParameters(u, v);
          uv[i] = gp_Pnt2d(u, v);
        }
      }
    }
  });
  for (std::size_t i = 0; i < occt_count; ++i) uv[i] = gp_Pnt2d(before[i].where.u, before[i].where.v);
  const double occt_warm = rate(occt_count, 3, [&] {
    for (std::size_t i = 0; i < occt_count; ++i) {
      const auto& surface = analysis[static_cast<std::size_t>(face_of[i])];
      static_cast<void>(surface->NextValueOfUV(uv[i], gp_Pnt(moved[i].x, moved[i].y, moved[i].z), 1e-9));
    }
  });

  const auto n = static_cast<double>(count);
  std::printf("| mode | projections/s | mean Newton iterations | answers from the hint |\n|---|---|---|---|\n");
  std::printf("| cold (global search + Newton) | %.3g | %.1f | |\n", cold, cold_iterations / n);
  std::printf("| warm, checked (default) | %.3g | %.1f | %.1f %% |\n", warm, warm_iterations / n, 100.0 * static_cast<double>(accepted) / n);
  std::printf("| warm, unchecked | %.3g | %.1f | |\n", warm_unchecked, unchecked_iterations / n);
  std::printf("| trimmed (a hole in each face), cold | %.3g | | |\n", trimmed_cold);
  std::printf("| trimmed (a hole in each face), warm, checked | %.3g | %.1f | %.1f %% on a rim |\n", trimmed_warm,
              trimmed_iterations / n, 100.0 * static_cast<double>(on_rims) / n);
  std::printf("| OpenCASCADE GeomAPI_ProjectPointOnSurf, 4 faces (undeformed) | %.3g | | |\n", occt_cold);
  std::printf("| OpenCASCADE ShapeAnalysis_Surface::NextValueOfUV, warm (undeformed) | %.3g | | |\n", occt_warm);
  std::fprintf(stderr,
               "%zu points, 4 patches; set-up %.3f s, %zu sub-patches; largest |warm - cold| distance: checked %.2g, "
               "unchecked %.2g; other processes kept %.1f cores busy\n",
               count, setup, projector.sub_patch_count(), worst, worst_unchecked, others);
  return 0;
}
