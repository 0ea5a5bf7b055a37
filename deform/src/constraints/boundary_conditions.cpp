// hotmesh deform: boundary roles to node constraints, prescribed motions and sliding nodes.
#include "constraints/boundary_conditions.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <cmath>
#include <numbers>
#include <optional>
#include <unordered_map>

#include "constraints/passive.hpp"
#include "constraints/rigid_modes.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform::detail {
namespace {

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

/// Where `nodes` lie on the undeformed shape (stage 0), and the farthest of them from it.
struct Located {
  std::vector<geometry::ShapeParameter> parameters;
  WallGap gap;
};

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

Vec3 prescribed_position(const PrescribedNode& p, const Vec3& original, double lambda) {
  const Vec3 moved = p.shape->at(p.parameter, lambda, original).point;
  const Vec3 start = p.shape->at(p.parameter, 0.0, original).point;
  if (p.reaches_shape) return moved + (1.0 - lambda) * (original - start);
  return original + (moved - start);
}

namespace {

/// set_up_boundaries, phase by phase. Each phase reads what the ones before it decided.
class BoundaryBuilder {
 public:
  BoundaryBuilder(const Mesh& mesh, std::span<const PatchMotion> patches, const MotionStart* start)
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
  void assign_motions() {
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
  void couple_periodic_pairs() {
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
  void assign_node_roles() {
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

  /// Slip planes: constrain slip nodes now; sliding nodes collect them below.
  void constrain_slip_nodes() {
    for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
      if (motion_of_[p]->role != BoundaryRole::slip || mesh_.patches[p].nodes.empty()) continue;
      plane_of_[p] = static_cast<int>(setup_.slip_planes.size());
      setup_.slip_planes.push_back(slip_plane(mesh_, mesh_.patches[p]));
      for (NodeId n : mesh_.patches[p].nodes) {
        if (has_role(n, BoundaryRole::slip)) setup_.constraints.constrain(n, setup_.slip_planes.back().normal);
      }
    }
  }

  /// Fixed and prescribed nodes.
  void constrain_fixed_and_prescribed_nodes() {
    for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
      const Patch& patch = mesh_.patches[p];
      const PatchMotion& m = *motion_of_[p];
      if (patch.nodes.empty()) continue;
      if (m.role == BoundaryRole::fixed) {
        for (NodeId n : patch.nodes) {
          if (!is_slave(n)) setup_.constraints.fix(n);
        }
      } else if (m.role == BoundaryRole::prescribed) {
        std::vector<NodeId> nodes;
        for (NodeId n : patch.nodes) {
          if (owner_[static_cast<std::size_t>(n)] == static_cast<int>(p) && !is_slave(n)) nodes.push_back(n);
        }
        const Located located = locate(mesh_, x0_, patch, m, nodes);
        setup_.wall_gaps.push_back(located.gap);
        for (std::size_t k = 0; k < nodes.size(); ++k) {
          setup_.prescribed.push_back({nodes[k], located.parameters[k], m.shape.get()});
          setup_.constraints.fix(nodes[k]);
        }
      }
    }
  }

  /// Sliding nodes: every sliding shape and slip plane they lie on, and where on each shape.
  void collect_sliding_nodes() {
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
  void slide_along_creases() {
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
  void note_crease(std::map<std::pair<std::string, std::vector<int>>, std::size_t>& crease_of, const std::string& patch,
                   NodeId n, const std::vector<std::shared_ptr<const geometry::BoundaryShape>>& sides) {
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

  /// Adds a crease the mesh's lines miss, and the nodes given it, to the wall's record of that
  /// crease (where nodes lie on it already, slide_along_creases made one).
  void note_crease_given_nodes(const std::string& patch, const geometry::BoundaryShape& wall, const HeldFeature& held) {
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

  /// The sliding patch's motion whose shape this is, if any.
  const PatchMotion* sliding_motion_of(const geometry::BoundaryShape* shape) const {
    for (const PatchMotion* m : motion_of_) {
      if (m->role == BoundaryRole::sliding && m->shape.get() == shape) return m;
    }
    return nullptr;
  }

  /// A sliding node on the rim of a passive surface that crosses its wall is held on that
  /// surface too: on the plane tangent to the surface's undeformed shape at the node (for an
  /// inlet or outlet plane, the plane itself). It then slides along the line where wall and
  /// surface meet (in 2D, it sits at their intersection), and the surface follows it.
  void hold_sliding_rims_on_passive_surfaces() {
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

  /// How a node holds a corner (give_corners).
  static constexpr char kPrescribedOntoCorner = 1;
  static constexpr char kSlidesAlongCorner = 2;

  /// Sliding node n, given the corner line at `corner` of `wall`, slides on the two paths that
  /// take it onto that line (CornerPath): in the line's cross-section it is led onto the line,
  /// along the line it is free.
  void follow_corner_line(NodeId n, const geometry::BoundaryShape& wall, const CornerLine& line) {
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
  bool can_hold_corner(NodeId n, const Vec3& q, double on_plane) const {
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
  std::vector<SlipPlane> planes_of(NodeId n) const {
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
  void give_corners(WallFeaturePlan& plan, const PatchMotion& m, const Patch& patch) {
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

  /// The nodes prescribed onto corners slide no more.
  void drop_nodes_prescribed_onto_corners() {
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
  void hold_corners_on_nodes() {
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
  void hold_wall_corners() {
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

  /// x_F: where each sliding node's material point moves, plus (restart) the slide already
  /// made (section 4.3); a restarted run keeps the material parameters of the previous runs
  /// (SlidingOrigin). Nodes where walls meet in a point are fixed, the others tracked.
  void set_sliding_targets() {
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

  /// Passive surfaces (section 6.1): their rim moves with the walls around them; a spring
  /// analogy on each surface gives the rest. Then they are prescribed.
  void solve_passive_surfaces() {
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

  /// Where a stronger role overrules a patch's deflection at shared nodes (a fixed wall beside
  /// a moving one), say so if the two disagree about where the node goes.
  void note_overruled_deflections() {
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
  BoundarySetup finish() {
    refuse_free_rigid_motions(mesh_, setup_, follows_sliding_);
    return std::move(setup_);
  }

 private:
  std::size_t patch_index(const std::string& name) const {
    const auto it =
        std::find_if(mesh_.patches.begin(), mesh_.patches.end(), [&](const Patch& p) { return p.name == name; });
    if (it == mesh_.patches.end()) throw InputError(fmt::format("the mesh has no patch '{}'", name));
    return static_cast<std::size_t>(it - mesh_.patches.begin());
  }
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

}  // namespace

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
