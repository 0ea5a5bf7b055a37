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

/// Whether node n may be given the corner whose point (in its meridional plane) is q.
using CanHold = std::function<bool(NodeId n, const Vec3& q)>;

/// The corners of `shape` (of at least `min_angle`) on one sliding patch, and the nodes that
/// hold them. `can_hold`: a sliding node of this wall only, free or held on planes through the
/// corner (a slip side of a sector). `x0` the positions of stage 0.
WallFeaturePlan plan_wall_features(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch,
                                   const geometry::BoundaryShape& shape, double min_angle, const CanHold& can_hold);

}  // namespace hotmesh::deform::detail
