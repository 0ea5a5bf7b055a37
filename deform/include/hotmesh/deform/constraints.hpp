// hotmesh deform: the directions in which boundary nodes may not move during a linear solve.
// A node can be fixed (all directions: fixed and prescribed nodes), or constrained along up
// to d-1 orthonormal normals: one for a slip node (u . n = 0, eq. 11) or a sliding node
// (eqs. 16-19, normal of the deformed surface), two where two such surfaces meet (the node
// moves along their intersection). project() removes the constrained components of a vector:
// the operator, the preconditioner and the residual all go through it, so PCG iterates
// started from zero stay in the admissible subspace.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform {

class NodeConstraints {
 public:
  NodeConstraints(std::size_t nodes, int dimension);

  void fix(NodeId n);
  /// Adds the direction `normal` (any length) to the node's constrained directions,
  /// orthonormalised against those it has; a node constrained in d directions is fixed.
  /// Directions (nearly) parallel to existing ones add nothing.
  void constrain(NodeId n, const Vec3& normal);
  /// Removes every direction of a node that is not fixed (before setting new normals).
  void release(NodeId n);
  /// Prepares node n for set_normals (call once, single-threaded, before any parallel use).
  void track(NodeId n);
  /// Replaces the directions of a tracked node by `normals` (orthonormalised; at most d - 1 are
  /// kept, so the node is never fixed here). Does nothing for fixed nodes. Safe to call from
  /// several threads for different nodes.
  void set_normals(NodeId n, std::span<const Vec3> normals);

  bool is_fixed(NodeId n) const { return state_[static_cast<std::size_t>(n)] == kFixed; }
  /// Number of constrained directions of node n (d if fixed).
  int constrained_directions(NodeId n) const;
  std::span<const Vec3> normals(NodeId n) const;

  /// v <- P v: zero at fixed nodes, constrained normal components removed elsewhere.
  void project(std::span<double> v) const;
  /// Number of free scalar unknowns (total dofs minus constrained directions).
  std::size_t free_dofs() const;
  int dimension() const { return dim_; }
  std::size_t node_count() const { return state_.size(); }

 private:
  static constexpr std::int32_t kFree = -1;
  static constexpr std::int32_t kFixed = -2;
  struct Partial {
    NodeId node = 0;
    int count = 0;
    std::array<Vec3, 2> normals{};
  };
  int dim_;
  std::vector<std::int32_t> state_;  ///< kFree, kFixed, or an index into partial_
  std::vector<NodeId> fixed_;
  std::vector<Partial> partial_;
};

}  // namespace hotmesh::deform
