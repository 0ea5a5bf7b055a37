// hotmesh sample stator_well: the boundary loop of a planar region as one arc-length coordinate
// s (for the block mesher, block_mesh.hpp). Points at a given s lie exactly on the loop's curves;
// points on the loop are located by projection; walls are the loop's curves grouped into smooth
// chains (curves joined with a continuous tangent belong to one wall).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "block_mesh.hpp"

namespace hotmesh::samples {

class BoundaryLoop {
 public:
  /// Throws std::invalid_argument if a curve does not end where the next one starts.
  explicit BoundaryLoop(const std::vector<LoopCurve>& curves);

  double length() const { return start_.back(); }
  /// The point at loop coordinate s (taken modulo the length), on its curve.
  Vec2 point(double s) const;
  /// The loop coordinate of p, in [0, length()), if p is within `tolerance` of the loop.
  std::optional<double> locate(Vec2 p, double tolerance) const;
  /// The curve holding [s, s + ds) and the one holding (s - ds, s].
  std::size_t curve_after(double s) const;
  std::size_t curve_before(double s) const;
  /// The walls (smooth chains of wall curves) touching s; open boundaries are left out.
  std::vector<int> walls_at(double s) const;
  /// The wall of curve i, or -1 for an open boundary.
  int wall(std::size_t i) const { return wall_[i]; }

 private:
  std::vector<BSplineCurve2d> curves_;
  std::vector<double> start_;                            // loop coordinate where each curve starts; then the length
  std::vector<std::vector<std::array<double, 2>>> arc_;  // per curve: (parameter, arc length) samples
  std::vector<int> wall_;
  double eps_ = 0.0;
};

}  // namespace hotmesh::samples
