// hotmesh deform (internal): rotational periodicity. The nodes of a periodic face (master)
// and of its partner (slave) are paired by rotating the master face through the sector angle
// about the axis; the slave then follows its master everywhere: u_slave = R u_master.
// Slaves are not unknowns: displacement vectors are expanded (u_s = R u_m) before the stiffness
// is applied, forces are folded back (f_m += R^T f_s, f_s = 0) after it, so the operator is
// T^T K T, symmetric on the masters, and the preconditioner's diagonal blocks fold the same way.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/deform/mesh_names.hpp"
#include "hotmesh/geometry/axis.hpp"

namespace hotmesh::deform::detail {

/// A rotation by `angle` (radians, right-handed) about an axis.
class Rotation {
 public:
  Rotation(const geometry::Axis& axis, double angle);
  Vec3 vector(const Vec3& v) const;          ///< R v
  Vec3 inverse_vector(const Vec3& v) const;  ///< R^T v
  Vec3 point(const Vec3& p) const { return origin_ + vector(p - origin_); }
  double entry(std::size_t i, std::size_t j) const { return r_[i][j]; }

 private:
  Vec3 origin_;
  std::array<std::array<double, 3>, 3> r_{};
};

struct PeriodicPair {
  NodeId master = 0;
  NodeId slave = 0;
  std::size_t rotation = 0;  ///< index into PeriodicCoupling's rotations
};

class PeriodicCoupling {
 public:
  explicit PeriodicCoupling(std::size_t dofs_per_node = 3) : dim_(dofs_per_node) {}

  /// Pairs the nodes of `master` with those of `slave` (x_slave = R x_master). Throws
  /// hotmesh::InputError listing the nodes without a partner within `tolerance`.
  void add(const Mesh& mesh, const Patch& master, const Patch& slave, const geometry::Axis& axis, double angle,
           double tolerance);

  bool empty() const { return pairs_.empty(); }
  std::span<const PeriodicPair> pairs() const { return pairs_; }
  const Rotation& rotation(std::size_t i) const { return rotations_[i]; }
  bool is_slave(NodeId n) const { return !slave_of_.empty() && slave_of_[static_cast<std::size_t>(n)] >= 0; }
  /// The master a slave node follows; -1 for other nodes.
  NodeId master_of(NodeId n) const {
    return is_slave(n) ? pairs_[static_cast<std::size_t>(slave_of_[static_cast<std::size_t>(n)])].master : NodeId{-1};
  }

  void expand(std::span<double> u) const;         ///< u_s = R u_m
  void fold(std::span<double> f) const;           ///< f_m += R^T f_s, f_s = 0
  void fold_blocks(std::span<double> blocks) const;  ///< B_m += R^T B_s R, B_s = 0
  void fold_nodal(std::span<double> values) const;   ///< v_m += v_s, v_s = 0 (one rotation-invariant value per node)
  /// Largest distance between a rotated master position and its slave.
  double mismatch(std::span<const Vec3> points) const;

 private:
  std::size_t dim_;
  std::vector<Rotation> rotations_;
  std::vector<PeriodicPair> pairs_;
  std::vector<std::int32_t> slave_of_;  ///< per node: index of its pair if it is a slave, else -1
};

}  // namespace hotmesh::deform::detail
