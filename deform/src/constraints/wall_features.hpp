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
// A wall made of faces has creases instead (issue 20 item 2 on faces): edges where two faces
// meet at an angle. Where the mesh has nodes on a crease they slide along it from the start
// (BoundaryShape::crease_sides); where its lines miss it, the crease is crossed by the wall
// edges whose ends lie on its two faces, and one end of each is given it as a corner circle
// is: that node is led onto the crease and then slides along it. The other sliding nodes of
// such a wall keep to their region, the faces between its creases that hold theirs.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/deform/mesh_motion.hpp"

namespace hotmesh::deform::detail {

/// One corner of a sliding wall and the nodes that hold it.
struct HeldFeature {
  geometry::ShapeFeature feature;  ///< for a crease: its angle only
  /// A crease between two faces of the wall (a line the mesh's lines may miss) instead of a
  /// corner of a curve.
  std::optional<geometry::ShapeCrease> crease;
  std::vector<NodeId> nodes;   ///< the nodes given the corner (free sliding nodes)
  std::vector<NodeId> held_by_role;  ///< nodes of other roles that lie on it already
  double largest_offset = 0.0;  ///< largest distance of a node from the corner before the motion
  std::size_t unheld_edges = 0;  ///< crossing edges left without a node on the corner
  std::string note;              ///< why, where edges were left
  bool from_start = false;       ///< its nodes lay on it before the motion (plan_corners_on_nodes)
};

struct WallFeaturePlan {
  std::vector<HeldFeature> features;  ///< in increasing parameter
  /// Per node of the patch (Patch::nodes order): the parameter of the node on the shape at
  /// stage 0, and the segment it keeps to.
  std::vector<double> parameters;
  std::vector<geometry::ParameterRange> segments;
};

/// A line of a wall that nodes are led onto: a corner of its meridional curve (a circle about
/// the axis, at parameter `corner`) or a crease between two of its faces.
struct CornerLine {
  double corner = 0.0;
  std::optional<geometry::ShapeCrease> crease;
};

/// The way a node given a corner line (a circle of a surface of revolution, or a crease of a
/// wall made of faces) goes onto it: in the line's cross-section through the node (for a
/// circle, the meridional plane) it moves from where it starts, `start` (its offset from the
/// line at stage 0), onto the line at stage lambda, the offset fading as (1 - lambda); along the
/// line it is free. Seen as a shape, it constrains one direction of that cross-section
/// (`direction` 0 or 1, of an orthonormal pair spanning it): a node sliding on both directions'
/// paths slides along the line only. In the corner pass `wall` is the wall at its final stage
/// for every lambda (the pass's walls); a node on a corner circle from the start follows the
/// circle of each stage through the motion.
class CornerPath final : public geometry::BoundaryShape {
 public:
  CornerPath(const geometry::BoundaryShape& wall, CornerLine line, const Vec3& start, int direction);

  geometry::ShapePoint project(const Vec3& p, double lambda, const geometry::ShapeParameter& hint = geometry::kNoHint,
                               const geometry::ParameterRange& range = {}) const override;
  geometry::ShapePoint at(const geometry::ShapeParameter& where, double lambda, const Vec3& reference) const override;

 private:
  /// The corner's point at stage lambda in the cross-section through p, and an orthonormal
  /// pair spanning that cross-section (from the wall's normals on either side of the corner).
  struct Section {
    Vec3 corner;
    std::array<Vec3, 2> axes;
  };
  Section section(const Vec3& p, double lambda) const;

  const geometry::BoundaryShape& wall_;
  CornerLine line_;
  std::array<double, 2> offset_{};  ///< of `start` from the corner, along the section's axes
  int direction_;
};

/// Whether node n may be given the corner whose point (in its meridional plane) is q.
using CanHold = std::function<bool(NodeId n, const Vec3& q)>;

/// The node a periodic slave n follows (its master), or -1: where a slave's master holds a
/// corner, the slave holds it too.
using MasterOf = std::function<NodeId(NodeId n)>;

/// The plane a slip patch keeps its nodes on (u . n = 0, eq. 11).
struct SlipPlane {
  Vec3 origin;
  Vec3 normal;  ///< unit
};
/// The slip planes node n is held on (a side of a sector: none, one or two). A crease's point
/// for a node on a plane is where the crease crosses it, which the node can reach.
using PlanesOf = std::function<std::vector<SlipPlane>(NodeId n)>;

/// The corners and creases of `shape` (of at least `min_angle`) on one sliding patch, and the
/// nodes that hold them. A crease is crossed by the wall edges
/// whose ends lie on its two faces. `can_hold`: a sliding node of this wall only, free or held on planes through the
/// corner (a slip side of a sector). A crossing edge with an end on a periodic slave whose master
/// holds the corner is held through it (`master_of`). `x0` the positions of stage 0.
WallFeaturePlan plan_wall_features(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch,
                                   const geometry::BoundaryShape& shape, double min_angle, const CanHold& can_hold,
                                   const PlanesOf& planes_of, const MasterOf& master_of);

/// The corners of `shape` (of at least `min_angle`) that nodes of the wall lie on before the
/// motion, as every mesh made from CAD has them. Such a node cannot slide: the wall has no
/// tangent there, and Newton would alternate between the sides. It holds the corner from the
/// start; the other nodes keep to the segments between these corners. A node lies on a corner
/// if it is within kOnCornerRounding of its shortest wall edge from it; in a fresh run
/// (`drawn_corners`), on a corner of the wall as drawn (a CAD vertex, a kink of the cold FEM
/// wall: ShapeFeature::undeformed_angle) within kOnCornerShare, since a node that close slides
/// into the corner and stalls there too. A restarted run and the corner pass start where such
/// nodes were put on their corners, and take them to rounding only, so that a chain of
/// restarted runs makes the moves of one straight run. Corners without such a node are left
/// out (the corner pass gives them nodes). Creases are not planned here: nodes on them slide
/// along them (BoundaryShape::crease_sides).
WallFeaturePlan plan_corners_on_nodes(const Mesh& mesh, std::span<const Vec3> x0, const Patch& patch,
                                      const geometry::BoundaryShape& shape, double min_angle, bool drawn_corners,
                                      const CanHold& can_hold);

/// A node within this share of its shortest wall edge from a corner of the wall as drawn lies
/// on it (plan_corners_on_nodes).
inline constexpr double kOnCornerShare = 0.25;
/// A node within this share of its shortest wall edge from a corner lies on it up to the
/// rounding of the files and of the motion.
inline constexpr double kOnCornerRounding = 1e-6;

}  // namespace hotmesh::deform::detail
