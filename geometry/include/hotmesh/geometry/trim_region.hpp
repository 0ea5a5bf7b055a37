// hotmesh geometry: the part of a face's parameter rectangle that its trimming curves enclose
// (issue 23). A CAD face is a surface S(t, s) over a rectangle and the loops of edges that bound
// it there (CadFace::trims): a plate with a hole is a plane whose rectangle covers the hole, a
// cap of a cylinder is a square cut by a circle. A node sliding on such a face must stay inside
// its loops: beyond them lies no wall (the hole's footprint), or another face of it.
//
// TrimRegion holds the loops as polylines in (t, s) and answers whether a parameter pair lies
// inside them (even-odd rule, so loops need no order or orientation; the outer loop and the
// holes alike). A uniform grid of cells keeps each query to the few segments of its cell: a cell
// knows whether its centre is inside, and a query counts the crossings of the segment from the
// centre to its point.
//
// Each curve says whether it binds: a curve the wall goes on across (an edge shared with another
// face of the wall) holds a sliding node inside; a free one (where the wall ends, a seam, a
// pole) does not, so the face reaches beyond it as it does beyond its rectangle's free sides.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "hotmesh/geometry/cad_face.hpp"
#include "hotmesh/geometry/parametric_surface.hpp"
#include "hotmesh/core/vec2.hpp"

namespace hotmesh::geometry {

class TrimRegion {
 public:
  struct Curve {
    std::vector<Vec2> points;  ///< a polyline in (t, s)
    bool binding = true;       ///< a sliding node stays on its inner side
  };

  /// Throws std::invalid_argument for no curve with two points, a point that is not finite or
  /// an empty rectangle.
  TrimRegion(std::vector<Curve> curves, const ParameterRectangle& rectangle);

  /// Whether (t, s) lies inside the loops (points beyond the rectangle do not).
  bool contains(double t, double s) const;
  /// Whether a part of the rectangle lies wholly outside the loops with a binding curve nearest
  /// its middle: no point of it belongs to the face a node slides on, nor is it beyond a free
  /// curve where the face reaches on.
  bool excludes(const ParameterRectangle& part) const;
  const std::vector<Curve>& curves() const { return curves_; }

 private:
  struct Segment {
    Vec2 a;
    Vec2 b;
  };
  /// Whether the segments from `from` to `to` and `s` cross (one endpoint of s counted, so a
  /// path through a vertex of two segments crosses one of them).
  static bool crosses(const Vec2& from, const Vec2& to, const Segment& s);
  Vec2 centre(std::size_t i, std::size_t j) const;

  std::vector<Curve> curves_;
  std::vector<Segment> segments_;
  std::vector<char> binding_;  ///< per segment: its curve binds
  ParameterRectangle rectangle_;
  std::size_t cells_ = 1;                    ///< per direction
  std::vector<std::vector<std::size_t>> in_cell_;  ///< segments meeting each cell, i * cells_ + j
  std::vector<char> centre_inside_;
};

/// Whether every point lies on one side of the rectangle (to 1e-9 of its extent): a trimming
/// curve that runs along that side rather than across the rectangle.
bool along_rectangle_side(std::span<const Vec2> points, const ParameterRectangle& rectangle);

/// The point at x (in vertices: 0 at the first, n - 1 at the last) of the smooth curve through a
/// polyline's vertices, as a Catmull-Rom spline (the vertices are even in the edge's parameter,
/// as CadFace::trims are): within rounding of the edge's curve where its chords are within 1e-6
/// of it. Beyond an end, the parabola through the last three vertices gives the tangent.
Vec2 curve_point(std::span<const Vec2> q, double x);

/// The x in [a, b] (vertices) where the surface point S(curve_point(q, x)) is nearest p:
/// golden-section search, then a bracketed secant on the distance's derivative. `surface`
/// gives S and its derivatives at (t, s); the distance is unimodal over a few spans around its
/// minimum.
double nearest_on_curve(std::span<const Vec2> q, double a, double b, const Vec3& p,
                        const std::function<SurfaceDerivatives(const Vec2&)>& surface);

/// The region a wall's face slides in: nullptr where each of its trims (CadFace::trims) runs
/// along a side of its rectangle, or it has none (the whole rectangle is the face). A trim curve
/// binds where `shared(edge)`: an edge of the CAD file that another face of the wall also names.
std::shared_ptr<const TrimRegion> trim_region(const CadFace& face, const std::function<bool(int edge)>& shared);

}  // namespace hotmesh::geometry
