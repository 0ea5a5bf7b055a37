// hotmesh geometry (internal): conversions between hotmesh's own types and OpenCASCADE's
// (points, B-spline curves and surfaces). Flat knot vectors on our side, knots with
// multiplicities (1-based arrays) on OpenCASCADE's; periodic curves are made non-periodic.
#pragma once

#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Curve.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <functional>

#include "hotmesh/geometry/bspline_curve.hpp"
#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry::detail {

inline Vec3 to_vec3(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }
inline Vec3 to_vec3(const gp_Pnt& p) { return to_vec3(p.XYZ()); }
inline Vec3 to_vec3(const gp_Dir& d) { return to_vec3(d.XYZ()); }
inline gp_Pnt to_pnt(const Vec3& p) { return gp_Pnt(p.x, p.y, p.z); }
inline gp_Dir to_dir(const Vec3& d) { return gp_Dir(d.x, d.y, d.z); }

BSplineCurve2d to_curve(const Handle(Geom2d_BSplineCurve)& curve);
Handle(Geom2d_BSplineCurve) to_occt(const BSplineCurve2d& curve);

/// `curve` over [first, last] as a non-periodic B-spline (GeomConvert: exact, rational for
/// circles and other conics).
Handle(Geom_BSplineCurve) to_bspline(const Handle(Geom_Curve)& curve, double first, double last);

/// A 3D B-spline curve that lies in a plane as a curve in that plane's coordinates: its poles
/// mapped by `to_plane`, an affine map (so the curve maps exactly), knots and weights kept.
BSplineCurve2d to_plane_curve(const Handle(Geom_BSplineCurve)& curve, const std::function<Vec2(const Vec3&)>& to_plane);

/// The 3D curve of a plane curve placed by origin + x u + y v.
Handle(Geom_BSplineCurve) to_occt_3d(const BSplineCurve2d& curve, const Vec3& origin, const Vec3& u, const Vec3& v);

BSplineSurface to_surface(const Handle(Geom_BSplineSurface)& surface);
Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& surface);

}  // namespace hotmesh::geometry::detail
