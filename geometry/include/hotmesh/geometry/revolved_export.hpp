// hotmesh geometry: a meridional profile revolved about an axis and written to STEP (AP214)
// with OpenCASCADE: the CAD model of an axisymmetric part as the paper's section 4.2 reads it
// back ("the intersection of a CAD surface with a meridional plane is a B-Spline curve r(t)").
//
// Each meridian (r, z) becomes one face, swept from theta = 0 (Axis frame) by the angle given.
// Faces are written in the order given, each as a product named after it, so CadModel::read
// numbers them 1, 2, ... in that order and CAD systems show their names. A straight meridian (degree 1, two poles) is written as a line, which the sweep
// turns into an analytic face: a plane (meridian normal to the axis), a cylinder (parallel) or
// a cone; other meridians give surfaces of revolution of their B-spline (rational ones stay
// rational, so circle arcs are exact).
#pragma once

#include <numbers>
#include <string>
#include <vector>

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/bspline_curve.hpp"
#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::geometry {

struct RevolvedFace {
  std::string name;         ///< written as the STEP item's name; may be empty
  BSplineCurve2d meridian;  ///< (r, z) about the axis, r >= 0
};

struct RevolvedModel {
  Axis axis;
  double angle = 2.0 * std::numbers::pi;  ///< sweep in radians, 0 < angle <= 2 pi, from theta = 0
  std::vector<RevolvedFace> faces;
  LengthUnit unit = LengthUnit::metre;  ///< the unit of the coordinates, declared in the file
  /// The header's time stamp (FILE_NAME); empty: the current time. Give one (e.g.
  /// "2000-01-01T00:00:00") for files that must come out the same byte for byte.
  std::string time_stamp;
};

/// The content of a STEP file with one face per meridian, in order. Throws std::invalid_argument
/// for an angle outside (0, 2 pi], a meridian with r < 0 or no faces, and std::runtime_error
/// if OpenCASCADE fails.
std::string to_step(const RevolvedModel& model);

}  // namespace hotmesh::geometry
