// hotmesh deform: the corners of the sliding walls given to their nodes (wall_features.hpp):
// those nodes lie on from the start, and, in the corner pass, those of the walls' features.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>

#include "constraints/boundary_builder.hpp"

namespace hotmesh::deform::detail {

/// Sliding node n, given the corner line at `corner` of `wall`, slides on the two paths that
/// take it onto that line (CornerPath): in the line's cross-section it is led onto the line,
/// along the line it is free.
void BoundaryBuilder::follow_corner_line(NodeId n, const geometry::BoundaryShape& wall, const CornerLine& line) {
  SlidingNode& s = setup_.sliding[static_cast<std::size_t>(sliding_index_[static_cast<std::size_t>(n)])];
  for (std::size_t d = 0; d < 2; ++d) {
    auto path = std::make_shared<const CornerPath>(wall, line, x0_[static_cast<std::size_t>(n)], static_cast<int>(d));
    s.shapes[d] = path.get();
    s.segments[d] = {};
    s.hints[d] = {.t = line.corner};
    setup_.corner_paths.push_back(std::move(path));
  }
  s.shape_count = 2;
}

/// Whether sliding node n may be given a corner whose point is q: a node of one wall only,
/// free or held on slip planes through the corner (the side of a sector), holding no other.
bool BoundaryBuilder::can_hold_corner(NodeId n, const Vec3& q, double on_plane) const {
  const int i = sliding_index_[static_cast<std::size_t>(n)];
  if (i < 0 || holds_[static_cast<std::size_t>(n)]) return false;
  const SlidingNode& s = setup_.sliding[static_cast<std::size_t>(i)];
  const auto planes = std::span(s.planes).first(static_cast<std::size_t>(s.plane_count));
  return s.shape_count == 1 && std::all_of(planes.begin(), planes.end(), [&](int k) {
           const SlipPlane& plane = setup_.slip_planes[static_cast<std::size_t>(k)];
           return std::abs(dot(q - plane.origin, plane.normal)) <= on_plane;
         });
}

/// The slip planes sliding node n is held on.
std::vector<SlipPlane> BoundaryBuilder::planes_of(NodeId n) const {
  std::vector<SlipPlane> planes;
  const int i = sliding_index_[static_cast<std::size_t>(n)];
  if (i < 0) return planes;
  const SlidingNode& s = setup_.sliding[static_cast<std::size_t>(i)];
  for (const int k : std::span(s.planes).first(static_cast<std::size_t>(s.plane_count))) {
    planes.push_back(setup_.slip_planes[static_cast<std::size_t>(k)]);
  }
  return planes;
}

/// The plan's corners given to its nodes: in 2D a node is prescribed onto its corner point,
/// in 3D it goes onto its corner line and slides along it. The wall's other sliding nodes keep
/// to their segments. Corners are recorded for the report, creases with the wall's creases.
void BoundaryBuilder::give_corners(WallFeaturePlan& plan, const PatchMotion& m, const Patch& patch) {
  for (std::size_t k = 0; k < patch.nodes.size() && !plan.features.empty(); ++k) {
    const int i = sliding_index_[static_cast<std::size_t>(patch.nodes[k])];
    if (i < 0) continue;
    SlidingNode& s = setup_.sliding[static_cast<std::size_t>(i)];
    const auto j = static_cast<std::size_t>(std::find(s.shapes.begin(), s.shapes.end(), m.shape.get()) - s.shapes.begin());
    if (j < s.segments.size()) s.segments[j] = plan.segments[k];
  }
  for (HeldFeature& held : plan.features) {
    for (NodeId n : held.nodes) {
      if (mesh_.dimension == 3) {  // a corner line: the node goes onto it and slides along it
        holds_[static_cast<std::size_t>(n)] = kSlidesAlongCorner;
        follow_corner_line(n, *m.shape, {held.feature.parameter, held.crease});
      } else {  // a corner point: the node is prescribed onto it
        holds_[static_cast<std::size_t>(n)] = kPrescribedOntoCorner;
        setup_.prescribed.push_back({n, {.t = held.feature.parameter}, m.shape.get(), true});
        setup_.constraints.fix(n);
      }
    }
    if (!held.note.empty()) setup_.notes.push_back(held.note);
    if (held.crease) {
      note_crease_given_nodes(patch.name, *m.shape, held);
      continue;
    }
    setup_.corners.push_back({patch.name, m.shape.get(), x0_[static_cast<std::size_t>(patch.nodes.front())], std::move(held)});
  }
}

/// Adds a crease the mesh's lines miss, and the nodes given it, to the wall's record of that
/// crease (where nodes lie on it already, slide_along_creases made one).
void BoundaryBuilder::note_crease_given_nodes(const std::string& patch, const geometry::BoundaryShape& wall, const HeldFeature& held) {
  if (held.nodes.empty() && held.unheld_edges == 0) return;  // the nodes on it hold it from the start
  const std::vector<int> key{held.crease->faces[0], held.crease->faces[1]};
  auto it = std::find_if(setup_.creases.begin(), setup_.creases.end(),
                         [&](const WallCrease& c) { return c.patch == patch && c.faces == key; });
  if (it == setup_.creases.end()) {
    setup_.creases.push_back({patch, key, held.crease->angle, {}, {}});
    it = std::prev(setup_.creases.end());
  }
  it->wall = &wall;
  it->line = *held.crease;
  it->nodes.insert(it->nodes.end(), held.nodes.begin(), held.nodes.end());
  it->largest_offset = std::max(it->largest_offset, held.largest_offset);
  it->unheld_edges += held.unheld_edges;
}

/// The nodes prescribed onto corners slide no more.
void BoundaryBuilder::drop_nodes_prescribed_onto_corners() {
  std::erase_if(setup_.sliding,
                [&](const SlidingNode& s) { return holds_[static_cast<std::size_t>(s.node)] == kPrescribedOntoCorner; });
  std::fill(sliding_index_.begin(), sliding_index_.end(), -1);
  for (std::size_t k = 0; k < setup_.sliding.size(); ++k) {
    sliding_index_[static_cast<std::size_t>(setup_.sliding[k].node)] = static_cast<int>(k);
  }
}

/// The corners that nodes of a sliding wall lie on before the motion (a mesh made from CAD
/// has a node on every CAD vertex) are held by those nodes from the start, whatever the
/// wall's `features`: the wall has no tangent there for them to slide along. The other nodes
/// keep to the segments between these corners (plan_corners_on_nodes; a run that starts from
/// an earlier one's mesh takes the nodes on corners to rounding only).
void BoundaryBuilder::hold_corners_on_nodes() {
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    const PatchMotion& m = *motion_of_[p];
    const Patch& patch = mesh_.patches[p];
    if (m.role != BoundaryRole::sliding || patch.nodes.empty()) continue;
    const double on_plane = 1e-9 * bounding_diagonal(mesh_.points, patch.nodes);
    WallFeaturePlan plan =
        plan_corners_on_nodes(mesh_, x0_, patch, *m.shape, m.features.angle, start_ == nullptr,
                              [&](NodeId n, const Vec3& q) { return can_hold_corner(n, q, on_plane); });
    give_corners(plan, m, patch);
  }
  drop_nodes_prescribed_onto_corners();
}

/// The corners of each sliding wall with features (wall_features.hpp), in the corner pass:
/// the nodes given one become prescribed nodes that reach it; the other sliding nodes keep to
/// their segments.
void BoundaryBuilder::hold_wall_corners() {
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    const PatchMotion& m = *motion_of_[p];
    const Patch& patch = mesh_.patches[p];
    if (m.role != BoundaryRole::sliding || !m.features.enabled || patch.nodes.empty()) continue;
    const double on_plane = 1e-9 * bounding_diagonal(mesh_.points, patch.nodes);
    WallFeaturePlan plan = plan_wall_features(
        mesh_, x0_, patch, *m.shape, m.features.angle,
        [&](NodeId n, const Vec3& q) { return can_hold_corner(n, q, on_plane); },
        [&](NodeId n) { return planes_of(n); }, [&](NodeId n) { return setup_.periodic.master_of(n); });
    std::erase_if(plan.features, [&](const HeldFeature& held) {  // held from the start (hold_corners_on_nodes)
      return !held.crease && std::any_of(setup_.corners.begin(), setup_.corners.end(), [&](const WallCorner& c) {
               return c.patch == patch.name && c.held.feature.parameter == held.feature.parameter;
             });
    });
    give_corners(plan, m, patch);
  }
  drop_nodes_prescribed_onto_corners();
}

}  // namespace hotmesh::deform::detail
