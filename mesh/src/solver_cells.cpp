// hotmesh mesh: the cells a flow solver sees and the faces where they meet (see
// solver_cells.hpp).
#include "solver_cells.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace hotmesh::mesh::detail {

Layer layer_of(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& extrusion) {
  Layer layer;
  if (mesh.dimension != 2 || points.empty()) return layer;
  layer.planar = true;
  layer.extrusion = extrusion;
  // The prisms must run from back to front along the right-hand normal of the 2D cells (which
  // validate_mesh orients counter-clockwise), so that every face's area vector points out.
  Vec3 centre{};
  for (const Vec3& p : points) centre += p;
  centre = centre / static_cast<double>(points.size());
  const Vec3 through = extrusion.front.at(centre) - extrusion.back.at(centre);
  if (dot(cross(extrusion.back.u, extrusion.back.v), through) < 0.0) std::swap(layer.extrusion.back, layer.extrusion.front);
  // The axis the layer is thin along (an empty or wedge direction) is left out, as OpenFOAM
  // leaves out the directions that are not geometric.
  int thin = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(through[k]) > std::abs(through[thin])) thin = k;
  }
  layer.axes[static_cast<std::size_t>(thin)] = false;
  return layer;
}

namespace {

// Every face of the cells, paired where two cells share it, by the faces filed under their
// smallest node (mesh_topology.hpp).
std::vector<MeshFace> element_faces(const ElementList& cells, std::size_t node_count) {
  const FaceIndex index(cells, node_count);
  std::vector<MeshFace> faces;
  std::vector<bool> paired;
  for (std::size_t n = 0; n < node_count; ++n) {
    const auto bucket = index.bucket(static_cast<NodeId>(n));
    paired.assign(bucket.size(), false);
    for (std::size_t i = 0; i < bucket.size(); ++i) {
      if (paired[i]) continue;
      MeshFace face{bucket[i]};
      const FaceNodes a = face_nodes(cells, bucket[i]);
      for (std::size_t j = i + 1; j < bucket.size(); ++j) {
        if (!paired[j] && same_node_set(a.view(), face_nodes(cells, bucket[j]).view())) {
          face.neighbour = bucket[j];
          paired[j] = true;
          break;
        }
      }
      faces.push_back(face);
    }
  }
  return faces;
}

}  // namespace

SolverCells::SolverCells(const Mesh& mesh, std::span<const Vec3> points, const Layer& layer)
    : mesh_(mesh), points_(points), layer_(layer), count_(mesh.cells.size()) {
  const Polyhedra& p = mesh.polyhedra;
  if (p.empty()) return;
  count_ = p.file_cells;
  polyhedron_.assign(count_, -1);
  for (std::size_t k = 0; k < p.cells.size(); ++k) polyhedron_[static_cast<std::size_t>(p.cells[k])] = static_cast<std::int32_t>(k);
}

std::optional<ElementType> SolverCells::type(std::size_t c) const {
  if (!polyhedron_.empty() && polyhedron_[c] >= 0) return std::nullopt;
  return mesh_.cells.type(c);
}

int SolverCells::side_count(std::size_t c) const {
  if (!polyhedron_.empty() && polyhedron_[c] >= 0) {
    const auto k = static_cast<std::size_t>(polyhedron_[c]);
    return static_cast<int>(mesh_.polyhedra.faces[k + 1] - mesh_.polyhedra.faces[k]);
  }
  return static_cast<int>(mesh::faces(mesh_.cells.type(c)).size());
}

std::span<const NodeId> SolverCells::polyhedron_face(std::size_t c, int local) const {
  const Polyhedra& p = mesh_.polyhedra;
  const auto f = static_cast<std::size_t>(p.faces[static_cast<std::size_t>(polyhedron_[c])] + local);
  return {p.face_nodes.data() + p.face_offsets[f], static_cast<std::size_t>(p.face_offsets[f + 1] - p.face_offsets[f])};
}

// Face `local` of cell `c` as a polygon in 3D, outward: a 3D cell's face, or the side of a 2D
// cell's prism over its edge `local`.
Polygon SolverCells::polygon(std::size_t c, int local) const {
  Polygon polygon;
  if (!polyhedron_.empty() && polyhedron_[c] >= 0) {
    const auto nodes = polyhedron_face(c, local);
    polygon.resize(static_cast<int>(nodes.size()));
    for (std::size_t k = 0; k < nodes.size(); ++k) polygon[static_cast<int>(k)] = points_[static_cast<std::size_t>(nodes[k])];
    return polygon;
  }
  const LocalFace& f = mesh::faces(mesh_.cells.type(c))[static_cast<std::size_t>(local)];
  const auto nodes = mesh_.cells.nodes(c);
  const auto point = [&](int k) { return points_[static_cast<std::size_t>(nodes[f.nodes[static_cast<std::size_t>(k)]])]; };
  if (!layer_.planar) {
    polygon.resize(f.count);
    for (int k = 0; k < f.count; ++k) polygon[k] = point(k);
    return polygon;
  }
  const Vec3 a = point(0), b = point(1);
  polygon.resize(4);
  polygon[0] = layer_.back(a);
  polygon[1] = layer_.back(b);
  polygon[2] = layer_.front(b);
  polygon[3] = layer_.front(a);
  return polygon;
}

std::array<Polygon, 2> SolverCells::planes(std::size_t c) const {
  const auto nodes = mesh_.cells.nodes(c);
  const auto n = static_cast<int>(nodes.size());
  std::array<Polygon, 2> out;
  auto& [back, front] = out;
  back.resize(n);
  front.resize(n);
  for (int k = 0; k < n; ++k) {
    const Vec3& p = points_[static_cast<std::size_t>(nodes[static_cast<std::size_t>(k)])];
    back[n - 1 - k] = layer_.back(p);
    front[k] = layer_.front(p);
  }
  return out;
}

std::vector<MeshFace> SolverCells::faces() const {
  return polyhedron_.empty() ? element_faces(mesh_.cells, points_.size()) : polyhedral_faces();
}

// The faces of the file's cells, paired by their sorted node lists.
std::vector<MeshFace> SolverCells::polyhedral_faces() const {
  std::vector<NodeId> sorted;
  std::vector<std::size_t> offsets{0};
  std::vector<CellFace> owners;
  for (std::size_t c = 0; c < count_; ++c) {
    for (int local = 0; local < side_count(c); ++local) {
      const std::size_t begin = sorted.size();
      if (polyhedron_[c] >= 0) {
        const auto nodes = polyhedron_face(c, local);
        sorted.insert(sorted.end(), nodes.begin(), nodes.end());
      } else {
        const FaceNodes f = face_nodes(mesh_.cells, {static_cast<CellId>(c), local});
        sorted.insert(sorted.end(), f.view().begin(), f.view().end());
      }
      std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(begin), sorted.end());
      offsets.push_back(sorted.size());
      owners.push_back({static_cast<CellId>(c), local});
    }
  }
  const auto key = [&](std::size_t i) {
    return std::span<const NodeId>(sorted.data() + offsets[i], offsets[i + 1] - offsets[i]);
  };
  std::vector<std::size_t> order(owners.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  // By node list, then by cell: the owner of a shared face is the cell with the lower number.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto ka = key(a), kb = key(b);
    if (std::lexicographical_compare(ka.begin(), ka.end(), kb.begin(), kb.end())) return true;
    if (std::lexicographical_compare(kb.begin(), kb.end(), ka.begin(), ka.end())) return false;
    return a < b;
  });
  std::vector<MeshFace> faces;
  for (std::size_t i = 0; i < order.size(); ++i) {
    MeshFace face{owners[order[i]]};
    if (i + 1 < order.size() && std::ranges::equal(key(order[i]), key(order[i + 1]))) face.neighbour = owners[order[++i]];
    faces.push_back(face);
  }
  return faces;
}

}  // namespace hotmesh::mesh::detail
