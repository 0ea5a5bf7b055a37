// hotmesh geometry: the deformed face S + d as one B-spline surface (see deformed_face.hpp):
// exact by degree elevation and knot insertion (OpenCASCADE) for polynomial faces, interpolated
// on a refined tensor grid for rational ones.
#include "hotmesh/geometry/deformed_face.hpp"

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cad/occt_convert.hpp"
#include "reconstruct/grid_interpolation.hpp"

namespace hotmesh::geometry {

namespace {

/// Knots closer than this fraction of their direction's range are one knot.
constexpr double kSameKnot = 1e-12;
/// The interpolant of a rational face has at least this degree: the error of interpolation
/// falls as h^(p+1) with the span length h, so a quintic meets 1e-9 of a cylinder's radius
/// with some 16 spans per quarter turn where a cubic needs some 90.
constexpr int kMinInterpolationDegree = 5;

double pole_box_diagonal(const BSplineSurface& s) {
  Vec3 lo = s.poles().front(), hi = lo;
  for (const Vec3& p : s.poles()) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return distance(lo, hi);
}

/// The face as a polynomial B-spline if it is one: no weights, or all weights equal (then
/// sum N_i w P_i / sum N_i w = sum N_i P_i).
std::optional<BSplineSurface> polynomial_form(const BSplineSurface& s) {
  if (!s.is_rational()) return s;
  const auto [lo, hi] = std::minmax_element(s.weights().begin(), s.weights().end());
  if (*hi - *lo > 1e-14 * *hi) return std::nullopt;
  return BSplineSurface(s.u_degree(), s.v_degree(), s.u_knots(), s.v_knots(), s.poles());
}

/// Distinct knot values of a flat knot vector and their multiplicities.
struct KnotRuns {
  std::vector<double> values;
  std::vector<int> mults;
};

KnotRuns runs_of(const std::vector<double>& flat) {
  KnotRuns runs;
  for (const double k : flat) {
    if (!runs.values.empty() && k == runs.values.back()) {
      ++runs.mults.back();
    } else {
      runs.values.push_back(k);
      runs.mults.push_back(1);
    }
  }
  return runs;
}

/// A surface's interior knots in one direction and their multiplicities.
std::vector<std::pair<double, int>> interior_knots(const TColStd_Array1OfReal& knots,
                                                   const TColStd_Array1OfInteger& mults) {
  std::vector<std::pair<double, int>> interior;
  for (int i = knots.Lower() + 1; i < knots.Upper(); ++i) interior.emplace_back(knots(i), mults(i));
  return interior;
}

/// Gives the surface the knots in one direction (u or v), raising the multiplicity of a knot it
/// has (within `tolerance`) to the one given where that is larger.
void insert_knots(const Handle(Geom_BSplineSurface)& surface, bool along_u,
                  const std::vector<std::pair<double, int>>& knots, double tolerance) {
  if (knots.empty()) return;  // OpenCASCADE's arrays cannot be empty
  const int count = static_cast<int>(knots.size());
  TColStd_Array1OfReal values(1, count);
  TColStd_Array1OfInteger mults(1, count);
  for (int i = 1; i <= count; ++i) {
    values(i) = knots[static_cast<std::size_t>(i - 1)].first;
    mults(i) = knots[static_cast<std::size_t>(i - 1)].second;
  }
  if (along_u) {
    surface->InsertUKnots(values, mults, tolerance, false);
  } else {
    surface->InsertVKnots(values, mults, tolerance, false);
  }
}

/// The exact sum of a polynomial face and its field: both raised to the larger degree in each
/// direction, each given the other's knots (a knot both have gets the larger multiplicity),
/// then their poles added.
BSplineSurface exact_sum(const BSplineSurface& face, const BSplineSurface& field) {
  const Handle(Geom_BSplineSurface) s = detail::to_occt(face);
  const Handle(Geom_BSplineSurface) d = detail::to_occt(field);
  const int pu = std::max(face.u_degree(), field.u_degree());
  const int pv = std::max(face.v_degree(), field.v_degree());
  s->IncreaseDegree(pu, pv);
  d->IncreaseDegree(pu, pv);
  const double u_tolerance = kSameKnot * (face.u_last() - face.u_first());
  const double v_tolerance = kSameKnot * (face.v_last() - face.v_first());
  const auto su = interior_knots(s->UKnots(), s->UMultiplicities());
  const auto sv = interior_knots(s->VKnots(), s->VMultiplicities());
  insert_knots(s, true, interior_knots(d->UKnots(), d->UMultiplicities()), u_tolerance);
  insert_knots(s, false, interior_knots(d->VKnots(), d->VMultiplicities()), v_tolerance);
  insert_knots(d, true, su, u_tolerance);
  insert_knots(d, false, sv, v_tolerance);
  const BSplineSurface a = detail::to_surface(s);
  const BSplineSurface b = detail::to_surface(d);
  const auto same = [](const std::vector<double>& x, const std::vector<double>& y, double tolerance) {
    return x.size() == y.size() &&
           std::equal(x.begin(), x.end(), y.begin(), [&](double p, double q) { return std::abs(p - q) <= tolerance; });
  };
  if (!same(a.u_knots(), b.u_knots(), u_tolerance) || !same(a.v_knots(), b.v_knots(), v_tolerance)) {
    throw std::logic_error("deformed face: the face and its field did not reach common knots");
  }
  std::vector<Vec3> poles = a.poles();
  for (std::size_t i = 0; i < poles.size(); ++i) poles[i] = poles[i] + b.poles()[i];
  return BSplineSurface(pu, pv, a.u_knots(), a.v_knots(), std::move(poles));
}

/// Flat clamped knots of degree p on [first, last] holding the interior knots of `a` (degree
/// pa) and `b` (degree pb) with the continuity each has there: multiplicity m at degree pa is
/// continuity C^(pa - m), which needs multiplicity p - pa + m at degree p (at most p).
std::vector<double> joined_knots(const std::vector<double>& a, int pa, const std::vector<double>& b, int pb, int p) {
  const double first = a[static_cast<std::size_t>(pa)];
  const double last = a[a.size() - static_cast<std::size_t>(pa) - 1];
  std::vector<std::pair<double, int>> interior;
  for (const auto& [flat, degree] : {std::pair{&a, pa}, std::pair{&b, pb}}) {
    const KnotRuns runs = runs_of(*flat);
    for (std::size_t i = 1; i + 1 < runs.values.size(); ++i) {
      interior.emplace_back(runs.values[i], std::min(p, p - degree + runs.mults[i]));
    }
  }
  std::sort(interior.begin(), interior.end());
  const double tolerance = kSameKnot * (last - first);
  std::vector<double> knots(static_cast<std::size_t>(p) + 1, first);
  for (std::size_t i = 0; i < interior.size();) {
    int mult = interior[i].second;
    std::size_t j = i + 1;
    for (; j < interior.size() && interior[j].first - interior[i].first <= tolerance; ++j) {
      mult = std::max(mult, interior[j].second);
    }
    knots.insert(knots.end(), static_cast<std::size_t>(mult), interior[i].first);
    i = j;
  }
  knots.insert(knots.end(), static_cast<std::size_t>(p) + 1, last);
  return knots;
}

/// The knots with every span cut into `pieces` equal spans by simple knots.
std::vector<double> subdivided(const std::vector<double>& flat, std::size_t pieces) {
  const KnotRuns runs = runs_of(flat);
  std::vector<double> knots;
  for (std::size_t i = 0; i < runs.values.size(); ++i) {
    knots.insert(knots.end(), static_cast<std::size_t>(runs.mults[i]), runs.values[i]);
    if (i + 1 == runs.values.size()) break;
    for (std::size_t k = 1; k < pieces; ++k) {
      knots.push_back(runs.values[i] + (runs.values[i + 1] - runs.values[i]) * static_cast<double>(k) /
                                            static_cast<double>(pieces));
    }
  }
  return knots;
}

std::size_t span_count(const std::vector<double>& flat) { return runs_of(flat).values.size() - 1; }

/// Greville abscissae (t_{i+1} + ... + t_{i+p}) / p: one interpolation parameter per pole,
/// satisfying Schoenberg-Whitney for knots of multiplicity at most p inside.
std::vector<double> greville(const std::vector<double>& knots, int p) {
  const auto q = static_cast<std::size_t>(p);
  const std::size_t count = knots.size() - q - 1;
  std::vector<double> xi(count);
  if (count < 2) return xi;  // not a B-spline: at least p + 1 >= 2 poles
  for (std::size_t i = 0; i < count; ++i) {
    double sum = 0.0;
    for (std::size_t k = 1; k <= q; ++k) sum += knots[i + k];
    xi[i] = sum / static_cast<double>(p);
  }
  // The ends exactly (a sum of p equal knots over p may round).
  xi[0] = knots[0];
  xi[count - 1] = knots[knots.size() - 1];
  return xi;
}

std::vector<double> midpoints(const std::vector<double>& t) {
  std::vector<double> mid;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) mid.push_back(0.5 * (t[i] + t[i + 1]));
  return mid;
}

using Target = std::function<Vec3(double, double)>;

/// max |surface - target| over the grid us x vs.
double deviation(const BSplineSurface& surface, const Target& target, const std::vector<double>& us,
                 const std::vector<double>& vs) {
  double worst = 0.0;
  for (const double u : us) {
    for (const double v : vs) worst = std::max(worst, distance(surface.point(u, v), target(u, v)));
  }
  return worst;
}

// A rational face: S + d interpolated at the Greville abscissae of knots that hold S's and d's
// (with their continuity), spans halved in a direction while the deviation measured between
// grid lines across it exceeds the tolerance. Deviations are measured at the midpoints between
// Greville abscissae: across u at (u mid, v Greville), across v at (u Greville, v mid), and at
// the cells' centres, which refine both directions when neither alone exceeds the tolerance.
DeformedFace interpolated_sum(const BSplineSurface& face, const BSplineSurface& field, const DeformedFaceOptions& options) {
  const int pu = std::max({kMinInterpolationDegree, face.u_degree(), field.u_degree()});
  const int pv = std::max({kMinInterpolationDegree, face.v_degree(), field.v_degree()});
  const std::vector<double> u_base = joined_knots(face.u_knots(), face.u_degree(), field.u_knots(), field.u_degree(), pu);
  const std::vector<double> v_base = joined_knots(face.v_knots(), face.v_degree(), field.v_knots(), field.v_degree(), pv);
  const Target target = [&](double u, double v) { return face.point(u, v) + field.point(u, v); };
  const double tolerance = options.relative_tolerance * pole_box_diagonal(face);
  std::size_t u_pieces = 1, v_pieces = 1;
  for (;;) {
    std::vector<double> u_knots = subdivided(u_base, u_pieces);
    std::vector<double> v_knots = subdivided(v_base, v_pieces);
    const std::vector<double> us = greville(u_knots, pu);
    const std::vector<double> vs = greville(v_knots, pv);
    std::vector<Vec3> values;
    values.reserve(us.size() * vs.size());
    for (const double u : us) {
      for (const double v : vs) values.push_back(target(u, v));
    }
    std::vector<Vec3> poles = detail::interpolate_on_grid(u_knots, pu, us, v_knots, pv, vs, values);
    const bool u_room = 2 * span_count(u_knots) <= options.max_spans;
    const bool v_room = 2 * span_count(v_knots) <= options.max_spans;
    BSplineSurface surface(pu, pv, std::move(u_knots), std::move(v_knots), std::move(poles));
    const std::vector<double> u_mid = midpoints(us), v_mid = midpoints(vs);
    const double across_u = deviation(surface, target, u_mid, vs);
    const double across_v = deviation(surface, target, us, v_mid);
    const double centres = deviation(surface, target, u_mid, v_mid);
    bool refine_u = u_room && across_u > tolerance;
    bool refine_v = v_room && across_v > tolerance;
    if (!refine_u && !refine_v && centres > tolerance) {
      refine_u = u_room;
      refine_v = v_room;
    }
    if (!refine_u && !refine_v) {
      const std::size_t checks = u_mid.size() * vs.size() + us.size() * v_mid.size() + u_mid.size() * v_mid.size();
      return {std::move(surface), false, std::max({across_u, across_v, centres}), checks};
    }
    if (refine_u) u_pieces *= 2;
    if (refine_v) v_pieces *= 2;
  }
}

}  // namespace

DeformedFace deformed_face(const BSplineSurface& face, const BSplineSurface& displacement,
                           const DeformedFaceOptions& options) {
  const ParameterRectangle a = face.domain(), b = displacement.domain();
  if (a.u_first != b.u_first || a.u_last != b.u_last || a.v_first != b.v_first || a.v_last != b.v_last) {
    throw std::invalid_argument("deformed_face: the displacement's parameter rectangle differs from the face's");
  }
  if (!(options.relative_tolerance > 0.0) || !std::isfinite(options.relative_tolerance) || options.max_spans < 1) {
    throw std::invalid_argument("deformed_face: the tolerance must be positive and finite, max_spans at least 1");
  }
  const std::optional<BSplineSurface> polynomial = polynomial_form(face);
  if (!polynomial) return interpolated_sum(face, displacement, options);

  // Exact: the deviation is round-off, measured at the Greville abscissae of the result and
  // the midpoints between them.
  BSplineSurface sum = exact_sum(*polynomial, displacement);
  const Target target = [&](double u, double v) { return face.point(u, v) + displacement.point(u, v); };
  std::vector<double> us = greville(sum.u_knots(), sum.u_degree());
  std::vector<double> vs = greville(sum.v_knots(), sum.v_degree());
  const std::vector<double> u_mid = midpoints(us), v_mid = midpoints(vs);
  us.insert(us.end(), u_mid.begin(), u_mid.end());
  vs.insert(vs.end(), v_mid.begin(), v_mid.end());
  const double worst = deviation(sum, target, us, vs);
  return {std::move(sum), true, worst, us.size() * vs.size()};
}

}  // namespace hotmesh::geometry
