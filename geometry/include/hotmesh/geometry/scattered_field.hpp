// hotmesh geometry: a vector field known at scattered points (the FEM nodes of a wall, in
// cartesian x, y, z) interpolated anywhere near them. A prescribed 3D patch without CAD takes
// its nodes' deflections from this at degree 2 and more (issue 23, item 0); at degree 1 from
// the linear interpolation of linear_field.hpp, which does not overshoot at kinks.
//
// Method: partition-of-unity interpolation with local polyharmonic radial basis functions
// (Wendland, "Fast evaluation of radial basis functions: methods based on partition of unity",
// 2002; Cavoretto & De Rossi, "A trivariate interpolation algorithm using a cube-partition
// searching procedure", 2015). Overlapping balls (patches) cover the points; on each, the
// r^3 spline plus a linear polynomial interpolates the patch's points exactly; the patch
// interpolants are blended by Wendland's C2 functions normalised to sum to one. Chosen because
// it is
//   exact at the points:  every patch interpolant is, and every patch that weighs a point holds it;
//   linear-exact:         every patch interpolant reproduces a linear field (over its points'
//                         affine hull, so points on a plane or a line are handled; but see
//                         coordinate_precision);
//   smooth:               C2 between the points (r^3 is C2, so are the weights);
//   local:                set-up is O(N) small dense solves, an evaluation O(log N + the points of
//                         the few patches around it), where one global RBF system costs O(N^3).
//
// Patches: the points' bounding cube is split as an octree. A cell's ball is centred on the
// cell with radius `overlap` times its half-diagonal, so it covers the cell. A cell is split
// while its ball holds more than `max_patch_points` points; every leaf cell holding points is a
// patch, its ball grown (if it holds fewer than `min_patch_points`) to 1.1 times the distance
// of its min_patch_points-th nearest point. Every point lies in its leaf's ball; cells are
// refined where the points are dense, and only cells holding points are kept, so curved
// surfaces, thin strips and graded FEM meshes get patches of bounded size. With the defaults a
// patch holds about 30 to 100 points; data of at most `max_patch_points` points are one patch.
//
// Outside every ball (far from the data) the value is that of the patch whose ball is nearest:
// finite and bounded near the data, but neither smooth nor meaningful far away. Callers that
// care check the distance of their points to the data themselves.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "hotmesh/core/vec3.hpp"
#include "hotmesh/geometry/wall_field.hpp"

namespace hotmesh::geometry {

struct ScatteredFieldOptions {
  /// A patch's ball is grown until it holds this many points (or all of them).
  std::size_t min_patch_points = 30;
  /// A cell is split while its ball holds more points than this (the size of the local dense
  /// systems); data with at most this many distinct points are one patch.
  std::size_t max_patch_points = 100;
  /// A cell's ball radius over the cell's half-diagonal, 1.05 to 4: how far patches overlap.
  double overlap = 1.25;
  /// A patch's dimension: a principal extent (RMS) of its points at most `flatness` times the
  /// largest one, or at most `coordinate_precision` times the largest |coordinate| of the data,
  /// is dropped; the patch's linear polynomial is then over the plane (or line) that remains,
  /// and the field is constant along the dropped directions. The second test is for rounding:
  /// points on a plane written with 7 significant digits would otherwise span 3D, and the field
  /// off the plane would follow a normal gradient fitted to the rounding noise. The price: on a
  /// patch curved by less than that, a linear field is reproduced only to its normal gradient
  /// times the patch's RMS distance from its plane. 0 turns the second test off.
  double flatness = 1e-6;
  double coordinate_precision = 1e-6;
  /// Points closer than this fraction of the data's bounding-box diagonal are one point: the
  /// first sample's is kept...
  double same_point = 1e-10;
  /// ...provided their values agree within this fraction of the largest |value|; otherwise
  /// the constructor throws hotmesh::InputError naming both samples.
  double same_value = 1e-6;
};

struct ScatteredFieldReport {
  std::size_t samples = 0;            ///< points given
  std::size_t points = 0;             ///< distinct points interpolated
  std::size_t merged_duplicates = 0;  ///< samples - points
  std::size_t patches = 0;
  std::size_t flat_patches = 0;       ///< patches whose points span a plane or a line only
  std::size_t largest_patch = 0;      ///< points of the largest local system
  double mean_patch = 0.0;            ///< mean points per patch
  /// Largest |s_j(p_i) - f_i| over every patch j and point i of it (in the values' units);
  /// bounds the residual of the blended field at the points.
  double max_residual = 0.0;
};

/// A vector field known at scattered points, interpolated anywhere near them (see above).
class ScatteredField final : public WallField {
 public:
  /// Throws hotmesh::InputError for a non-finite coordinate or value, duplicates with
  /// different values, or fewer than 3 distinct points not on one line (a field over a surface
  /// or a volume); std::invalid_argument for sizes that differ or options out of range.
  ScatteredField(std::vector<Vec3> points, std::vector<Vec3> values, const ScatteredFieldOptions& options = {});

  /// The interpolated value at x. Const and thread-safe (no state is changed).
  Vec3 operator()(const Vec3& x) const override;

  /// How far x lies outside every patch's ball, the region the points cover (0 within).
  double outside(const Vec3& x) const override;

  const ScatteredFieldReport& report() const { return report_; }

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;  // immutable after construction: copies share it
  ScatteredFieldReport report_;
};

}  // namespace hotmesh::geometry
