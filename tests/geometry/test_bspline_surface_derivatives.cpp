// Tests of BSplineSurface::derivatives: the point and first and second partial derivatives of
// polynomial and rational surfaces agree with finite differences and with OpenCASCADE's
// Geom_BSplineSurface::D2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hotmesh/geometry/bspline_surface.hpp"
#include "occt_surfaces.hpp"

namespace hotmesh::geometry {
namespace {

double max_norm(std::initializer_list<Vec3> vs) {
  double m = 0.0;
  for (const Vec3& v : vs) m = std::max(m, norm(v));
  return m;
}

/// Central differences of the point give S_u and S_v; of the analytic first derivatives, the
/// second ones (S_uv both ways). h = 1e-5 leaves errors of order h^2 |S'''|.
void expect_finite_differences(const BSplineSurface& s, double u, double v) {
  const double h = 1e-5;
  const SurfaceDerivatives d = s.derivatives(u, v);
  const SurfaceDerivatives up = s.derivatives(u + h, v), um = s.derivatives(u - h, v);
  const SurfaceDerivatives vp = s.derivatives(u, v + h), vm = s.derivatives(u, v - h);
  const double scale = max_norm({d.du, d.dv, d.duu, d.duv, d.dvv});
  const double tolerance = 1e-7 * scale;
  const auto near = [&](const Vec3& a, const Vec3& b, const char* what) {
    EXPECT_LE(distance(a, b), tolerance) << what << " at (" << u << ", " << v << ")";
  };
  near(d.point, s.point(u, v), "point");
  near(d.du, (up.point - um.point) / (2 * h), "S_u");
  near(d.dv, (vp.point - vm.point) / (2 * h), "S_v");
  near(d.duu, (up.du - um.du) / (2 * h), "S_uu");
  near(d.duv, (vp.du - vm.du) / (2 * h), "S_uv from S_u");
  near(d.duv, (up.dv - um.dv) / (2 * h), "S_uv from S_v");
  near(d.dvv, (vp.dv - vm.dv) / (2 * h), "S_vv");
}

/// Parameters inside the knot spans (differences across a knot see the jump of S_uu).
std::vector<std::pair<double, double>> inner_parameters(const BSplineSurface& s) {
  const std::vector<double> ub = s.u_breakpoints(), vb = s.v_breakpoints();
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 0; i + 1 < ub.size(); ++i) {
    for (std::size_t j = 0; j + 1 < vb.size(); ++j) {
      for (const double a : {0.3, 0.71}) out.emplace_back(ub[i] + a * (ub[i + 1] - ub[i]), vb[j] + (1 - a) * (vb[j + 1] - vb[j]));
    }
  }
  return out;
}

TEST(BSplineSurfaceDerivatives, PolynomialMatchFiniteDifferences) {
  const BSplineSurface s = test::from_occt(test::occt_wavy());
  ASSERT_FALSE(s.is_rational());
  for (const auto& [u, v] : inner_parameters(s)) expect_finite_differences(s, u, v);
}

TEST(BSplineSurfaceDerivatives, RationalMatchFiniteDifferences) {
  for (const BSplineSurface& s : {test::from_occt(test::occt_wavy_rational()), test::from_occt(test::occt_sphere()),
                                  test::from_occt(test::occt_cylinder())}) {
    ASSERT_TRUE(s.is_rational());
    for (const auto& [u, v] : inner_parameters(s)) expect_finite_differences(s, u, v);
  }
}

TEST(BSplineSurfaceDerivatives, MatchOpenCascadeD2) {
  for (const Handle(Geom_BSplineSurface)& occt :
       {test::occt_wavy(), test::occt_wavy_rational(), test::occt_sphere(), test::occt_cylinder(), test::occt_plane()}) {
    const BSplineSurface s = test::from_occt(occt);
    for (int i = 0; i <= 10; ++i) {
      for (int j = 0; j <= 10; ++j) {
        // Off the knots (OpenCASCADE and we may take either span at a knot), ends included.
        const double u = s.u_first() + (s.u_last() - s.u_first()) * std::min(1.0, (i + (i > 0 && i < 10 ? 0.013 : 0.0)) / 10);
        const double v = s.v_first() + (s.v_last() - s.v_first()) * std::min(1.0, (j + (j > 0 && j < 10 ? 0.029 : 0.0)) / 10);
        gp_Pnt p;
        gp_Vec du, dv, duu, dvv, duv;
        occt->D2(u, v, p, du, dv, duu, dvv, duv);
        const SurfaceDerivatives d = s.derivatives(u, v);
        const auto vec = [](const gp_XYZ& x) { return Vec3{x.X(), x.Y(), x.Z()}; };
        const double scale = max_norm({vec(du.XYZ()), vec(dv.XYZ()), vec(duu.XYZ()), vec(duv.XYZ()), vec(dvv.XYZ())});
        const double tolerance = 1e-12 * std::max(1.0, scale);
        EXPECT_LE(distance(d.point, vec(p.XYZ())), 1e-13 * std::max(1.0, norm(vec(p.XYZ()))));
        EXPECT_LE(distance(d.du, vec(du.XYZ())), tolerance) << u << " " << v;
        EXPECT_LE(distance(d.dv, vec(dv.XYZ())), tolerance) << u << " " << v;
        EXPECT_LE(distance(d.duu, vec(duu.XYZ())), tolerance) << u << " " << v;
        EXPECT_LE(distance(d.duv, vec(duv.XYZ())), tolerance) << u << " " << v;
        EXPECT_LE(distance(d.dvv, vec(dvv.XYZ())), tolerance) << u << " " << v;
      }
    }
  }
}

TEST(BSplineSurfaceDerivatives, ClampedToTheParameterRectangle) {
  const BSplineSurface s = test::from_occt(test::occt_wavy_rational());
  const SurfaceDerivatives inside = s.derivatives(s.u_last(), s.v_first());
  const SurfaceDerivatives outside = s.derivatives(s.u_last() + 0.5, s.v_first() - 0.5);
  EXPECT_EQ(inside.point, outside.point);
  EXPECT_EQ(inside.duu, outside.duu);
  EXPECT_EQ(inside.duv, outside.duv);
}

TEST(BSplineSurfaceDerivatives, DegreeOneDirectionHasNoSecondDerivative) {
  // Bilinear: S(u, v) = (u, v, u v): S_uu = S_vv = 0, S_uv = (0, 0, 1).
  const BSplineSurface s(1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 1}});
  const SurfaceDerivatives d = s.derivatives(0.3, 0.6);
  EXPECT_EQ(d.duu, (Vec3{0, 0, 0}));
  EXPECT_EQ(d.dvv, (Vec3{0, 0, 0}));
  EXPECT_NEAR(distance(d.duv, {0, 0, 1}), 0.0, 1e-15);
  EXPECT_NEAR(distance(d.du, {1, 0, 0.6}), 0.0, 1e-15);
  EXPECT_NEAR(distance(d.dv, {0, 1, 0.3}), 0.0, 1e-15);
}

TEST(BSplineSurfaceDerivatives, BreakpointsAreTheDistinctKnots) {
  const BSplineSurface s = test::from_occt(test::occt_wavy());
  EXPECT_EQ(s.u_breakpoints(), (std::vector<double>{0.0, 0.2, 0.5, 0.7, 1.1, 1.4, 2.0}));
  EXPECT_EQ(s.v_breakpoints(), (std::vector<double>{1.0, 1.3, 1.45, 1.8, 2.0}));
}

}  // namespace
}  // namespace hotmesh::geometry
