// hotmesh deform (internal): the corners of a sliding wall held by mesh nodes (beyond the
// paper: its sliding rounds the corners of a deflected wall, because no node need lie on them).
//
// Each corner (a feature of the wall's shape, BoundaryShape::features) is crossed by wall
// edges: edges whose ends lie on either side of its parameter. One end of every crossing edge
// is given the corner, the nearer one unless it is taken (it holds another corner, or lies
// where the wall meets another patch, except a slip plane through the corner: the side of a
// sector); that node then follows the corner exactly. In 2D a
// corner is crossed by one edge and held by one node; on a surface of revolution the corner is
// a circle, crossed by one edge per meridional row of wall faces, and held by one node per row.
// A node is not given a corner if that would shrink one of its wall edges below a quarter of
// its length (two corners within one cell): the corner is then reported as not held.
// The other sliding nodes of the wall keep to their segment: the parameter interval between
// the corners on either side of them.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/deform/mesh_motion.hpp"

namespace hotmesh::deform::detail {

/// One corner of a sliding wall and the nodes that hold it.
struct HeldFeature {
  geometry::ShapeFeature feature;
  std::vector<NodeId> nodes;   ///< the nodes given the corner (free sliding nodes)
  std::vector<NodeId> held_by_role;  ///< nodes of other roles that lie on it already
  double largest_offset = 0.0;  ///< largest distance of a node from the corner before the motion
  std::size_t unheld_edges = 0;  ///< crossing edges left without a node on the corner
  std::string note;              ///< why, where edges were left
};

struct WallFeaturePlan {
  std::vector<HeldFeature> features;  ///< in increasing parameter
  /// Per node of the patch (Patch::nodes order): the parameter of the node on the shape at
  /// stage 0, and the segment it keeps to.
  std::vector<double> parameters;
  std::vector<geometry::ParameterRange> segments;
};

/// The way a node given a corner line (a circle of a surface of revolution) goes onto it in
/// the corner pass: in the corner's cross-section (the meridional plane through the node) it
/// moves from where it starts, `start`, straight onto the corner as the stage goes from 0 to 1;
/// along the line it is free. Seen as a shape, it constrains one direction of that
/// cross-section (`direction` 0 or 1, of an orthonormal pair spanning it): a node sliding on
/// both directions' paths slides along the corner line only. `wall` is the wall at its final
/// stage (the pass's walls), `corner` the corner's parameter.
class CornerPath final : public geometry::BoundaryShape {
 public:
  CornerPath(const geometry::BoundaryShape& wall, double corner, const Vec3& start, int direction);

  geometry::ShapePoint project(const Vec3& p, double lambda, const geometry::ShapeParameter& hint = geometry::kNoHint,
                               const geometry::ParameterRange& range = {}) const override;
  geometry::ShapePoint at(const geometry::ShapeParameter& where, double lambda, const Vec3& reference) const override;

 private:
  /// The corner's point in the cross-section through p, and an orthonormal pair spanning
  /// that cross-section (from the wall's normals on either side of the corner).
  struct Section {
    Vec3 corner;
    std::array<Vec3, 2> axes;
  };
  Section section(const Vec3& p) const;

  const geometry::BoundaryShape& wall_;
  double corner_;
  std::array<double, 2> offset_{};  ///< of `start` from the corner, along the section's axes
  int direction_;
};

/// Whether node n may be given the corner whose point (in its meridional plane) is q.
using CanHold = std::function<bool(NodeId n, const Vec3& q)>;

/// The corners of `shape` (of at least `min_angle`) on one sliding patch, and the nodes that
/// hold them. `can_hold`: a sliding node of this wall only, free or held on planes through the
/// corner (a slip side of a sector). `x0` the positions of stage 0.
WallFeaturePlan plan_wall_features(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch,
                                   const geometry::BoundaryShape& shape, double min_angle, const CanHold& can_hold);

}  // namespace hotmesh::deform::detail
