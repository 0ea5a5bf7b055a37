// hotmesh geometry: section 4.2, eq. (20): the meridional curve r(t) of CAD faces about an
// axis. Surfaces of revolution with that axis give their generating curve exactly (the iso
// curve at constant angle, trimmed to the face); other faces are cut by a meridional plane
// and checked to be rotational. The pieces are joined into one profile.
#include <BRepAlgoAPI_Section.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Ax3.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <optional>
#include <span>
#include <cmath>
#include <numbers>
#include <sstream>

#include "cad/cad_model_impl.hpp"
#include "cad/face_analysis.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/core/input_error.hpp"
#include "cad/occt_convert.hpp"
#include "cad/profile_chain.hpp"

namespace hotmesh::geometry {

namespace {

using detail::ProfilePiece;

std::string describe(const Axis& axis) {
  std::ostringstream out;
  out.precision(6);
  const Vec3& o = axis.origin();
  const Vec3& d = axis.direction();
  out << "(" << o.x << ", " << o.y << ", " << o.z << ") along (" << d.x << ", " << d.y << ", " << d.z << ")";
  return out.str();
}

/// Two axes are the same line within `tolerance` over a region of size `size`.
bool same_axis(const Axis& a, const Axis& b, double tolerance, double size) {
  const double sine = norm(cross(a.direction(), b.direction()));
  const auto off_line = [](const Axis& line, const Vec3& p) {
    const Vec3 d = p - line.origin();
    return norm(d - dot(d, line.direction()) * line.direction());
  };
  return sine * size <= tolerance && off_line(a, b.origin()) <= tolerance && off_line(b, a.origin()) <= tolerance;
}

/// A 3D B-spline curve lying in the meridional half-plane theta as a curve in (r, z): the
/// map is linear, so poles (and weights) map exactly. Returns false if a pole is off the plane.
bool to_meridional(const Handle(Geom_BSplineCurve)& curve, const Axis& axis, const Vec3& radial, double tolerance,
                   BSplineCurve2d& out) {
  const Vec3 normal = cross(radial, axis.direction());
  for (Standard_Integer i = 1; i <= curve->NbPoles(); ++i) {
    if (std::abs(dot(detail::to_vec3(curve->Pole(i)) - axis.origin(), normal)) > tolerance) return false;
  }
  out = detail::to_plane_curve(curve, [&](const Vec3& p) {
    const Vec3 d = p - axis.origin();
    return Vec2{dot(d, radial), dot(d, axis.direction())};
  });
  return true;
}

/// Unit radial direction, about the axis, of the point of `points` farthest from it.
bool radial_direction(const Axis& axis, const std::vector<Vec3>& points, Vec3& radial) {
  double best = 0.0;
  for (const Vec3& p : points) {
    const Vec3 d = p - axis.origin();
    const Vec3 r = d - dot(d, axis.direction()) * axis.direction();
    if (norm(r) > best) {
      best = norm(r);
      radial = r / best;
    }
  }
  return best > 0.0;
}

/// The generating curve of an analytic surface of revolution: its iso curve at constant
/// angle (U), trimmed to the face's V range. False if it does not lie in a meridional plane
/// (a revolved curve skew to the axis).
bool iso_profile(const TopoDS_Face& face, const Axis& axis, double tolerance, BSplineCurve2d& out) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  const Handle(Geom_Curve) iso = surface->UIso(0.5 * (u0 + u1));
  const double first = iso->IsPeriodic() ? v0 : std::max(v0, iso->FirstParameter());
  const double last = iso->IsPeriodic() ? v1 : std::min(v1, iso->LastParameter());
  if (!(last > first)) return false;
  const Handle(Geom_BSplineCurve) curve = detail::to_bspline(iso, first, last);
  std::vector<Vec3> points;
  for (int i = 0; i <= 16; ++i) points.push_back(detail::to_vec3(curve->Value(first + (last - first) * i / 16)));
  Vec3 radial;
  if (!radial_direction(axis, points, radial)) return false;
  return to_meridional(curve, axis, radial, tolerance, out);
}

/// The angle (about the axis) in the middle of the arc the face covers: the complement of
/// the largest gap between the angles of its sample points.
double middle_angle(const Axis& axis, const std::vector<Vec3>& points) {
  std::vector<double> angles;
  for (const Vec3& p : points) angles.push_back(axis.to_cylindrical(p).theta);
  std::sort(angles.begin(), angles.end());
  if (angles.empty()) return 0.0;
  double gap = angles.front() + 2 * std::numbers::pi - angles.back();
  double gap_end = angles.front();
  for (std::size_t i = 1; i < angles.size(); ++i) {
    if (angles[i] - angles[i - 1] > gap) {
      gap = angles[i] - angles[i - 1];
      gap_end = angles[i];
    }
  }
  return gap_end + 0.5 * (2 * std::numbers::pi - gap);
}

/// The parts of a section curve with r >= 0: a plane through the axis cuts a face crossing the
/// axis (a disc, a sphere) along a curve that runs on into the other half-plane, r < 0.
std::vector<BSplineCurve2d> positive_parts(const BSplineCurve2d& curve, double tolerance) {
  constexpr int kSamples = 128;
  const double a = curve.first_parameter();
  const double b = curve.last_parameter();
  std::vector<double> cuts{a};
  double previous = curve.point(a).x;
  for (int i = 1; i <= kSamples; ++i) {
    const double t = a + (b - a) * i / kSamples;
    const double r = curve.point(t).x;
    if ((previous < 0.0) != (r < 0.0)) {
      double lo = t - (b - a) / kSamples;
      double hi = t;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((curve.point(mid).x < 0.0) == (previous < 0.0) ? lo : hi) = mid;
      }
      cuts.push_back(0.5 * (lo + hi));
    }
    previous = r;
  }
  cuts.push_back(b);
  std::vector<BSplineCurve2d> parts;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double mid = 0.5 * (cuts[i] + cuts[i + 1]);
    if (curve.point(mid).x < 0.0 || cuts[i + 1] - cuts[i] <= 1e-12 * (b - a)) continue;
    if (cuts.size() == 2) {
      parts.push_back(curve);
      continue;
    }
    const Handle(Geom2d_BSplineCurve) part = detail::to_occt(curve);
    part->Segment(cuts[i], cuts[i + 1]);
    BSplineCurve2d piece = detail::to_curve(part);
    if (distance(piece.point(piece.first_parameter()), piece.point(piece.last_parameter())) > tolerance) {
      parts.push_back(std::move(piece));
    }
  }
  return parts;
}

/// The face cut by the meridional half-plane at the middle of its arc, in (r, z).
std::vector<BSplineCurve2d> section_profile(const TopoDS_Face& face, const Axis& axis,
                                            const std::vector<Vec3>& points, double tolerance) {
  const double theta = middle_angle(axis, points);
  const Vec3 radial = axis.meridional_vector(theta, 1.0, 0.0);
  const gp_Pln plane(gp_Ax3(detail::to_pnt(axis.origin()), detail::to_dir(cross(radial, axis.direction())),
                            detail::to_dir(radial)));
  BRepAlgoAPI_Section section(face, plane, false);
  section.Approximation(true);
  section.Build();
  std::vector<BSplineCurve2d> pieces;
  if (!section.IsDone()) return pieces;
  for (TopExp_Explorer it(section.Shape(), TopAbs_EDGE); it.More(); it.Next()) {
    double first = 0.0;
    double last = 0.0;
    const Handle(Geom_Curve) curve = BRep_Tool::Curve(TopoDS::Edge(it.Current()), first, last);
    if (curve.IsNull() || !(last > first)) continue;
    const Handle(Geom_BSplineCurve) bspline = detail::to_bspline(curve, first, last);
    BSplineCurve2d piece = BSplineCurve2d::polyline(std::vector<double>{0, 1}, std::vector<Vec2>{{0, 0}, {1, 0}});
    // The section lies in the plane up to the intersection's approximation.
    if (!to_meridional(bspline, axis, radial, 10 * tolerance, piece)) continue;
    for (BSplineCurve2d& half : positive_parts(piece, tolerance)) pieces.push_back(std::move(half));
  }
  return pieces;
}

/// Largest distance of the face's sample points, in (r, z), from its meridional pieces.
double rotational_deviation(const std::vector<Vec3>& points, const Axis& axis, const std::vector<BSplineCurve2d>& pieces,
                            Vec3& worst_point) {
  std::vector<CurveProjector> projectors;
  for (const auto& piece : pieces) projectors.emplace_back(DeflectedCurve(piece));
  double worst = 0.0;
  for (const Vec3& p : points) {
    const Cylindrical c = axis.to_cylindrical(p);
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& projector : projectors) nearest = std::min(nearest, projector.project({c.r, c.z}, 0.0).distance);
    if (nearest > worst) {
      worst = nearest;
      worst_point = p;
    }
  }
  return worst;
}

}  // namespace

namespace {

/// The meridional pieces of some faces, about the axis they turn about, with the tolerance.
struct MeridionalPieces {
  std::vector<ProfilePiece> pieces;
  Axis axis;
  double tolerance = 0.0;
};

MeridionalPieces meridional_pieces(const CadModel& model, const std::vector<TopoDS_Face>& faces,
                                   std::span<const int> face_ids, const MeridionalOptions& options) {
  const std::string source = model.path().string();
  if (face_ids.empty()) throw InputError::in(source, "no faces given for the meridional curve");
  Box3 box{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (std::size_t i = 0; i < face_ids.size(); ++i) {
    const FaceInfo& info = model.face(face_ids[i]);
    if (std::count(face_ids.begin(), face_ids.end(), face_ids[i]) > 1) {
      throw InputError::in(source, "face " + std::to_string(face_ids[i]) + " is given twice");
    }
    for (int k = 0; k < 3; ++k) {
      box.min[k] = std::min(box.min[k], info.bounds.min[k]);
      box.max[k] = std::max(box.max[k], info.bounds.max[k]);
    }
  }
  const double size = detail::diagonal(box);
  const double tolerance = options.relative_tolerance * size;

  // The axis: given, or the one the faces with an axis agree on.
  std::optional<Axis> axis = options.axis;
  int axis_face = 0;
  if (!axis) {
    for (const int id : face_ids) {
      const FaceInfo& info = model.face(id);
      if (!info.axis) continue;
      if (!axis) {
        axis = info.axis;
        axis_face = id;
      } else if (!same_axis(*axis, *info.axis, tolerance, size)) {
        throw InputError::in(source, "faces " + std::to_string(axis_face) + " and " + std::to_string(id) +
                                         " turn about different axes, " + describe(*axis) + " and " +
                                         describe(*info.axis) + ": give the axis");
      }
    }
    if (!axis) throw InputError::in(source, "none of the faces is a surface of revolution: give the axis");
  }

  std::vector<ProfilePiece> pieces;
  try {
    for (const int id : face_ids) {
      const FaceInfo& info = model.face(id);
      const TopoDS_Face& f = faces[static_cast<std::size_t>(id - 1)];
      BSplineCurve2d exact = BSplineCurve2d::polyline(std::vector<double>{0, 1}, std::vector<Vec2>{{0, 0}, {1, 0}});
      if (info.axis_source == AxisSource::analytic && same_axis(*axis, *info.axis, tolerance, size) &&
          iso_profile(f, *axis, tolerance, exact)) {
        pieces.push_back({std::move(exact), id});
        continue;
      }
      const std::vector<Vec3> points = detail::sample_face(f, 12, true).points;
      const std::vector<BSplineCurve2d> cut = section_profile(f, *axis, points, tolerance);
      if (cut.empty()) {
        throw InputError::in(source, "face " + std::to_string(id) + " has no section with a meridional plane of the axis " +
                                         describe(*axis));
      }
      Vec3 worst;
      const double deviation = rotational_deviation(points, *axis, cut, worst);
      if (deviation > tolerance) {
        std::ostringstream out;
        out.precision(6);
        out << "face " << id << " (" << to_string(info.kind) << ") is not a surface of revolution about the axis "
            << describe(*axis) << ": its point (" << worst.x << ", " << worst.y << ", " << worst.z << ") is "
            << deviation << " from the meridional section (tolerance " << tolerance << ")";
        throw InputError::in(source, out.str());
      }
      for (const auto& piece : cut) pieces.push_back({piece, id});
    }
  } catch (const Standard_Failure& e) {
    throw InputError::in(source, std::string("OpenCASCADE failed on the meridional curve: ") + e.GetMessageString());
  }
  return {std::move(pieces), *axis, tolerance};
}

}  // namespace

MeridionalCurve CadModel::meridional_curve(std::span<const int> face_ids, const MeridionalOptions& options) const {
  MeridionalPieces m = meridional_pieces(*this, impl_->faces, face_ids, options);
  detail::Profile profile = detail::join_profile(std::move(m.pieces), m.tolerance, impl_->path.string());
  return {std::move(profile.curve), m.axis, std::move(profile.faces), std::move(profile.face_breaks), m.tolerance};
}

std::vector<MeridionalCurve> CadModel::meridional_profiles(std::span<const int> face_ids,
                                                           const MeridionalOptions& options) const {
  MeridionalPieces m = meridional_pieces(*this, impl_->faces, face_ids, options);
  std::vector<MeridionalCurve> curves;
  for (detail::Profile& profile : detail::join_profiles(std::move(m.pieces), m.tolerance, impl_->path.string())) {
    curves.push_back({std::move(profile.curve), m.axis, std::move(profile.faces), std::move(profile.face_breaks),
                      m.tolerance});
  }
  return curves;
}

}  // namespace hotmesh::geometry
