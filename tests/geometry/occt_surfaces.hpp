// hotmesh tests: B-spline surfaces built by OpenCASCADE (planes, cylinders, spheres converted to
// rational B-splines, a wavy free-form patch) and copied into hotmesh's BSplineSurface, to test
// surface derivatives and projection against OpenCASCADE and against analytic answers.
// Header-only: test_geometry links OpenCASCADE (hotmesh_occt); the library's own converter is
// internal to hotmesh_geometry.
#pragma once

#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Ax3.hxx>

#include <cmath>
#include <numbers>
#include <vector>

#include "hotmesh/geometry/bspline_surface.hpp"

namespace hotmesh::geometry::test {

inline std::vector<double> flat_knots(const TColStd_Array1OfReal& knots, const TColStd_Array1OfInteger& mults) {
  std::vector<double> flat;
  for (int i = knots.Lower(); i <= knots.Upper(); ++i) flat.insert(flat.end(), static_cast<std::size_t>(mults(i)), knots(i));
  return flat;
}

/// OpenCASCADE's (non-periodic) B-spline surface as hotmesh's: poles u-major, weights if rational.
inline BSplineSurface from_occt(const Handle(Geom_BSplineSurface)& input) {
  Handle(Geom_BSplineSurface) s = Handle(Geom_BSplineSurface)::DownCast(input->Copy());
  if (s->IsUPeriodic()) s->SetUNotPeriodic();
  if (s->IsVPeriodic()) s->SetVNotPeriodic();
  std::vector<Vec3> poles;
  std::vector<double> weights;
  for (int i = 1; i <= s->NbUPoles(); ++i) {
    for (int j = 1; j <= s->NbVPoles(); ++j) {
      const gp_Pnt p = s->Pole(i, j);
      poles.push_back({p.X(), p.Y(), p.Z()});
      weights.push_back(s->Weight(i, j));
    }
  }
  if (!s->IsURational() && !s->IsVRational()) weights.clear();
  return BSplineSurface(s->UDegree(), s->VDegree(), flat_knots(s->UKnots(), s->UMultiplicities()),
                        flat_knots(s->VKnots(), s->VMultiplicities()), std::move(poles), std::move(weights));
}

/// The B-spline form of an analytic surface trimmed to [u0, u1] x [v0, v1].
inline Handle(Geom_BSplineSurface) trimmed_bspline(const Handle(Geom_Surface)& surface, double u0, double u1,
                                                  double v0, double v1) {
  const Handle(Geom_RectangularTrimmedSurface) trimmed = new Geom_RectangularTrimmedSurface(surface, u0, u1, v0, v1);
  return GeomConvert::SurfaceToBSplineSurface(trimmed);
}

/// Frame of the analytic test surfaces: origin (0.3, -0.2, 0.1), axis z' tilted away from z.
inline gp_Ax3 test_frame() {
  return gp_Ax3(gp_Pnt(0.3, -0.2, 0.1), gp_Dir(0.2, -0.3, 1.0), gp_Dir(1.0, 0.0, -0.2));
}

/// Cylinder of radius 2 about the test frame's axis, angles [0.2, 2.8], height [-1, 3]: a
/// rational B-spline (quadratic arcs around, linear along).
inline Handle(Geom_BSplineSurface) occt_cylinder() {
  return trimmed_bspline(new Geom_CylindricalSurface(test_frame(), 2.0), 0.2, 2.8, -1.0, 3.0);
}

/// Sphere of radius 1.5 centred at the test frame's origin, longitude [0, 4.5], latitude from
/// pole to pole (both v edges collapse to points).
inline Handle(Geom_BSplineSurface) occt_sphere() {
  return trimmed_bspline(new Geom_SphericalSurface(test_frame(), 1.5), 0.0, 4.5, -std::numbers::pi / 2, std::numbers::pi / 2);
}

/// The plane through the test frame, [-1, 2] x [-0.5, 1.5] in its (x', y').
inline Handle(Geom_BSplineSurface) occt_plane() {
  return trimmed_bspline(new Geom_Plane(test_frame()), -1.0, 2.0, -0.5, 1.5);
}

/// A bicubic polynomial patch over [0, 2] x [1, 2] with non-uniform knots and wavy heights.
inline Handle(Geom_BSplineSurface) occt_wavy() {
  const int nu = 9;
  const int nv = 7;
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i) {
    for (int j = 1; j <= nv; ++j) {
      const double x = 2.0 * (i - 1) / (nu - 1);
      const double y = 1.0 + (j - 1.0) / (nv - 1);
      poles(i, j) = gp_Pnt(x + 0.05 * std::sin(3.0 * j), y, 0.3 * std::sin(2.1 * i) * std::cos(1.7 * j));
    }
  }
  TColStd_Array1OfReal u_knots(1, 7);
  TColStd_Array1OfInteger u_mults(1, 7);
  const double uk[] = {0.0, 0.2, 0.5, 0.7, 1.1, 1.4, 2.0};
  for (int i = 1; i <= 7; ++i) u_knots(i) = uk[i - 1], u_mults(i) = (i == 1 || i == 7) ? 4 : 1;
  TColStd_Array1OfReal v_knots(1, 5);
  TColStd_Array1OfInteger v_mults(1, 5);
  const double vk[] = {1.0, 1.3, 1.45, 1.8, 2.0};
  for (int i = 1; i <= 5; ++i) v_knots(i) = vk[i - 1], v_mults(i) = (i == 1 || i == 5) ? 4 : 1;
  return new Geom_BSplineSurface(poles, u_knots, v_knots, u_mults, v_mults, 3, 3);
}

/// The wavy patch made rational: the same poles and knots with weights in [0.6, 1.6].
inline Handle(Geom_BSplineSurface) occt_wavy_rational() {
  Handle(Geom_BSplineSurface) s = occt_wavy();
  for (int i = 1; i <= s->NbUPoles(); ++i) {
    for (int j = 1; j <= s->NbVPoles(); ++j) s->SetWeight(i, j, 1.1 + 0.5 * std::sin(1.3 * i + 0.7 * j));
  }
  return s;
}

}  // namespace hotmesh::geometry::test
