// hotmesh deform: boundary roles to node constraints, prescribed motions and sliding nodes.
#include "boundary_conditions.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hotmesh/geometry/input_error.hpp"
#include "parallel.hpp"
#include "passive.hpp"

namespace hotmesh::deform::detail {
namespace {

int priority(BoundaryRole role) {
  switch (role) {
    case BoundaryRole::fixed: return 6;
    case BoundaryRole::prescribed: return 5;
    case BoundaryRole::sliding: return 4;
    case BoundaryRole::passive: return 3;
    case BoundaryRole::slip: return 2;
    case BoundaryRole::periodic: return 1;
  }
  return 0;
}

/// Best-fit plane (line in 2D) of a slip patch; throws if the patch is not planar.
SlipPlane slip_plane(const Mesh& mesh, const Patch& patch) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (NodeId n : patch.nodes) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    centre += Eigen::Vector3d(p.x, p.y, p.z);
  }
  centre /= static_cast<double>(patch.nodes.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (NodeId n : patch.nodes) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    const Eigen::Vector3d r = Eigen::Vector3d(p.x, p.y, p.z) - centre;
    covariance += r * r.transpose();
  }
  Vec3 normal;
  if (mesh.dimension == 2) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance.topLeftCorner<2, 2>());
    normal = {eigen.eigenvectors()(0, 0), eigen.eigenvectors()(1, 0), 0.0};
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    normal = {eigen.eigenvectors()(0, 0), eigen.eigenvectors()(1, 0), eigen.eigenvectors()(2, 0)};
  }
  const Vec3 origin{centre.x(), centre.y(), centre.z()};
  double worst = 0.0;
  for (NodeId n : patch.nodes) worst = std::max(worst, std::abs(dot(mesh.points[static_cast<std::size_t>(n)] - origin, normal)));
  const double size = bounding_diagonal(mesh.points, patch.nodes);
  if (worst > 1e-6 * size) {
    throw InputError(fmt::format("patch '{}' has role slip but is not planar: a node is {:.3g} off its best-fit {} "
                                 "(patch size {:.3g}); slip keeps nodes on a plane, use sliding for curved walls",
                                 patch.name, worst, mesh.dimension == 2 ? "line" : "plane", size));
  }
  return {origin, normal / norm(normal)};
}

/// Parameters of `nodes` on the undeformed shape (stage 0); throws if any is farther than the
/// tolerance, listing them.
std::vector<double> locate(const Mesh& mesh, std::span<const Vec3> points, const Patch& patch, const PatchMotion& m,
                           std::span<const NodeId> nodes) {
  const double tolerance = m.tolerance > 0.0 ? m.tolerance : 1e-3 * bounding_diagonal(mesh.points, patch.nodes);
  std::vector<geometry::ShapePoint> found(nodes.size());
  LoopExceptions errors;  // the projections run behind geometry's BoundaryShape interface
#pragma omp parallel for schedule(dynamic, 64) if (static_cast<std::ptrdiff_t>(nodes.size()) >= kParallelProjections)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(nodes.size()); ++i) {
    errors.run([&] {
      const auto k = static_cast<std::size_t>(i);
      found[k] = m.shape->project(points[static_cast<std::size_t>(nodes[k])], 0.0);
    });
  }
  errors.rethrow();
  std::size_t off = 0;
  std::string examples;
  std::vector<double> parameters(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    parameters[k] = found[k].parameter;
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
  return parameters;
}

}  // namespace

Vec3 prescribed_position(const PrescribedNode& p, const Vec3& original, double lambda) {
  const Vec3 moved = p.shape->at(p.parameter, lambda, original).point;
  const Vec3 start = p.shape->at(p.parameter, 0.0, original).point;
  return original + (moved - start);
}

Placement place_sliding_node(SlidingNode& node, const Vec3& p, double lambda, std::span<const SlipPlane> planes) {
  Placement out;
  out.point = p;
  // One pass for a single wall; where walls meet, alternate projections converge on their
  // intersection (for walls that are not tangent there).
  const int passes = node.shape_count + node.plane_count > 1 ? 8 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    out.normal_count = 0;
    for (int s = 0; s < node.shape_count; ++s) {
      const auto i = static_cast<std::size_t>(s);
      const geometry::ShapePoint q = node.shapes[i]->project(out.point, lambda, node.hints[i]);
      node.hints[i] = q.parameter;
      out.point = q.point;
      out.normals[static_cast<std::size_t>(out.normal_count++)] = q.normal;
    }
    for (int k = 0; k < node.plane_count; ++k) {
      const SlipPlane& plane = planes[static_cast<std::size_t>(node.planes[static_cast<std::size_t>(k)])];
      out.point -= dot(out.point - plane.origin, plane.normal) * plane.normal;
      out.normals[static_cast<std::size_t>(out.normal_count++)] = plane.normal;
    }
  }
  return out;
}

BoundarySetup set_up_boundaries(const Mesh& mesh, std::span<const PatchMotion> patches, const MotionStart* start) {
  BoundarySetup setup{start ? start->points : mesh.points,
                      NodeConstraints(mesh.node_count(), mesh.dimension),
                      {},
                      {},
                      {},
                      {},
                      PeriodicCoupling(static_cast<std::size_t>(mesh.dimension)),
                      std::vector<NodeRoleCode>(mesh.node_count(), 0),
                      {}};
  if (setup.reference.size() != mesh.node_count()) {
    throw InputError(fmt::format("the state to restart from has {} nodes, the mesh {}", setup.reference.size(),
                                 mesh.node_count()));
  }
  const std::vector<Vec3>& x0 = setup.reference;

  std::vector<const PatchMotion*> motion_of(mesh.patches.size(), nullptr);
  const auto patch_index = [&](const std::string& name) {
    const auto it = std::find_if(mesh.patches.begin(), mesh.patches.end(), [&](const Patch& p) { return p.name == name; });
    if (it == mesh.patches.end()) throw InputError(fmt::format("the mesh has no patch '{}'", name));
    return static_cast<std::size_t>(it - mesh.patches.begin());
  };
  for (const PatchMotion& m : patches) {
    motion_of[patch_index(m.patch)] = &m;
    if ((m.role == BoundaryRole::prescribed || m.role == BoundaryRole::sliding) && !m.shape) {
      throw InputError(fmt::format("patch '{}' is {} but has no shape to follow", m.patch, to_string(m.role)));
    }
  }
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    if (!motion_of[p]) throw InputError(fmt::format("mesh patch '{}' has no role", mesh.patches[p].name));
  }

  // Periodic pairs: slaves follow their masters and take no role of their own.
  const double mesh_size = bounding_diagonal(mesh.points);
  for (const PatchMotion& m : patches) {
    if (m.role != BoundaryRole::periodic || m.partner.empty()) continue;
    const std::size_t partner = patch_index(m.partner);
    if (motion_of[partner]->role != BoundaryRole::periodic) {
      throw InputError(fmt::format("periodic patch '{}' has partner '{}', which is not periodic", m.patch, m.partner));
    }
    setup.periodic.add(mesh, mesh.patches[patch_index(m.patch)], mesh.patches[partner], m.axis, m.angle, 1e-8 * mesh_size);
  }
  for (const PatchMotion& m : patches) {
    if (m.role != BoundaryRole::periodic || !m.partner.empty()) continue;
    const bool declared = std::any_of(patches.begin(), patches.end(), [&](const PatchMotion& o) { return o.partner == m.patch; });
    if (!declared) throw InputError(fmt::format("periodic patch '{}' has no partner", m.patch));
  }
  const auto is_slave = [&](NodeId n) { return setup.periodic.is_slave(n); };

  // The strongest role of each node, and the patch that gives it.
  std::vector<int> owner(mesh.node_count(), -1);
  auto role_priority = [&](NodeId n) {
    const int o = owner[static_cast<std::size_t>(n)];
    return o < 0 ? 0 : priority(motion_of[static_cast<std::size_t>(o)]->role);
  };
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    for (NodeId n : mesh.patches[p].nodes) {
      if (priority(motion_of[p]->role) > role_priority(n)) owner[static_cast<std::size_t>(n)] = static_cast<int>(p);
    }
  }
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    if (is_slave(static_cast<NodeId>(n))) {
      setup.roles[n] = static_cast<NodeRoleCode>(1 + static_cast<int>(BoundaryRole::periodic));
      setup.constraints.fix(static_cast<NodeId>(n));  // not an unknown: it follows its master
    } else if (owner[n] >= 0) {
      setup.roles[n] = static_cast<NodeRoleCode>(1 + static_cast<int>(motion_of[static_cast<std::size_t>(owner[n])]->role));
    }
  }
  const auto has_role = [&](NodeId n, BoundaryRole role) { return !is_slave(n) && role_priority(n) == priority(role); };

  // Slip planes: constrain slip nodes now; sliding nodes collect them below.
  std::vector<int> plane_of(mesh.patches.size(), -1);
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    if (motion_of[p]->role != BoundaryRole::slip || mesh.patches[p].nodes.empty()) continue;
    plane_of[p] = static_cast<int>(setup.slip_planes.size());
    setup.slip_planes.push_back(slip_plane(mesh, mesh.patches[p]));
    for (NodeId n : mesh.patches[p].nodes) {
      if (has_role(n, BoundaryRole::slip)) setup.constraints.constrain(n, setup.slip_planes.back().normal);
    }
  }

  // Fixed and prescribed nodes.
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    const PatchMotion& m = *motion_of[p];
    if (patch.nodes.empty()) continue;
    if (m.role == BoundaryRole::fixed) {
      for (NodeId n : patch.nodes) {
        if (!is_slave(n)) setup.constraints.fix(n);
      }
    } else if (m.role == BoundaryRole::prescribed) {
      std::vector<NodeId> nodes;
      for (NodeId n : patch.nodes) {
        if (owner[static_cast<std::size_t>(n)] == static_cast<int>(p) && !is_slave(n)) nodes.push_back(n);
      }
      const auto parameters = locate(mesh, x0, patch, m, nodes);
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        setup.prescribed.push_back({nodes[k], parameters[k], m.shape.get()});
        setup.constraints.fix(nodes[k]);
      }
    }
  }

  // Sliding nodes: every sliding shape and slip plane they lie on.
  std::vector<int> sliding_index(mesh.node_count(), -1);
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    const PatchMotion& m = *motion_of[p];
    if (m.role != BoundaryRole::sliding && m.role != BoundaryRole::slip) continue;
    for (NodeId n : mesh.patches[p].nodes) {
      if (!has_role(n, BoundaryRole::sliding)) continue;
      auto& index = sliding_index[static_cast<std::size_t>(n)];
      if (index < 0) {
        index = static_cast<int>(setup.sliding.size());
        setup.sliding.push_back({});
        setup.sliding.back().node = n;
      }
      SlidingNode& s = setup.sliding[static_cast<std::size_t>(index)];
      if (m.role == BoundaryRole::sliding) {
        if (s.shape_count == SlidingNode::kMaxShapes) {
          throw InputError(fmt::format("node {} lies on more than {} sliding patches", mesh.node_id(n), SlidingNode::kMaxShapes));
        }
        s.shapes[static_cast<std::size_t>(s.shape_count++)] = m.shape.get();
      } else if (s.plane_count < 2) {
        s.planes[static_cast<std::size_t>(s.plane_count++)] = plane_of[p];
      }
    }
  }
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    const PatchMotion& m = *motion_of[p];
    if (m.role != BoundaryRole::sliding || mesh.patches[p].nodes.empty()) continue;
    std::vector<NodeId> nodes;
    for (NodeId n : mesh.patches[p].nodes) {
      if (has_role(n, BoundaryRole::sliding)) nodes.push_back(n);
    }
    const auto parameters = locate(mesh, x0, mesh.patches[p], m, nodes);
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      SlidingNode& s = setup.sliding[static_cast<std::size_t>(sliding_index[static_cast<std::size_t>(nodes[k])])];
      const auto i = static_cast<std::size_t>(std::find(s.shapes.begin(), s.shapes.end(), m.shape.get()) - s.shapes.begin());
      s.hints[i] = parameters[k];
      if (i == 0) s.origin = parameters[k];
    }
  }
  // A restarted run keeps the material parameters of the previous runs (SlidingOrigin).
  if (start) {
    for (const SlidingOrigin& o : start->sliding) {
      if (o.node < 0 || static_cast<std::size_t>(o.node) >= mesh.node_count()) continue;
      const int index = sliding_index[static_cast<std::size_t>(o.node)];
      if (index >= 0) setup.sliding[static_cast<std::size_t>(index)].origin = o.parameter;
    }
  }
  // x_F: where the material point moves, plus (restart) the slide already made (section 4.3).
  for (SlidingNode& s : setup.sliding) {
    if (s.shape_count == 0) continue;
    const Vec3& x = x0[static_cast<std::size_t>(s.node)];
    s.target = x + (s.shapes[0]->at(s.origin, 1.0, x).point - s.shapes[0]->at(s.origin, 0.0, x).point);
    if (start) s.target = place_sliding_node(s, s.target, 1.0, setup.slip_planes).point;
  }
  for (SlidingNode& s : setup.sliding) {
    if (s.shape_count + s.plane_count >= mesh.dimension) {
      setup.constraints.fix(s.node);  // walls meeting in a point: it moves only as they do
    } else {
      setup.constraints.track(s.node);
    }
    if (s.shape_count + s.plane_count > 1 && !start) s.target = place_sliding_node(s, s.target, 1.0, setup.slip_planes).point;
  }

  // Passive surfaces (section 6.1): their rim moves with the walls around them; a spring
  // analogy on each surface gives the rest. Then they are prescribed.
  std::vector<std::optional<Vec3>> rim(mesh.node_count());
  for (const PrescribedNode& p : setup.prescribed) {
    rim[static_cast<std::size_t>(p.node)] = prescribed_position(p, x0[static_cast<std::size_t>(p.node)], 1.0) - x0[static_cast<std::size_t>(p.node)];
  }
  for (const SlidingNode& s : setup.sliding) rim[static_cast<std::size_t>(s.node)] = s.target - x0[static_cast<std::size_t>(s.node)];
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    if (!is_slave(static_cast<NodeId>(n)) && has_role(static_cast<NodeId>(n), BoundaryRole::fixed)) rim[n] = Vec3{};
  }
  std::vector<char> passive_done(mesh.node_count(), 0);
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    if (motion_of[p]->role != BoundaryRole::passive || mesh.patches[p].nodes.empty()) continue;
    const Patch& patch = mesh.patches[p];
    const auto moved = passive_displacements(
        mesh, x0, patch, [&](NodeId n) { return rim[static_cast<std::size_t>(n)]; }, setup.periodic);
    for (std::size_t k = 0; k < patch.nodes.size(); ++k) {
      const NodeId n = patch.nodes[k];
      if (!has_role(n, BoundaryRole::passive) || passive_done[static_cast<std::size_t>(n)]) continue;
      passive_done[static_cast<std::size_t>(n)] = 1;
      rim[static_cast<std::size_t>(n)] = moved[k];  // a rim of the passive surfaces still to solve
      setup.passive.push_back({n, moved[k]});
      setup.constraints.fix(n);
    }
  }

  // Where a stronger role overrules a patch's deflection at shared nodes (a fixed wall beside a
  // moving one), say so if the two disagree about where the node goes.
  const auto final_position = [&](const PatchMotion& m, NodeId n) {
    const Vec3& x = x0[static_cast<std::size_t>(n)];
    if (m.role == BoundaryRole::fixed || !m.shape) return x;
    return prescribed_position({n, m.shape->project(x, 0.0).parameter, m.shape.get()}, x, 1.0);
  };
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    const PatchMotion& m = *motion_of[p];
    if (m.role != BoundaryRole::prescribed && m.role != BoundaryRole::sliding) continue;
    std::size_t overruled = 0;
    double largest = 0.0;
    const double tolerance = 1e-6 * bounding_diagonal(mesh.points, mesh.patches[p].nodes);
    for (NodeId n : mesh.patches[p].nodes) {
      if (is_slave(n) || role_priority(n) <= priority(m.role)) continue;
      const PatchMotion& winner = *motion_of[static_cast<std::size_t>(owner[static_cast<std::size_t>(n)])];
      const double gap = distance(final_position(m, n), final_position(winner, n));
      if (gap > tolerance) {
        ++overruled;
        largest = std::max(largest, gap);
      }
    }
    if (overruled > 0) {
      setup.notes.push_back(fmt::format("patch '{}': {} nodes shared with fixed or prescribed patches follow those, "
                                        "{:.3g} away at most from where this patch's deflection would take them",
                                        mesh.patches[p].name, overruled, largest));
    }
  }
  const bool held = std::any_of(patches.begin(), patches.end(), [&](const PatchMotion& m) {
    return m.role == BoundaryRole::fixed || m.role == BoundaryRole::prescribed;
  });
  if (!held) throw InputError("no patch holds the mesh in place: give at least one patch the role fixed or prescribed");
  return setup;
}

}  // namespace hotmesh::deform::detail
