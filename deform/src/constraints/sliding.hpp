// hotmesh deform (internal): the sliding boundary nodes of the paper's section 4: what a sliding
// node carries, where it lands on its walls (place_sliding_node, Fig. 4), and the nodes across
// one increment (stage a to b):
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

#include <array>
#include <span>
#include <vector>

#include "constraints/wall_features.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"

namespace hotmesh::deform::detail {

struct BoundarySetup;  // boundary_conditions.hpp

/// A node on a sliding boundary (section 4): u = u0s + us (eq. 13), u0s the forcing
/// displacement of the increment, us tangential to the deformed boundary.
struct SlidingNode {
  static constexpr int kMaxShapes = 3;
  NodeId node = 0;
  std::array<const geometry::BoundaryShape*, kMaxShapes> shapes{};
  int shape_count = 0;
  std::array<geometry::ShapeParameter, kMaxShapes> hints{};  ///< parameter of the last projection on each shape
  std::array<int, 2> planes{};             ///< indices into BoundarySetup::slip_planes
  int plane_count = 0;
  Vec3 target;  ///< x_F: where the node is to end on the fully deflected boundary (section 4.3)
  geometry::ShapeParameter origin;  ///< t0: its material parameter on shapes[0] (SlidingOrigin)
  /// The part of each shape it slides on: between the corners on either side of it.
  std::array<geometry::ParameterRange, kMaxShapes> segments{};
};

/// Where a sliding node at p lands on its boundary at stage lambda (Fig. 4): projected on
/// each of its shapes and planes in turn (repeatedly where several meet). Updates the hints
/// and writes the normals of its shapes and planes (the directions it may not move in).
struct Placement {
  Vec3 point;
  std::array<Vec3, SlidingNode::kMaxShapes + 2> normals{};
  int normal_count = 0;
};
Placement place_sliding_node(SlidingNode& node, const Vec3& p, double lambda, std::span<const SlipPlane> planes);

/// Moves the nodes of the passive surfaces that follow sliding rims to the spring solution
/// for their rims as they stand at x + u (u the displacements of the increment from x; the
/// surfaces' displacements are measured from setup.reference).
void follow_sliding_rims(const BoundarySetup& setup, std::span<const Vec3> x, std::span<double> u);

class SlidingNodes {
 public:
  /// The nodes are projected in shares by the ranks of `ranks`, every rank getting them all.
  SlidingNodes(BoundarySetup& setup, std::size_t dofs_per_node, const parallel::RankExchange& ranks)
      : setup_(setup), dim_(dofs_per_node), ranks_(ranks) {}

  std::size_t size() const;

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
  /// Places this rank's share of the sliding nodes on stage b's wall, each from the point
  /// `from(k, start)` gives (start: its undeformed position), sets their displacements and
  /// normals, shares them and follows the rims; the farthest a node was moved onto the wall.
  template <class From>
  double place_all(double b, std::span<const Vec3> x, std::span<double> u, const From& from);
  void share_targets();

  BoundarySetup& setup_;
  std::size_t dim_;
  const parallel::RankExchange& ranks_;
  std::vector<Vec3> forcing_;       ///< dx1 = u0s of the current increment, per sliding node
  std::vector<PlacedNode> placed_;  ///< per sliding node (several processes only)
};

}  // namespace hotmesh::deform::detail
