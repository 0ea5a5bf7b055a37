// hotmesh deform: boundary roles to node constraints (boundary_conditions.hpp): the set-up's
// phases in order (their work by role in the files boundary_builder.hpp names); here each
// patch's motion, periodic pairs, each node's strongest role, and the checks of the whole.
#include "constraints/boundary_conditions.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "constraints/boundary_builder.hpp"
#include "constraints/rigid_modes.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform::detail {

namespace {

/// Throws FreeRigidMotion if the constraints of the set-up, as they stand at its start, leave
/// a rigid-body motion free (rigid_modes.hpp). Nodes of passive surfaces that follow sliding
/// rims hold nothing themselves: they move as their rim does.
void refuse_free_rigid_motions(const Mesh& mesh, const BoundarySetup& setup, const std::vector<char>& follows_sliding) {
  RigidModes modes(mesh);
  const std::span<const Vec3> x0 = setup.reference;
  const NodeConstraints& c = setup.constraints;
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    const auto node = static_cast<NodeId>(n);
    if (setup.periodic.is_slave(node) || follows_sliding[n]) continue;
    if (c.is_fixed(node)) {
      modes.fix(x0[n]);
    } else {
      for (const Vec3& normal : c.normals(node)) modes.constrain(x0[n], normal);  // slip nodes
    }
  }
  for (const SlidingNode& s : setup.sliding) {  // their normals are set per increment: those at the start
    const Vec3& x = x0[static_cast<std::size_t>(s.node)];
    if (c.is_fixed(s.node)) {
      modes.fix(x);  // walls meeting in a point: it goes where they meet
      continue;
    }
    for (int i = 0; i < s.shape_count; ++i) {
      const auto j = static_cast<std::size_t>(i);
      modes.constrain(x, s.shapes[j]->at(s.hints[j], 0.0, x).normal);
    }
    for (int k = 0; k < s.plane_count; ++k) {
      modes.constrain(x, setup.slip_planes[static_cast<std::size_t>(s.planes[static_cast<std::size_t>(k)])].normal);
    }
  }
  for (const PeriodicPair& p : setup.periodic.pairs()) {
    modes.tie(x0[static_cast<std::size_t>(p.slave)], x0[static_cast<std::size_t>(p.master)], setup.periodic.rotation(p.rotation));
  }
  const std::vector<std::string> free = modes.free_motions();
  if (free.empty()) return;
  throw FreeRigidMotion(fmt::format(
      "the patch roles leave the mesh free to move as a rigid body: it can {}. No fixed or prescribed node, slip "
      "plane, sliding wall or periodic pair resists that motion, so the mesh's position is not determined; give "
      "a patch the role fixed or prescribed, or slip or sliding on a wall that the motion would cross",
      fmt::join(free, ", and it can ")));
}

}  // namespace

/// Parameters of `nodes` on the undeformed shape (stage 0); throws if any is farther from it
/// than 1e-3 times the diagonal of the patch's bounding box, listing them.
Located locate(const Mesh& mesh, std::span<const Vec3> points, const Patch& patch, const PatchMotion& m,
               std::span<const NodeId> nodes) {
  const double tolerance = 1e-3 * bounding_diagonal(mesh.points, patch.nodes);
  std::vector<geometry::ShapePoint> found(nodes.size());
  mesh::LoopExceptions errors;  // the projections run behind geometry's BoundaryShape interface
#pragma omp parallel for schedule(dynamic, 64) if (static_cast<std::ptrdiff_t>(nodes.size()) >= mesh::kParallelProjections)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(nodes.size()); ++i) {
    errors.run([&] {
      const auto k = static_cast<std::size_t>(i);
      found[k] = m.shape->project(points[static_cast<std::size_t>(nodes[k])], 0.0);
    });
  }
  errors.rethrow();
  std::size_t off = 0;
  std::string examples;
  Located located{std::vector<geometry::ShapeParameter>(nodes.size()), {patch.name, 0.0, -1}};
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    located.parameters[k] = found[k].parameter;
    if (found[k].distance > located.gap.distance || located.gap.node < 0) located.gap = {patch.name, found[k].distance, nodes[k]};
    if (found[k].distance > tolerance || !std::isfinite(found[k].distance)) {
      if (off++ < 5) {
        const Vec3& x = points[static_cast<std::size_t>(nodes[k])];
        examples += fmt::format("\n  node {} at ({:.6g}, {:.6g}, {:.6g}) is {:.3g} away", mesh.node_id(nodes[k]), x.x, x.y,
                                x.z, found[k].distance);
      }
    }
  }
  if (off > 0) {
    throw InputError(fmt::format("patch '{}': {} nodes lie farther than {:.3g} from the undeformed shape of the patch "
                                 "({}):{}\nCheck that the deflection table or CAD faces describe this patch (same "
                                 "units, same axis).",
                                 patch.name, off, tolerance, to_string(m.role), examples));
  }
  return located;
}

BoundaryBuilder::BoundaryBuilder(const Mesh& mesh, std::span<const PatchMotion> patches, const MotionStart* start)
    : mesh_(mesh),
      patches_(patches),
      start_(start),
      setup_{start ? std::span<const Vec3>(start->points) : std::span<const Vec3>(mesh.points),
             NodeConstraints(mesh.node_count(), mesh.dimension),
             {},
             {},
             {},
             {},
             {},
             PeriodicCoupling(static_cast<std::size_t>(mesh.dimension)),
             {},
             {},
             {},
             std::vector<NodeRoleCode>(mesh.node_count(), 0),
             {}},
      x0_(setup_.reference),
      motion_of_(mesh.patches.size(), nullptr),
      owner_(mesh.node_count(), -1),
      plane_of_(mesh.patches.size(), -1),
      sliding_index_(mesh.node_count(), -1),
      rim_(mesh.node_count()),
      follows_sliding_(mesh.node_count(), 0),
      holds_(mesh.node_count(), 0) {
  if (setup_.reference.size() != mesh.node_count()) {
    throw InputError(fmt::format("the state to restart from has {} nodes, the mesh {}", setup_.reference.size(),
                                 mesh.node_count()));
  }
}

/// Each mesh patch's motion; every patch has one, and those that move have a shape.
void BoundaryBuilder::assign_motions() {
  for (const PatchMotion& m : patches_) {
    motion_of_[patch_index(m.patch)] = &m;
    if (follows_shape(m.role) && !m.shape) {
      throw InputError(fmt::format("patch '{}' is {} but has no shape to follow", m.patch, to_string(m.role)));
    }
  }
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    if (!motion_of_[p]) throw InputError(fmt::format("mesh patch '{}' has no role", mesh_.patches[p].name));
  }
}

/// Periodic pairs: slaves follow their masters and take no role of their own.
void BoundaryBuilder::couple_periodic_pairs() {
  const double mesh_size = bounding_diagonal(mesh_.points);
  for (const PatchMotion& m : patches_) {
    if (m.role != BoundaryRole::periodic || m.partner.empty()) continue;
    const std::size_t partner = patch_index(m.partner);
    if (motion_of_[partner]->role != BoundaryRole::periodic) {
      throw InputError(fmt::format("periodic patch '{}' has partner '{}', which is not periodic", m.patch, m.partner));
    }
    setup_.periodic.add(mesh_, mesh_.patches[patch_index(m.patch)], mesh_.patches[partner], m.axis, m.angle,
                        1e-8 * mesh_size);
  }
  for (const PatchMotion& m : patches_) {
    if (m.role != BoundaryRole::periodic || !m.partner.empty()) continue;
    const bool declared =
        std::any_of(patches_.begin(), patches_.end(), [&](const PatchMotion& o) { return o.partner == m.patch; });
    if (!declared) throw InputError(fmt::format("periodic patch '{}' has no partner", m.patch));
  }
}

/// The strongest role of each node, and the patch that gives it.
void BoundaryBuilder::assign_node_roles() {
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    for (NodeId n : mesh_.patches[p].nodes) {
      if (role_strength(motion_of_[p]->role) > role_priority(n)) owner_[static_cast<std::size_t>(n)] = static_cast<int>(p);
    }
  }
  for (std::size_t n = 0; n < mesh_.node_count(); ++n) {
    if (is_slave(static_cast<NodeId>(n))) {
      setup_.roles[n] = node_role_code(BoundaryRole::periodic);
      setup_.constraints.fix(static_cast<NodeId>(n));  // not an unknown: it follows its master
    } else if (owner_[n] >= 0) {
      setup_.roles[n] = node_role_code(motion_of_[static_cast<std::size_t>(owner_[n])]->role);
    }
  }
}

/// Where a stronger role overrules a patch's deflection at shared nodes (a fixed wall beside
/// a moving one), say so if the two disagree about where the node goes.
void BoundaryBuilder::note_overruled_deflections() {
  const auto final_position = [&](const PatchMotion& m, NodeId n) {
    const Vec3& x = x0_[static_cast<std::size_t>(n)];
    if (m.role == BoundaryRole::fixed || !m.shape) return x;
    return prescribed_position({n, m.shape->project(x, 0.0).parameter, m.shape.get()}, x, 1.0);
  };
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    const PatchMotion& m = *motion_of_[p];
    if (!follows_shape(m.role)) continue;
    std::size_t overruled = 0;
    double largest = 0.0;
    const double tolerance = 1e-6 * bounding_diagonal(mesh_.points, mesh_.patches[p].nodes);
    for (NodeId n : mesh_.patches[p].nodes) {
      if (is_slave(n) || role_priority(n) <= role_strength(m.role)) continue;
      const PatchMotion& winner = *motion_of_[static_cast<std::size_t>(owner_[static_cast<std::size_t>(n)])];
      const double gap = distance(final_position(m, n), final_position(winner, n));
      if (gap > tolerance) {
        ++overruled;
        largest = std::max(largest, gap);
      }
    }
    if (overruled > 0) {
      setup_.notes.push_back(fmt::format("patch '{}': {} nodes shared with fixed or prescribed patches follow those, "
                                         "{:.3g} away at most from where this patch's deflection would take them",
                                         mesh_.patches[p].name, overruled, largest));
    }
  }
}

/// The set-up, once every rigid-body motion is held (refuse_free_rigid_motions).
BoundarySetup BoundaryBuilder::finish() {
  refuse_free_rigid_motions(mesh_, setup_, follows_sliding_);
  return std::move(setup_);
}

std::size_t BoundaryBuilder::patch_index(const std::string& name) const {
  const auto it =
      std::find_if(mesh_.patches.begin(), mesh_.patches.end(), [&](const Patch& p) { return p.name == name; });
  if (it == mesh_.patches.end()) throw InputError(fmt::format("the mesh has no patch '{}'", name));
  return static_cast<std::size_t>(it - mesh_.patches.begin());
}

BoundarySetup set_up_boundaries(const Mesh& mesh, std::span<const PatchMotion> patches, const MotionStart* start) {
  BoundaryBuilder builder(mesh, patches, start);
  builder.assign_motions();
  builder.couple_periodic_pairs();
  builder.assign_node_roles();
  builder.constrain_slip_nodes();
  builder.constrain_fixed_and_prescribed_nodes();
  builder.collect_sliding_nodes();
  builder.slide_along_creases();
  builder.hold_sliding_rims_on_passive_surfaces();
  builder.hold_corners_on_nodes();
  builder.hold_wall_corners();
  builder.set_sliding_targets();
  builder.solve_passive_surfaces();
  builder.note_overruled_deflections();
  return builder.finish();
}

}  // namespace hotmesh::deform::detail
