// hotmesh deform (internal): passive surfaces (the paper's section 6.1). The interior nodes of
// a passive surface get their displacements from a linear spring analogy on the surface mesh
// alone — springs along the faces' edges, stiffness 1/length — driven by the displacements of
// the surface's rim (its nodes on fixed, prescribed or sliding walls, or on passive surfaces
// solved before it). In the volume solve they then act as prescribed. Periodic pairs inside
// the surface are tied (u_s = R u_m), so a passive surface across a periodic sector stays
// periodic.
//
// The springs and the factorisation are built once; solve() takes the rim's displacements as
// they stand, so a surface whose rim slides is solved again after every move of its rim.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "constraints/periodic.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform::detail {

/// Displacement of a rim node (a node of the surface whose motion is known), or nothing for
/// a node the surface solve decides.
using RimDisplacement = std::function<std::optional<Vec3>(NodeId)>;

class PassiveSurface {
 public:
  /// Sets up the spring analogy on `patch` at the node positions `points`; `rim` says which
  /// nodes are known (its values are not kept). Throws InputError if a part of the surface has
  /// no rim (nothing drives it).
  PassiveSurface(const Mesh& mesh, std::span<const Vec3> points, const Patch& patch, const RimDisplacement& rim,
                 const PeriodicCoupling& periodic);

  /// The displacement of every node of patch.nodes (in that order) for the rim displacements
  /// `rim`, which must know every node it knew at set-up (rim nodes keep theirs).
  std::vector<Vec3> solve(const RimDisplacement& rim) const;

  /// The nodes whose displacements the surface takes from outside (its rim, and the masters
  /// of its periodic slaves).
  std::span<const NodeId> rim_nodes() const { return rim_nodes_; }

 private:
  struct Spring {
    std::size_t a = 0, b = 0;  ///< local node indices
    double stiffness = 0.0;
  };
  struct Tie {
    std::size_t slave = 0;  ///< local index of a periodic slave known through its master
    NodeId master = 0;
    std::int64_t local_master = -1;  ///< its local index if it is a node of the surface
    std::size_t rotation = 0;  ///< index into rotations_
  };
  /// Node index -> local index (position in nodes_).
  using LocalIndex = std::unordered_map<NodeId, std::size_t>;

  /// The phases of the set-up: which nodes are known (rim, tied periodic slaves) and which
  /// are unknowns; the springs; the check that the rim reaches every node; the factors.
  void classify_nodes(const RimDisplacement& rim, const PeriodicCoupling& periodic, const LocalIndex& local);
  void build_springs(const Patch& patch, std::span<const Vec3> points, const LocalIndex& local);
  void require_every_node_driven(const Mesh& mesh) const;
  void factorise();

  /// u_i = T_i U (the unknown of node i, or of its master turned by R), or -1 for known nodes.
  std::pair<std::int64_t, const Rotation*> owner(std::size_t i) const;

  std::string name_;
  std::size_t dim_ = 3;
  std::vector<NodeId> nodes_;
  std::vector<Rotation> rotations_;     ///< those of the periodic pairs it ties
  static constexpr char kFromRim = 1;  ///< known_: the rim gives its displacement
  static constexpr char kTied = 2;     ///< known_: a periodic slave, from its master on the rim
  std::vector<char> known_;            ///< per local node: 0 (solved for), kFromRim or kTied
  std::vector<Tie> ties_;                   ///< known slaves, from their masters
  std::vector<std::int64_t> master_of_;     ///< per local node: local master of an unknown slave, or -1
  std::vector<std::size_t> rotation_of_;  ///< index into rotations_
  std::vector<std::int64_t> unknown_;       ///< per local node: index of its unknown, or -1
  std::size_t unknowns_ = 0;
  std::vector<Spring> springs_;
  std::vector<NodeId> rim_nodes_;
  struct Factorisation;  ///< the sparse Cholesky factors of the springs' matrix (passive.cpp)
  std::shared_ptr<const Factorisation> factors_;
};

}  // namespace hotmesh::deform::detail
