// hotmesh io: the zones of a CGNS base joined into one conforming mesh.
// Nodes: the pairs the connectivity declares one are merged (union-find); a base without any
// node-matching connectivity has its zones' coincident boundary nodes merged instead
// (merge_tolerance(): 1e-4 of the shortest boundary edge, more for single precision). Each set
// of merged nodes becomes one mesh node, numbered in the order of its first raw node.
// Patches: one per name (a BC's family, else its name), in the order the names first appear;
// a BC given by points gets the boundary faces of its zone's cells whose nodes are all in it.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <unordered_map>

#include "cgns/cgns_reader.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/mesh/mesh_topology.hpp"

namespace hotmesh::io::cgns {
namespace {

class NodeUnion {
 public:
  explicit NodeUnion(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i] = static_cast<NodeId>(i);
  }
  NodeId find(NodeId a) {
    while (parent_[static_cast<std::size_t>(a)] != a) {
      auto& p = parent_[static_cast<std::size_t>(a)];
      p = parent_[static_cast<std::size_t>(p)];
      a = p;
    }
    return a;
  }
  void unite(NodeId a, NodeId b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent_[static_cast<std::size_t>(b)] = a;  // the first raw node stays the root
  }

 private:
  std::vector<NodeId> parent_;
};

std::vector<std::size_t> zone_of_nodes(const RawMesh& raw) {
  std::vector<std::size_t> zone(raw.points.size());
  for (std::size_t z = 0; z < raw.zones.size(); ++z) {
    const auto first = static_cast<std::size_t>(raw.zones[z].first_node);
    std::fill(zone.begin() + static_cast<std::ptrdiff_t>(first),
              zone.begin() + static_cast<std::ptrdiff_t>(first + raw.zones[z].node_count), z);
  }
  return zone;
}

/// How close two boundary nodes of different zones must be to be one: 1e-4 of the shortest
/// boundary edge, or a few roundings of single precision coordinates if a zone has them, but
/// never above a tenth of the shortest edge.
double merge_tolerance(const RawMesh& raw, double shortest) {
  double tolerance = 1e-4 * shortest;
  const bool single = std::any_of(raw.zones.begin(), raw.zones.end(), [](const ZoneRecord& z) {
    return std::find(z.coordinate_types.begin(), z.coordinate_types.end(), CGNS_ENUMV(RealSingle)) !=
           z.coordinate_types.end();
  });
  if (single) {
    double largest = 0;
    for (const geometry::Vec3& p : raw.points) largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    tolerance = std::max(tolerance, 8.0 * static_cast<double>(std::numeric_limits<float>::epsilon()) * largest);
  }
  return std::min(tolerance, 0.1 * shortest);
}

/// Merges the coincident boundary nodes of different zones (zones without connectivity).
void join_coincident(const RawMesh& raw, NodeUnion& nodes) {
  const mesh::FaceIndex index(raw.cells, raw.points.size());
  const mesh::FaceTopology topology = mesh::face_topology(index);
  std::vector<char> on_boundary(raw.points.size(), 0);
  double shortest = std::numeric_limits<double>::infinity();
  for (const mesh::CellFace& f : topology.boundary) {
    const mesh::FaceNodes face = mesh::face_nodes(raw.cells, f);
    for (int i = 0; i < face.count; ++i) {
      on_boundary[static_cast<std::size_t>(face.nodes[static_cast<std::size_t>(i)])] = 1;
      const auto a = raw.points[static_cast<std::size_t>(face.nodes[static_cast<std::size_t>(i)])];
      const auto b = raw.points[static_cast<std::size_t>(face.nodes[static_cast<std::size_t>((i + 1) % face.count)])];
      shortest = std::min(shortest, norm(b - a));
    }
  }
  if (!(shortest > 0) || !std::isfinite(shortest)) return;
  const double tolerance = merge_tolerance(raw, shortest);
  const auto key = [&](const geometry::Vec3& p, int dx, int dy, int dz) {
    const auto cell = [&](double v, int d) { return static_cast<std::int64_t>(std::floor(v / tolerance)) + d; };
    const std::uint64_t h = static_cast<std::uint64_t>(cell(p.x, dx)) * 73856093u ^
                            static_cast<std::uint64_t>(cell(p.y, dy)) * 19349663u ^
                            static_cast<std::uint64_t>(cell(p.z, dz)) * 83492791u;
    return h;
  };
  const std::vector<std::size_t> zone = zone_of_nodes(raw);
  std::unordered_multimap<std::uint64_t, NodeId> grid;
  for (std::size_t n = 0; n < raw.points.size(); ++n) {
    if (!on_boundary[n]) continue;
    const geometry::Vec3& p = raw.points[n];
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto [lo, hi] = grid.equal_range(key(p, dx, dy, dz));
          for (auto it = lo; it != hi; ++it) {
            const auto m = static_cast<std::size_t>(it->second);
            if (zone[m] != zone[n] && norm(raw.points[m] - p) <= tolerance) nodes.unite(it->second, static_cast<NodeId>(n));
          }
        }
      }
    }
    grid.emplace(key(p, 0, 0, 0), static_cast<NodeId>(n));
  }
}

void check_joined(const RawMesh& raw) {
  const double tolerance = 1e-6 * mesh::bounding_diagonal(raw.points);
  for (const auto& [a, b] : raw.joined) {
    const double gap = norm(raw.points[static_cast<std::size_t>(a)] - raw.points[static_cast<std::size_t>(b)]);
    if (gap > tolerance) {
      const auto zone = zone_of_nodes(raw);
      throw InputError::in(raw.file, fmt::format("the connectivity of zone '{}' makes its node {} one with node {} of zone "
                                                 "'{}', {:.6g} away: the interface does not match point to point",
                                                 raw.zones[zone[static_cast<std::size_t>(a)]].name,
                                                 a - raw.zones[zone[static_cast<std::size_t>(a)]].first_node + 1,
                                                 b - raw.zones[zone[static_cast<std::size_t>(b)]].first_node + 1,
                                                 raw.zones[zone[static_cast<std::size_t>(b)]].name, gap));
    }
  }
}

/// The unique nodes: global_of_raw and the mesh's points.
void number_nodes(const RawMesh& raw, mesh::Mesh& mesh, std::vector<NodeId>& global_of_raw) {
  NodeUnion nodes(raw.points.size());
  check_joined(raw);
  for (const auto& [a, b] : raw.joined) nodes.unite(a, b);
  const bool any_connectivity =
      std::any_of(raw.zones.begin(), raw.zones.end(), [](const ZoneRecord& z) { return z.has_connectivity; });
  if (raw.zones.size() > 1 && !any_connectivity) join_coincident(raw, nodes);
  global_of_raw.assign(raw.points.size(), -1);
  for (std::size_t n = 0; n < raw.points.size(); ++n) {
    const auto root = static_cast<std::size_t>(nodes.find(static_cast<NodeId>(n)));
    if (global_of_raw[root] < 0) {
      global_of_raw[root] = static_cast<NodeId>(mesh.points.size());
      mesh.points.push_back(raw.points[n]);
    }
    global_of_raw[n] = global_of_raw[root];
  }
}

}  // namespace

namespace {

struct PatchBuilder {
  const RawMesh& raw;
  mesh::Mesh& mesh;
  const std::vector<NodeId>& global_of_raw;
  mesh::FaceIndex index;
  std::vector<std::vector<mesh::CellFace>> boundary_of_zone;
  std::vector<char> marked;

  PatchBuilder(const RawMesh& r, mesh::Mesh& m, const std::vector<NodeId>& g)
      : raw(r), mesh(m), global_of_raw(g), index(m.cells, m.node_count()), boundary_of_zone(r.zones.size()),
        marked(m.node_count(), 0) {
    std::vector<std::size_t> zone_of_cell(mesh.cell_count());
    for (std::size_t z = 0; z < raw.zones.size(); ++z) {
      for (std::size_t c = 0; c < raw.zones[z].cell_count; ++c) zone_of_cell[raw.zones[z].first_cell + c] = z;
    }
    for (const mesh::CellFace& f : mesh::face_topology(index).boundary) {
      boundary_of_zone[zone_of_cell[static_cast<std::size_t>(f.cell)]].push_back(f);
    }
  }

  /// Drops the faces a patch holds twice (BCs of one family that overlap).
  static void remove_repeated_faces(mesh::Patch& p) {
    std::set<std::array<NodeId, mesh::kMaxFaceNodes>> seen;
    mesh::ElementList unique;
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
      std::array<NodeId, mesh::kMaxFaceNodes> key{-1, -1, -1, -1};
      const auto nodes = p.faces.nodes(f);
      std::copy_n(nodes.begin(), std::min(nodes.size(), key.size()), key.begin());
      std::sort(key.begin(), key.end());  // the -1 of a 2-node face sort first
      if (seen.insert(key).second) unique.add(p.faces.type(f), nodes);
    }
    if (unique.size() != p.faces.size()) p.faces = std::move(unique);
  }

  mesh::Patch& patch(const std::string& name) {
    for (mesh::Patch& p : mesh.patches) {
      if (p.name == name) return p;
    }
    mesh::Patch& p = mesh.patches.emplace_back();
    p.name = name;
    p.tag = static_cast<int>(mesh.patches.size());
    return p;
  }

  void add_by_points(const RawBc& bc, mesh::Patch& p) {
    for (const NodeId n : bc.nodes) marked[static_cast<std::size_t>(global_of_raw[static_cast<std::size_t>(n)])] = 1;
    std::size_t found = 0;
    for (const mesh::CellFace& f : boundary_of_zone[bc.zone]) {
      const mesh::FaceNodes face = mesh::face_nodes(mesh.cells, f);
      const auto nodes = face.view();
      if (!std::all_of(nodes.begin(), nodes.end(), [&](NodeId n) { return marked[static_cast<std::size_t>(n)] != 0; })) continue;
      p.faces.add(mesh::face_type(mesh.dimension, face.count), nodes);
      ++found;
    }
    for (const NodeId n : bc.nodes) marked[static_cast<std::size_t>(global_of_raw[static_cast<std::size_t>(n)])] = 0;
    if (found == 0) {
      throw InputError::in(raw.file, fmt::format("{} names {} nodes, but no boundary face of the zone has all its nodes "
                                                 "among them",
                                                 bc.where, bc.nodes.size()));
    }
  }

  void add_faces(const RawBc& bc, mesh::Patch& p) {
    std::vector<NodeId> nodes;
    for (std::size_t f = 0; f < bc.faces.size(); ++f) {
      nodes.clear();
      for (const NodeId n : bc.faces.nodes(f)) nodes.push_back(global_of_raw[static_cast<std::size_t>(n)]);
      if (bc.from_section && index.find(nodes).size() > 1) continue;  // an interface between zones
      p.faces.add(bc.faces.type(f), nodes);
    }
  }

  void add(const RawBc& bc) {
    if (bc.from_section) {
      mesh::Patch scratch;
      add_faces(bc, scratch);
      if (scratch.faces.empty()) return;
      mesh::Patch& p = patch(bc.patch);
      for (std::size_t f = 0; f < scratch.faces.size(); ++f) p.faces.add(scratch.faces.type(f), scratch.faces.nodes(f));
      return;
    }
    mesh::Patch& p = patch(bc.patch);
    if (bc.by_points) {
      add_by_points(bc, p);
    } else {
      add_faces(bc, p);
    }
  }
};

}  // namespace

mesh::Mesh assemble(const RawMesh& raw, std::vector<NodeId>& global_of_raw) {
  mesh::Mesh mesh;
  mesh.dimension = raw.dimension;
  number_nodes(raw, mesh, global_of_raw);
  mesh.cells.reserve(raw.cells.size(), raw.cells.all_nodes().size());
  std::vector<NodeId> nodes;
  for (std::size_t c = 0; c < raw.cells.size(); ++c) {
    nodes.clear();
    for (const NodeId n : raw.cells.nodes(c)) nodes.push_back(global_of_raw[static_cast<std::size_t>(n)]);
    mesh.cells.add(raw.cells.type(c), nodes);
  }
  PatchBuilder patches(raw, mesh, global_of_raw);
  for (const RawBc& bc : raw.bcs) patches.add(bc);
  for (mesh::Patch& p : mesh.patches) PatchBuilder::remove_repeated_faces(p);
  return mesh;
}

}  // namespace hotmesh::io::cgns
