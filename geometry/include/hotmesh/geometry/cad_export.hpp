// hotmesh geometry: writing B-spline curves and surfaces to STEP (AP214) and IGES (5.3) with
// OpenCASCADE, so the reconstructed boundary (section 4.2) can be checked in any CAD system.
// Curves live in a plane (the x-y plane of a 2D case, the meridional plane of an axis) and
// are placed in 3D by a frame. Names are written where the format has room for them.
#pragma once

#include <string>
#include <vector>

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/bspline_curve.hpp"
#include "hotmesh/geometry/bspline_surface.hpp"
#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::geometry {

/// Places plane coordinates (a, b) at origin + a u + b v.
struct PlaneFrame {
  Vec3 origin{0.0, 0.0, 0.0};
  Vec3 u{1.0, 0.0, 0.0};
  Vec3 v{0.0, 1.0, 0.0};
};

/// (r, z) about the axis, in its meridional half-plane at angle theta (Axis::to_cartesian).
PlaneFrame meridional_frame(const Axis& axis, double theta = 0.0);

struct ExportCurve {
  std::string name;
  BSplineCurve2d curve;
  PlaneFrame frame;
};

struct ExportSurface {
  std::string name;
  BSplineSurface surface;
};

struct CadExport {
  std::vector<ExportCurve> curves;
  std::vector<ExportSurface> surfaces;
  LengthUnit unit = LengthUnit::metre;  ///< the unit of the coordinates, declared in the file
  /// The header's time stamp, "YYYY-MM-DDTHH:MM:SS" (STEP FILE_NAME; IGES dates of creation and
  /// last change, and the IGES author is then "hotmesh" instead of the user's login); empty:
  /// the current time. Give one for files that must come out the same byte for byte on any
  /// machine (a sample's committed CAD files).
  std::string time_stamp;
};

/// The content of a STEP file holding the curves (as edges) and surfaces (as faces).
std::string to_step(const CadExport& content);
/// The content of an IGES file holding the curves (entity 126) and surfaces (entity 128).
std::string to_iges(const CadExport& content);

}  // namespace hotmesh::geometry
