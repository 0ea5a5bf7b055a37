// hotmesh deform: the set-up of the sliding nodes (section 4): the shapes and slip planes each
// lies on, the creases of walls made of faces they slide along, and their targets x_F (4.3).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "constraints/boundary_builder.hpp"
#include "constraints/sliding.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::deform::detail {

/// Sliding nodes: every sliding shape and slip plane they lie on, and where on each shape.
void BoundaryBuilder::collect_sliding_nodes() {
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    const PatchMotion& m = *motion_of_[p];
    if (m.role != BoundaryRole::sliding && m.role != BoundaryRole::slip) continue;
    for (NodeId n : mesh_.patches[p].nodes) {
      if (!has_role(n, BoundaryRole::sliding)) continue;
      auto& index = sliding_index_[static_cast<std::size_t>(n)];
      if (index < 0) {
        index = static_cast<int>(setup_.sliding.size());
        setup_.sliding.push_back({});
        setup_.sliding.back().node = n;
      }
      SlidingNode& s = setup_.sliding[static_cast<std::size_t>(index)];
      if (m.role == BoundaryRole::sliding) {
        if (s.shape_count == SlidingNode::kMaxShapes) {
          throw InputError(
              fmt::format("node {} lies on more than {} sliding patches", mesh_.node_id(n), SlidingNode::kMaxShapes));
        }
        s.shapes[static_cast<std::size_t>(s.shape_count++)] = m.shape.get();
      } else if (s.plane_count < 2) {
        s.planes[static_cast<std::size_t>(s.plane_count++)] = plane_of_[p];
      }
    }
  }
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    const PatchMotion& m = *motion_of_[p];
    if (m.role != BoundaryRole::sliding || mesh_.patches[p].nodes.empty()) continue;
    std::vector<NodeId> nodes;
    for (NodeId n : mesh_.patches[p].nodes) {
      if (has_role(n, BoundaryRole::sliding)) nodes.push_back(n);
    }
    const Located located = locate(mesh_, x0_, mesh_.patches[p], m, nodes);
    setup_.wall_gaps.push_back(located.gap);
    const auto& parameters = located.parameters;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      SlidingNode& s = setup_.sliding[static_cast<std::size_t>(sliding_index_[static_cast<std::size_t>(nodes[k])])];
      const auto i =
          static_cast<std::size_t>(std::find(s.shapes.begin(), s.shapes.end(), m.shape.get()) - s.shapes.begin());
      s.hints[i] = parameters[k];
      if (i == 0) s.origin = parameters[k];
    }
  }
}

/// A sliding node on an edge where two faces of its wall meet at an angle (crease_sides:
/// at least the wall's feature angle) slides along that edge: it is held by each face as a
/// shape of its own instead of by the wall, so it never rounds the edge off; where three
/// faces meet it stays at their corner.
void BoundaryBuilder::slide_along_creases() {
  std::map<std::pair<std::string, std::vector<int>>, std::size_t> crease_of;
  for (SlidingNode& s : setup_.sliding) {
    for (int i = 0; i < s.shape_count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const PatchMotion* m = sliding_motion_of(s.shapes[k]);
      if (m == nullptr) continue;
      auto sides = s.shapes[k]->crease_sides(s.hints[k], m->features.angle);
      if (sides.size() < 2 || s.shape_count + static_cast<int>(sides.size()) - 1 > SlidingNode::kMaxShapes) continue;
      s.shapes[k] = sides[0].get();
      for (std::size_t j = 1; j < sides.size(); ++j) {
        const auto added = static_cast<std::size_t>(s.shape_count++);
        s.shapes[added] = sides[j].get();
        s.hints[added] = geometry::kNoHint;
        s.segments[added] = {};
      }
      note_crease(crease_of, m->patch, s.node, sides);
      for (auto& side : sides) setup_.corner_paths.push_back(std::move(side));
      break;
    }
  }
}

/// Adds node n, on the crease where `sides` meet, to the wall's record of that crease.
void BoundaryBuilder::note_crease(std::map<std::pair<std::string, std::vector<int>>, std::size_t>& crease_of,
                                  const std::string& patch, NodeId n,
                                  const std::vector<std::shared_ptr<const geometry::BoundaryShape>>& sides) {
  const Vec3& x = x0_[static_cast<std::size_t>(n)];
  std::vector<int> faces;
  double angle = 0.0;  // undeformed or fully deflected, as ShapeCrease::angle
  for (const double lambda : {0.0, 1.0}) {
    std::vector<Vec3> normals;
    for (const auto& side : sides) {
      const geometry::ShapePoint q = side->project(x, lambda);
      if (lambda == 0.0) faces.push_back(q.parameter.face);
      normals.push_back(q.normal);
    }
    for (std::size_t a = 0; a < normals.size(); ++a) {
      for (std::size_t b = a + 1; b < normals.size(); ++b) {
        angle = std::max(angle, std::acos(std::min(1.0, std::abs(dot(normals[a], normals[b])))));
      }
    }
  }
  std::vector<const geometry::BoundaryShape*> shapes;
  for (const auto& side : sides) shapes.push_back(side.get());
  std::vector<int> key = faces;
  std::sort(key.begin(), key.end());
  const auto [it, added] = crease_of.try_emplace({patch, key}, setup_.creases.size());
  if (added) setup_.creases.push_back({patch, key, 0.0, {}, shapes});
  WallCrease& crease = setup_.creases[it->second];
  crease.angle = std::max(crease.angle, angle);
  crease.nodes.push_back(n);
}

/// The sliding patch's motion whose shape this is, if any.
const PatchMotion* BoundaryBuilder::sliding_motion_of(const geometry::BoundaryShape* shape) const {
  for (const PatchMotion* m : motion_of_) {
    if (m->role == BoundaryRole::sliding && m->shape.get() == shape) return m;
  }
  return nullptr;
}

/// x_F: where each sliding node's material point moves, plus (restart) the slide already
/// made (section 4.3); a restarted run keeps the material parameters of the previous runs
/// (SlidingOrigin). Nodes where walls meet in a point are fixed, the others tracked.
void BoundaryBuilder::set_sliding_targets() {
  if (start_) {
    for (const SlidingOrigin& o : start_->sliding) {
      if (o.node < 0 || static_cast<std::size_t>(o.node) >= mesh_.node_count()) continue;
      const int index = sliding_index_[static_cast<std::size_t>(o.node)];
      if (index >= 0) setup_.sliding[static_cast<std::size_t>(index)].origin = o.parameter;
    }
  }
  for (SlidingNode& s : setup_.sliding) {
    if (s.shape_count == 0) continue;
    const Vec3& x = x0_[static_cast<std::size_t>(s.node)];
    s.target = x + (s.shapes[0]->at(s.origin, 1.0, x).point - s.shapes[0]->at(s.origin, 0.0, x).point);
    if (start_) s.target = place_sliding_node(s, s.target, 1.0, setup_.slip_planes).point;
  }
  for (SlidingNode& s : setup_.sliding) {
    if (s.shape_count + s.plane_count >= mesh_.dimension) {
      setup_.constraints.fix(s.node);  // walls meeting in a point: it moves only as they do
    } else {
      setup_.constraints.track(s.node);
    }
    if (s.shape_count + s.plane_count > 1 && !start_) {
      s.target = place_sliding_node(s, s.target, 1.0, setup_.slip_planes).point;
    }
  }
}

}  // namespace hotmesh::deform::detail
