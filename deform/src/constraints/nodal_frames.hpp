// hotmesh deform (internal): the constraints of the linear solve as nodal frames, so that the
// assembled system is symmetric positive definite with d unknowns per node (docs/method.md,
// "Constraints in nodal frames"). Every node n has an orthonormal frame Q_n (columns):
//  - a sliding or slip node: its constrained normals first, then tangents completing the basis;
//  - a fixed (or prescribed, passive) node: the Cartesian axes, all of them constrained;
//  - a free node: the Cartesian axes;
//  - a periodic slave s of master m: Q_s = R Q_m, and its motion is written in the master's
//    unknowns. Since u_s = R u_m, the slave's components in R Q_m equal the master's in Q_m:
//    master and slave share their degrees of freedom (for a free master these are Cartesian
//    components; cylindrical ones about the axis are turned by R the same way).
// With T the map from frame unknowns p~ to Cartesian displacements (u_n = Q_n p~_owner(n)),
// the assembled matrix is K~ = T^T K T with the rows and columns of constrained components
// cleared except their diagonal, element by element:
//     K~_e = T_e^T K_e T_e,    (K~_e)_ab = Q_a^T K_e,ab Q_b,
// scattered to the blocks of the owners (a slave's master). A constrained component then
// keeps only its own stiffness on the diagonal, and a slave's own row only the diagonal of
// its frame block: both get p~ = 0 from a zero right-hand side. On the free components K~
// equals the projected operator P T^T K T P of Jacobi-PCG (eq. 16) written in the
// frames; the right-hand side is r~ = T^T r, the solution p = T p~.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "constraints/periodic.hpp"
#include "hotmesh/deform/constraints.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform::detail {

class NodalFrames {
 public:
  NodalFrames(std::size_t nodes, int dimension);

  /// Frames from the constraints' current normals (sliding nodes change them every Newton
  /// step) and the periodic pairs.
  void update(const NodeConstraints& constraints, const PeriodicCoupling& periodic);

  int dimension() const { return dim_; }
  std::size_t node_count() const { return owner_.size(); }
  /// The node whose unknowns carry n's motion: its master for a periodic slave, else n.
  NodeId owner(NodeId n) const { return owner_[static_cast<std::size_t>(n)]; }
  bool is_slave(NodeId n) const { return owner(n) != n; }
  /// Leading components of the owner's unknowns that are constrained (d for fixed nodes).
  int constrained(NodeId n) const { return constrained_[static_cast<std::size_t>(owner(n))]; }
  /// Q_n, d x d row-major; its columns are the frame's directions.
  std::span<const double> frame(NodeId n) const;

  /// K~_e of the cell with these corners from its K_e (both row-major, (d corners)^2): the
  /// corner blocks turned into the frames, constrained rows and columns cleared but for the
  /// diagonal. Writes the owner of every corner to `blocks` (the block rows and columns).
  void transform_element(std::span<const NodeId> nodes, std::span<const double> ke, std::span<double> out,
                         std::span<std::int32_t> blocks) const;
  /// r~ = T^T r for a vector already folded onto the masters: r~_n = Q_n^T r_n at every node
  /// but slaves, zero on constrained components and at slaves. This and from_frames may write
  /// over their input (out the same vector).
  void to_frames(std::span<const double> r, std::span<double> out) const;
  /// p = T p~ restricted to the unknowns: p_n = Q_n p~_n with constrained components of p~
  /// dropped, and p = 0 at slaves (the Newton loop expands slaves from their masters).
  void from_frames(std::span<const double> p, std::span<double> out) const;

 private:
  /// Q_n^T v_n (into the frames) or Q_n v_n (out of them) on the unconstrained components.
  void turn(std::span<const double> v, std::span<double> out, bool into_frames) const;

  /// Q_n, row-major: the identity for a Cartesian node.
  const double* q(std::size_t n) const {
    if (slot_[n] >= 0) return frames_.data() + static_cast<std::size_t>(slot_[n]) * static_cast<std::size_t>(dim_ * dim_);
    return dim_ == 2 ? kIdentity2.data() : kIdentity3.data();
  }

  static constexpr std::array<double, 4> kIdentity2{1.0, 0.0, 0.0, 1.0};
  static constexpr std::array<double, 9> kIdentity3{1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};

  int dim_;
  std::vector<NodeId> owner_;
  std::vector<std::int8_t> constrained_;
  /// Where Q_n is in frames_, -1 for Q_n = I: most nodes (free or fixed) need no rotation, and
  /// storing theirs would take 72 bytes a node (200 MB a process at the paper's 2.9 million nodes).
  std::vector<std::int32_t> slot_;
  std::vector<double> frames_;   ///< Q_n of the rotated nodes (sliding, slip, periodic slaves), row-major
};

}  // namespace hotmesh::deform::detail
