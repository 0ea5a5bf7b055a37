// hotmesh deform (internal): the sliding boundary nodes of the paper's section 4 across one
// increment (stage a to b):
//  - begin: each node gets its forcing displacement u0s (eq. 13), its share of the way to its
//    target x_F on the fully deflected boundary, (x_F - x_I) (b - a) / (1 - a), which is
//    (x_F - x_I) / (N - k + 1) for increment k of N (eq. 22); it is placed on the partial
//    boundary c_b and constrained along the normals there;
//  - after every Newton step: the nodes, moved tangentially by the projected PCG (eqs.
//    16-19), are projected back onto c_b (Fig. 4) and their normals updated;
//  - after each of these placements, passive surfaces with sliding nodes on their rim are
//    solved again from the rim as it stands (section 6.1);
//  - end (increment accepted): the slide vector a = dx2 - dx1 moves the target, which is
//    projected onto the fully deflected boundary (section 4.3).
#pragma once

#include <span>
#include <vector>

#include "constraints/boundary_conditions.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"

namespace hotmesh::deform::detail {

class SlidingNodes {
 public:
  /// The nodes are projected in shares by the ranks of `ranks`, every rank getting them all.
  SlidingNodes(BoundarySetup& setup, std::size_t dofs_per_node, const parallel::RankExchange& ranks)
      : setup_(setup), dim_(dofs_per_node), ranks_(ranks) {}

  std::size_t size() const { return setup_.sliding.size(); }

  /// Writes the forcing displacements of the increment into u (dofs of the sliding nodes),
  /// with the nodes placed on c_b, and sets their constraint normals; the passive surfaces
  /// their rims carry follow.
  void begin_increment(double a, double b, std::span<const Vec3> x, std::span<double> u);

  /// Projects the sliding nodes at x + u onto c_b, writes the new u and normals (and moves the
  /// passive surfaces their rims carry); returns the largest distance a node was moved by the
  /// projection.
  double project(double b, std::span<const Vec3> x, std::span<double> u);

  /// The largest |p . n| of a Newton step p over the sliding nodes, n their current normals:
  /// zero up to round-off when the projected PCG keeps u_s tangential (eq. 19).
  double normal_component(std::span<const double> p) const;

  /// After an accepted increment with final displacement u: moves the targets by the slide
  /// vectors a = dx2 - dx1 and projects them on the fully deflected boundary.
  void end_increment(std::span<const double> u);

 private:
  Vec3 displacement(std::span<const double> u, NodeId n) const;
  void set_displacement(std::span<double> u, NodeId n, const Vec3& d) const;

  /// Several processes: each rank places its share of the nodes and record()s the placements,
  /// which share_placements() gives every rank; share_targets() does the same for the targets
  /// of end_increment(). A node's projection hints travel with it, so its projections do not
  /// depend on the number of ranks.
  struct PlacedNode {
    Vec3 displacement;
    decltype(Placement::normals) normals;
    int normal_count = 0;
    decltype(SlidingNode::hints) hints;
  };
  struct MovedTarget {
    Vec3 target;
    decltype(SlidingNode::hints) hints;
  };
  void record(std::size_t k, const Vec3& displacement, const Placement& p);
  void share_placements(std::span<double> u);
  void share_targets();

  BoundarySetup& setup_;
  std::size_t dim_;
  const parallel::RankExchange& ranks_;
  std::vector<Vec3> forcing_;       ///< dx1 = u0s of the current increment, per sliding node
  std::vector<PlacedNode> placed_;  ///< per sliding node (several processes only)
};

}  // namespace hotmesh::deform::detail
