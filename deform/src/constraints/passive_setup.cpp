// hotmesh deform: the set-up of the passive surfaces (section 6.1): solved from their rims, and
// the sliding nodes on a rim held on the surface where it crosses their wall.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "constraints/boundary_builder.hpp"
#include "constraints/passive.hpp"

namespace hotmesh::deform::detail {

namespace {

/// The unit normal of a patch's undeformed surface (in 2D: of its curve, in the x-y plane) at
/// each of `nodes`, averaged over the faces around the node; zero where they give none.
std::vector<Vec3> surface_normals(const Mesh& mesh, const Patch& patch, std::span<const NodeId> nodes) {
  std::unordered_map<NodeId, std::size_t> index;
  for (std::size_t k = 0; k < nodes.size(); ++k) index[nodes[k]] = k;
  std::vector<Vec3> normals(nodes.size());
  const auto at = [&](NodeId n) { return mesh.points[static_cast<std::size_t>(n)]; };
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto face = patch.faces.nodes(f);
    Vec3 normal;
    if (face.size() == 2) {
      const Vec3 t = at(face[1]) - at(face[0]);
      normal = {-t.y, t.x, 0.0};
    } else if (face.size() == 3) {
      normal = cross(at(face[1]) - at(face[0]), at(face[2]) - at(face[0]));
    } else if (face.size() == 4) {
      normal = cross(at(face[2]) - at(face[0]), at(face[3]) - at(face[1]));
    }
    for (NodeId n : face) {
      const auto it = index.find(n);
      if (it == index.end()) continue;
      Vec3& sum = normals[it->second];
      sum += dot(sum, normal) < 0.0 ? -1.0 * normal : normal;  // faces need not agree on orientation
    }
  }
  for (Vec3& n : normals) {
    const double length = norm(n);
    n = length > 0.0 ? n / length : Vec3{};
  }
  return normals;
}

/// A passive surface meeting a sliding wall at less than this angle continues the wall rather
/// than crossing it: the wall's nodes on its rim are not held on it (they could not be: after
/// a deflection normal to the wall the two need not meet at all).
constexpr double kCrossingAngle = std::numbers::pi / 6.0;  // 30 degrees

}  // namespace

/// A sliding node on the rim of a passive surface that crosses its wall is held on that
/// surface too: on the plane tangent to the surface's undeformed shape at the node (for an
/// inlet or outlet plane, the plane itself). It then slides along the line where wall and
/// surface meet (in 2D, it sits at their intersection), and the surface follows it.
void BoundaryBuilder::hold_sliding_rims_on_passive_surfaces() {
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    if (motion_of_[p]->role != BoundaryRole::passive) continue;
    std::vector<NodeId> rim_nodes;
    for (NodeId n : mesh_.patches[p].nodes) {
      if (sliding_index_[static_cast<std::size_t>(n)] >= 0) rim_nodes.push_back(n);
    }
    if (rim_nodes.empty()) continue;
    const std::vector<Vec3> normals = surface_normals(mesh_, mesh_.patches[p], rim_nodes);
    for (std::size_t k = 0; k < rim_nodes.size(); ++k) {
      SlidingNode& s = setup_.sliding[static_cast<std::size_t>(sliding_index_[static_cast<std::size_t>(rim_nodes[k])])];
      if (s.plane_count == static_cast<int>(s.planes.size()) || !(norm(normals[k]) > 0.0)) continue;
      const Vec3& x = x0_[static_cast<std::size_t>(s.node)];
      bool crosses = true;
      for (int i = 0; i < s.shape_count; ++i) {
        const auto j = static_cast<std::size_t>(i);
        const Vec3 wall = s.shapes[j]->at(s.hints[j], 0.0, x).normal;
        crosses = crosses && norm(cross(wall, normals[k])) >= std::sin(kCrossingAngle) * norm(wall);
      }
      if (!crosses) continue;
      s.planes[static_cast<std::size_t>(s.plane_count++)] = static_cast<int>(setup_.slip_planes.size());
      setup_.slip_planes.push_back({mesh_.points[static_cast<std::size_t>(s.node)], normals[k]});
    }
  }
}

/// Passive surfaces (section 6.1): their rim moves with the walls around them; a spring
/// analogy on each surface gives the rest. Then they are prescribed.
void BoundaryBuilder::solve_passive_surfaces() {
  for (const PrescribedNode& p : setup_.prescribed) {
    const Vec3& x = x0_[static_cast<std::size_t>(p.node)];
    rim_[static_cast<std::size_t>(p.node)] = prescribed_position(p, x, 1.0) - x;
  }
  for (const SlidingNode& s : setup_.sliding) rim_[static_cast<std::size_t>(s.node)] = s.target - x0_[static_cast<std::size_t>(s.node)];
  for (std::size_t n = 0; n < mesh_.node_count(); ++n) {
    if (!is_slave(static_cast<NodeId>(n)) && has_role(static_cast<NodeId>(n), BoundaryRole::fixed)) rim_[n] = Vec3{};
  }
  // A surface with a sliding node on its rim (or on the rim of a surface it follows) cannot
  // be solved once for all: it follows its rim through the increments (follow_sliding_rims).
  for (const SlidingNode& s : setup_.sliding) follows_sliding_[static_cast<std::size_t>(s.node)] = 1;
  std::vector<char> passive_done(mesh_.node_count(), 0);
  const RimDisplacement rim_of = [&](NodeId n) { return rim_[static_cast<std::size_t>(n)]; };
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    if (motion_of_[p]->role != BoundaryRole::passive || mesh_.patches[p].nodes.empty()) continue;
    const Patch& patch = mesh_.patches[p];
    PassiveSurface surface(mesh_, x0_, patch, rim_of, setup_.periodic);
    const auto moved = surface.solve(rim_of);  // at the rim's targets
    const auto rim_nodes = surface.rim_nodes();
    const bool following = std::any_of(rim_nodes.begin(), rim_nodes.end(),
                                       [&](NodeId n) { return follows_sliding_[static_cast<std::size_t>(n)] != 0; });
    std::vector<std::pair<std::size_t, NodeId>> solved;
    for (std::size_t k = 0; k < patch.nodes.size(); ++k) {
      const NodeId n = patch.nodes[k];
      if (!has_role(n, BoundaryRole::passive) || passive_done[static_cast<std::size_t>(n)]) continue;
      passive_done[static_cast<std::size_t>(n)] = 1;
      follows_sliding_[static_cast<std::size_t>(n)] = following ? 1 : 0;
      rim_[static_cast<std::size_t>(n)] = moved[k];  // a rim of the passive surfaces still to solve
      setup_.passive.push_back({n, moved[k]});
      setup_.constraints.fix(n);
      solved.emplace_back(k, n);
    }
    if (following && !solved.empty()) setup_.following.push_back({std::move(surface), std::move(solved)});
  }
}

}  // namespace hotmesh::deform::detail
