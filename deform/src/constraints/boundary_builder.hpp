// hotmesh deform (internal, constraints/ only): set_up_boundaries phase by phase
// (boundary_conditions.hpp). Each phase reads what the ones before it decided; the phases of
// one role are in that role's file:
//   boundary_conditions.cpp  patch motions, periodic pairs, node roles, overruled deflections, the checks at the end
//   prescribed.cpp           fixed and prescribed nodes
//   slip.cpp                 slip planes
//   sliding_setup.cpp        sliding nodes: their shapes, planes, creases and targets
//   passive_setup.cpp        passive surfaces, and the sliding nodes on their rims
//   corner_setup.cpp         the corners of sliding walls given to their nodes (wall_features.hpp)
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "constraints/boundary_conditions.hpp"
#include "constraints/wall_features.hpp"
#include "hotmesh/deform/mesh_motion.hpp"

namespace hotmesh::deform::detail {

/// Where `nodes` lie on the undeformed shape (stage 0), and the farthest of them from it.
struct Located {
  std::vector<geometry::ShapeParameter> parameters;
  WallGap gap;
};

/// Parameters of `nodes` on the undeformed shape (stage 0); throws if any is farther from it
/// than 1e-3 times the diagonal of the patch's bounding box, listing them (boundary_conditions.cpp).
Located locate(const Mesh& mesh, std::span<const Vec3> points, const Patch& patch, const PatchMotion& m,
               std::span<const NodeId> nodes);

class BoundaryBuilder {
 public:
  BoundaryBuilder(const Mesh& mesh, std::span<const PatchMotion> patches, const MotionStart* start);

  // The phases, in the order set_up_boundaries runs them.
  void assign_motions();                           // boundary_conditions.cpp
  void couple_periodic_pairs();                    // boundary_conditions.cpp
  void assign_node_roles();                        // boundary_conditions.cpp
  void constrain_slip_nodes();                     // slip.cpp
  void constrain_fixed_and_prescribed_nodes();     // prescribed.cpp
  void collect_sliding_nodes();                    // sliding_setup.cpp
  void slide_along_creases();                      // sliding_setup.cpp
  void hold_sliding_rims_on_passive_surfaces();    // passive_setup.cpp
  void hold_corners_on_nodes();                    // corner_setup.cpp
  void hold_wall_corners();                        // corner_setup.cpp
  void set_sliding_targets();                      // sliding_setup.cpp
  void solve_passive_surfaces();                   // passive_setup.cpp
  void note_overruled_deflections();               // boundary_conditions.cpp
  BoundarySetup finish();                          // boundary_conditions.cpp

 private:
  // sliding_setup.cpp
  void note_crease(std::map<std::pair<std::string, std::vector<int>>, std::size_t>& crease_of, const std::string& patch,
                   NodeId n, const std::vector<std::shared_ptr<const geometry::BoundaryShape>>& sides);
  const PatchMotion* sliding_motion_of(const geometry::BoundaryShape* shape) const;

  // corner_setup.cpp
  /// How a node holds a corner (give_corners).
  static constexpr char kPrescribedOntoCorner = 1;
  static constexpr char kSlidesAlongCorner = 2;
  void follow_corner_line(NodeId n, const geometry::BoundaryShape& wall, const CornerLine& line);
  bool can_hold_corner(NodeId n, const Vec3& q, double on_plane) const;
  std::vector<SlipPlane> planes_of(NodeId n) const;
  void give_corners(WallFeaturePlan& plan, const PatchMotion& m, const Patch& patch);
  void note_crease_given_nodes(const std::string& patch, const geometry::BoundaryShape& wall, const HeldFeature& held);
  void drop_nodes_prescribed_onto_corners();

  std::size_t patch_index(const std::string& name) const;
  bool is_slave(NodeId n) const { return setup_.periodic.is_slave(n); }
  int role_priority(NodeId n) const {
    const int o = owner_[static_cast<std::size_t>(n)];
    return o < 0 ? 0 : role_strength(motion_of_[static_cast<std::size_t>(o)]->role);
  }
  bool has_role(NodeId n, BoundaryRole role) const { return !is_slave(n) && role_priority(n) == role_strength(role); }

  const Mesh& mesh_;
  std::span<const PatchMotion> patches_;
  const MotionStart* start_;
  BoundarySetup setup_;
  const std::span<const Vec3> x0_;               ///< setup_.reference
  std::vector<const PatchMotion*> motion_of_;    ///< per mesh patch
  std::vector<int> owner_;                       ///< per node: the patch of its strongest role, or -1
  std::vector<int> plane_of_;                    ///< per mesh patch: its slip plane, or -1
  std::vector<int> sliding_index_;               ///< per node: its index in setup_.sliding, or -1
  std::vector<std::optional<Vec3>> rim_;         ///< per node: its displacement where known
  std::vector<char> follows_sliding_;            ///< per node: moves with a sliding node
  std::vector<char> holds_;                      ///< per node: how it holds a corner, or 0
};

}  // namespace hotmesh::deform::detail
