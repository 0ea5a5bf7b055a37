// hotmesh geometry (internal): a discrete wall's edges in the plane of its curve, for the measure
// against a curve (wall_deviation.cpp): the distinct edges of its faces in the x-y plane or the
// meridional plane, and a uniform grid over them that finds the edge nearest to a point.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "hotmesh/geometry/wall_deviation.hpp"

namespace hotmesh::geometry::detail {

/// A wall edge in the curve's plane, with the indices of its end points.
struct Segment {
  Vec2 a;
  Vec2 b;
  std::int32_t na = 0;
  std::int32_t nb = 0;
};

inline Vec2 lerp(const Vec2& a, const Vec2& b, double s) { return a + s * (b - a); }
inline Vec3 lerp(const Vec3& a, const Vec3& b, double s) { return a + s * (b - a); }

/// The distinct edges of the faces (an edge shared by two faces once), in the curve's plane.
std::vector<Segment> plane_segments(std::span<const Vec3> points, const WallFaces& faces,
                                    const std::optional<Axis>& axis);

/// Uniform grid over the wall's edges: each cell lists the edges passing through it, so that
/// the nearest edge to a point is found by searching rings of cells around the point's cell
/// until the ring is farther than the nearest edge found.
class SegmentGrid {
 public:
  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    std::size_t segment = 0;
    double s = 0.0;  ///< fraction along the segment of the nearest point
  };

  /// `cell`: the cell size wanted (the median edge length); enlarged so that there are at most
  /// about three cells per edge.
  SegmentGrid(std::span<const Segment> segments, double cell);

  Nearest nearest(const Vec2& p) const;

 private:
  std::pair<std::size_t, std::size_t> index(const Vec2& p) const;
  void visit(std::size_t cell, const Vec2& p, Nearest& best) const;

  std::span<const Segment> segments_;
  Vec2 lo_;
  double cell_ = 1.0;
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> items_;
};

}  // namespace hotmesh::geometry::detail
