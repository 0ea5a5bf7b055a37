// hotmesh geometry (internal): the skeleton both measures of wall_deviation.hpp follow, against a
// curve (wall_deviation.cpp) and against CAD faces (surface_wall_deviation.cpp). A measure gives
// its two directions as sides; each side samples its side of the wall or the shape, keeps the
// largest distance and where it is reached, and collects the samples that may hide a higher
// maximum between them and their neighbours (the distance to a set is 1-Lipschitz); the
// candidates are then refined from the highest down while they can still beat the largest
// distance found. A direction with a sample that is not a number is NaN.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "hotmesh/geometry/wall_deviation.hpp"

namespace hotmesh::geometry::detail {

/// Distances below this, relative to the curve's length scale or to the wall's size, are
/// round-off: a local maximum of samples this close to the other side is not refined.
constexpr double kRoundOff = 1e-9;

/// The largest distance one direction has found so far, and whether a sample was not a number.
struct RunningMaximum {
  double best = -1.0;
  bool not_finite = false;

  /// Takes a distance; true if it is the largest so far (the side then records where it is).
  bool raise(double distance) {
    if (!(distance > best)) return false;
    best = distance;
    return true;
  }
  /// The direction's distance: NaN if a sample was, else the largest found (0 without samples).
  double distance() const { return not_finite ? std::numeric_limits<double>::quiet_NaN() : std::max(best, 0.0); }
};

/// What the refinement does with the next candidate, highest first: refine it, pass over it
/// (its bound cannot beat the largest distance found), or stop (no later one can either).
enum class Refinement { refine, pass_over, stop };

/// One direction, measured by `side`, which gives
///   std::vector<Candidate> sample(RunningMaximum&)    its samples, raising the maximum (and
///       recording where it is reached), and the local maxima that may hide a higher one;
///   static bool higher(const Candidate&, const Candidate&)   the refinement's order;
///   Refinement judge(const Candidate&, double best) const    whether one can still beat `best`;
///   void refine(const Candidate&, RunningMaximum&)    the local maximum near one, raising the
///       maximum.
/// The direction's distance goes to `worst`, whose point the side has recorded.
template <class Side>
void measure_direction(Side& side, WallDeviationPoint& worst) {
  RunningMaximum maximum;
  auto candidates = side.sample(maximum);
  // The highest first, so that the bound prunes the most.
  std::sort(candidates.begin(), candidates.end(), Side::higher);
  for (const auto& c : candidates) {
    const Refinement next = side.judge(c, maximum.best);
    if (next == Refinement::stop) break;
    if (next == Refinement::refine) side.refine(c, maximum);
  }
  worst.distance = maximum.distance();
}

/// Both directions of a measure, the wall's first: `measure.wall_side(result)` measures
/// mesh_to_shape and finds the part of the shape the wall covers, `measure.shape_side(result)`
/// then measures shape_to_mesh over that part; then the worse of the two.
template <class Measure>
void measure_both_directions(Measure& measure, WallDeviation& result) {
  auto wall = measure.wall_side(result);
  measure_direction(wall, result.mesh_to_shape);
  auto shape = measure.shape_side(result);
  measure_direction(shape, result.shape_to_mesh);
  result.take_worst_direction();
}

/// The median of the wall's edge lengths (0 for none), the length scale of the shape's samples.
/// Reorders them.
double median_length(std::vector<double>& lengths);

}  // namespace hotmesh::geometry::detail
