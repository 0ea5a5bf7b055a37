// hotmesh geometry (internal): B-spline curves and surfaces between hotmesh and OpenCASCADE.
#include "cad/occt_convert.hpp"

#include <GeomConvert.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <vector>

namespace hotmesh::geometry::detail {

namespace {

std::vector<double> flat(const TColStd_Array1OfReal& knots, const TColStd_Array1OfInteger& mults) {
  std::vector<double> result;
  for (Standard_Integer i = knots.Lower(); i <= knots.Upper(); ++i) {
    result.insert(result.end(), static_cast<std::size_t>(mults(i)), knots(i));
  }
  return result;
}

/// Distinct knots and their multiplicities of a flat knot vector.
void unflatten(const std::vector<double>& flat_knots, TColStd_Array1OfReal& knots, TColStd_Array1OfInteger& mults) {
  std::vector<double> values;
  std::vector<int> counts;
  for (const double k : flat_knots) {
    if (!values.empty() && values.back() == k) {
      ++counts.back();
    } else {
      values.push_back(k);
      counts.push_back(1);
    }
  }
  knots.Resize(1, static_cast<Standard_Integer>(values.size()), false);
  mults.Resize(1, static_cast<Standard_Integer>(values.size()), false);
  for (std::size_t i = 0; i < values.size(); ++i) {
    knots(static_cast<Standard_Integer>(i) + 1) = values[i];
    mults(static_cast<Standard_Integer>(i) + 1) = counts[i];
  }
}

}  // namespace

BSplineCurve2d to_curve(const Handle(Geom2d_BSplineCurve)& input) {
  Handle(Geom2d_BSplineCurve) curve = input;
  if (curve->IsPeriodic()) {
    curve = Handle(Geom2d_BSplineCurve)::DownCast(input->Copy());
    curve->SetNotPeriodic();
  }
  // Floating ends (IGES allows knot vectors that do not open with degree + 1 equal knots): the
  // curve over its range, cut out with clamped ends.
  if (curve->Multiplicity(1) <= curve->Degree() || curve->Multiplicity(curve->NbKnots()) <= curve->Degree()) {
    if (curve == input) curve = Handle(Geom2d_BSplineCurve)::DownCast(input->Copy());
    curve->Segment(curve->FirstParameter(), curve->LastParameter());
  }
  std::vector<Vec2> poles;
  std::vector<double> weights;
  for (Standard_Integer i = 1; i <= curve->NbPoles(); ++i) {
    poles.push_back({curve->Pole(i).X(), curve->Pole(i).Y()});
    weights.push_back(curve->Weight(i));
  }
  if (!curve->IsRational()) weights.clear();
  return BSplineCurve2d(curve->Degree(), flat(curve->Knots(), curve->Multiplicities()), std::move(poles),
                        std::move(weights));
}

Handle(Geom2d_BSplineCurve) to_occt(const BSplineCurve2d& curve) {
  const auto n = static_cast<Standard_Integer>(curve.poles().size());
  TColgp_Array1OfPnt2d poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (Standard_Integer i = 1; i <= n; ++i) {
    const Vec2& p = curve.poles()[static_cast<std::size_t>(i - 1)];
    poles(i) = gp_Pnt2d(p.x, p.y);
    weights(i) = curve.is_rational() ? curve.weights()[static_cast<std::size_t>(i - 1)] : 1.0;
  }
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
  unflatten(curve.knots(), knots, mults);
  if (curve.is_rational()) return new Geom2d_BSplineCurve(poles, weights, knots, mults, curve.degree());
  return new Geom2d_BSplineCurve(poles, knots, mults, curve.degree());
}

Handle(Geom_BSplineCurve) to_bspline(const Handle(Geom_Curve)& curve, double first, double last) {
  Handle(Geom_BSplineCurve) result =
      GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(curve, first, last, true, false));
  if (result->IsPeriodic()) result->SetNotPeriodic();
  return result;
}

BSplineCurve2d to_plane_curve(const Handle(Geom_BSplineCurve)& curve, const std::function<Vec2(const Vec3&)>& to_plane) {
  std::vector<Vec2> poles;
  std::vector<double> weights;
  for (Standard_Integer i = 1; i <= curve->NbPoles(); ++i) {
    poles.push_back(to_plane(to_vec3(curve->Pole(i))));
    weights.push_back(curve->Weight(i));
  }
  if (!curve->IsRational()) weights.clear();
  std::vector<double> knots;
  for (Standard_Integer i = 1; i <= curve->NbKnots(); ++i) {
    knots.insert(knots.end(), static_cast<std::size_t>(curve->Multiplicity(i)), curve->Knot(i));
  }
  return BSplineCurve2d(curve->Degree(), std::move(knots), std::move(poles), std::move(weights));
}

Handle(Geom_BSplineCurve) to_occt_3d(const BSplineCurve2d& curve, const Vec3& origin, const Vec3& u, const Vec3& v) {
  const auto n = static_cast<Standard_Integer>(curve.poles().size());
  TColgp_Array1OfPnt poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (Standard_Integer i = 1; i <= n; ++i) {
    const Vec2& p = curve.poles()[static_cast<std::size_t>(i - 1)];
    poles(i) = to_pnt(origin + p.x * u + p.y * v);
    weights(i) = curve.is_rational() ? curve.weights()[static_cast<std::size_t>(i - 1)] : 1.0;
  }
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
  unflatten(curve.knots(), knots, mults);
  if (curve.is_rational()) return new Geom_BSplineCurve(poles, weights, knots, mults, curve.degree());
  return new Geom_BSplineCurve(poles, knots, mults, curve.degree());
}

BSplineSurface to_surface(const Handle(Geom_BSplineSurface)& input) {
  Handle(Geom_BSplineSurface) surface = input;
  if (surface->IsUPeriodic() || surface->IsVPeriodic()) {
    surface = Handle(Geom_BSplineSurface)::DownCast(input->Copy());
    if (surface->IsUPeriodic()) surface->SetUNotPeriodic();
    if (surface->IsVPeriodic()) surface->SetVNotPeriodic();
  }
  // Floating ends (IGES 128 allows knot vectors that do not open with degree + 1 equal knots;
  // I-DEAS writes them): the surface over its range, cut out with clamped ends.
  const bool u_floating = surface->UMultiplicity(1) <= surface->UDegree() ||
                          surface->UMultiplicity(surface->NbUKnots()) <= surface->UDegree();
  const bool v_floating = surface->VMultiplicity(1) <= surface->VDegree() ||
                          surface->VMultiplicity(surface->NbVKnots()) <= surface->VDegree();
  if (u_floating || v_floating) {
    if (surface == input) surface = Handle(Geom_BSplineSurface)::DownCast(input->Copy());
    double u0, u1, v0, v1;
    surface->Bounds(u0, u1, v0, v1);
    surface->Segment(u0, u1, v0, v1);
  }
  std::vector<Vec3> poles;
  std::vector<double> weights;
  for (Standard_Integer i = 1; i <= surface->NbUPoles(); ++i) {
    for (Standard_Integer j = 1; j <= surface->NbVPoles(); ++j) {
      poles.push_back(to_vec3(surface->Pole(i, j)));
      weights.push_back(surface->Weight(i, j));
    }
  }
  if (!surface->IsURational() && !surface->IsVRational()) weights.clear();
  return BSplineSurface(surface->UDegree(), surface->VDegree(), flat(surface->UKnots(), surface->UMultiplicities()),
                        flat(surface->VKnots(), surface->VMultiplicities()), std::move(poles), std::move(weights));
}

Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& surface) {
  const auto nu = static_cast<Standard_Integer>(surface.u_count());
  const auto nv = static_cast<Standard_Integer>(surface.v_count());
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (Standard_Integer i = 1; i <= nu; ++i) {
    for (Standard_Integer j = 1; j <= nv; ++j) {
      const auto k = static_cast<std::size_t>((i - 1) * nv + (j - 1));
      poles(i, j) = to_pnt(surface.poles()[k]);
      weights(i, j) = surface.is_rational() ? surface.weights()[k] : 1.0;
    }
  }
  TColStd_Array1OfReal u_knots;
  TColStd_Array1OfInteger u_mults;
  TColStd_Array1OfReal v_knots;
  TColStd_Array1OfInteger v_mults;
  unflatten(surface.u_knots(), u_knots, u_mults);
  unflatten(surface.v_knots(), v_knots, v_mults);
  if (surface.is_rational()) {
    return new Geom_BSplineSurface(poles, weights, u_knots, v_knots, u_mults, v_mults, surface.u_degree(),
                                   surface.v_degree());
  }
  return new Geom_BSplineSurface(poles, u_knots, v_knots, u_mults, v_mults, surface.u_degree(), surface.v_degree());
}

}  // namespace hotmesh::geometry::detail
