// hotmesh mesh: hybrid meshes from quad and hex meshes (see split_cells.hpp).
#include "hotmesh/mesh/split_cells.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace hotmesh::mesh {
namespace {

using Key = std::array<NodeId, 4>;  ///< a face's nodes, sorted (a triangle's fourth is -1)

Key key_of(std::span<const NodeId> nodes) {
  Key k{-1, -1, -1, -1};
  const std::size_t n = std::min<std::size_t>(nodes.size(), k.size());
  for (std::size_t i = 0; i < n; ++i) {  // insertion sort of 3 or 4 nodes
    std::size_t j = i;
    for (; j > 0 && k[j - 1] > nodes[i]; --j) k[j] = k[j - 1];
    k[j] = nodes[i];
  }
  return k;
}

/// The nodes of local face f of a hex, outward.
std::array<NodeId, 4> hex_face(std::span<const NodeId> cell, std::size_t f) {
  const LocalFace& local = faces(ElementType::hex8)[f];
  return {cell[local.nodes[0]], cell[local.nodes[1]], cell[local.nodes[2]], cell[local.nodes[3]]};
}

/// Position in a quad face (0..3) of its node of the smallest number: a triangulated face's
/// diagonal runs from it, whichever cell splits it.
std::size_t diagonal_start(std::span<const NodeId> face) {
  return static_cast<std::size_t>(std::min_element(face.begin(), face.end()) - face.begin());
}

/// Whether a face of `split`'s cell must stay a quad: every face of a kept hex or of a cell
/// split into pyramids, a prism's sides.
bool stays_quad(CellSplit split, std::size_t f) {
  if (split == CellSplit::keep || split == CellSplit::pyramids) return true;
  if (split == CellSplit::prisms) return f >= 2;  // faces 0 and 1 are the bottom and the top
  return false;
}

/// The hex faces that stay quads: those a kept hex or a prism's side keeps so.
std::set<Key> quad_faces_of(const Mesh& mesh, std::span<const CellSplit> split) {
  std::set<Key> quad_faces;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.cells.type(c) != ElementType::hex8) continue;
    for (std::size_t f = 0; f < 6; ++f) {
      if (stays_quad(split[c], f)) quad_faces.insert(key_of(hex_face(mesh.cells.nodes(c), f)));
    }
  }
  return quad_faces;
}

/// Adds the pieces of cell c (nodes n, of `type`) to `out`; a hex split about its centre adds
/// the centre to out.points.
void add_pieces(Mesh& out, std::size_t c, ElementType type, std::span<const NodeId> n, CellSplit s,
                const std::set<Key>& quad_faces) {
  if (s == CellSplit::keep) {
    out.cells.add(type, n);
  } else if (s == CellSplit::triangles && type == ElementType::quad4) {
    out.cells.add(ElementType::tri3, {n[0], n[1], n[2]});
    out.cells.add(ElementType::tri3, {n[0], n[2], n[3]});
  } else if (s == CellSplit::prisms && type == ElementType::hex8) {
    const std::size_t a = diagonal_start(n.first(4)) % 2;  // the bottom's diagonal: corners a, a + 2
    if (diagonal_start(n.subspan(4, 4)) % 2 != a) {
      throw std::invalid_argument("split_cells: cell " + std::to_string(c) + " has crossed diagonals on its ends: "
                                  "no two prisms split it as its neighbours split those faces");
    }
    const auto b = a + 1, d = (a + 2) % 4, e = (a + 3) % 4;
    out.cells.add(ElementType::wedge6, {n[a], n[b], n[d], n[a + 4], n[b + 4], n[d + 4]});
    out.cells.add(ElementType::wedge6, {n[a], n[d], n[e], n[a + 4], n[d + 4], n[e + 4]});
  } else if ((s == CellSplit::tetrahedra || s == CellSplit::pyramids) && type == ElementType::hex8) {
    Vec3 centre;
    for (NodeId a : n) centre += out.points[static_cast<std::size_t>(a)];
    const auto apex = static_cast<NodeId>(out.points.size());
    out.points.push_back(centre / 8.0);
    for (std::size_t f = 0; f < 6; ++f) {
      const auto face = hex_face(n, f);  // outward: reversed, its normal points to the apex
      if (quad_faces.count(key_of(face))) {
        out.cells.add(ElementType::pyramid5, {face[0], face[3], face[2], face[1], apex});
      } else {
        const std::size_t i = diagonal_start(face);
        const NodeId a = face[i], b = face[(i + 1) % 4], d = face[(i + 2) % 4], e = face[(i + 3) % 4];
        out.cells.add(ElementType::tet4, {a, d, b, apex});
        out.cells.add(ElementType::tet4, {a, e, d, apex});
      }
    }
  } else {
    throw std::invalid_argument("split_cells: cell " + std::to_string(c) + " is a " + std::string(name(type)) +
                                ", which this split does not apply to");
  }
}

/// Patch faces as the new cells have them: a quad kept, or the two triangles of a cell.
void split_patches(const Mesh& mesh, const std::set<Key>& quad_faces, Mesh& out) {
  std::map<Key, std::array<NodeId, 3>> triangles;  // the triangle faces of the new cells
  for (std::size_t c = 0; c < out.cells.size(); ++c) {
    const auto n = out.cells.nodes(c);
    for (const LocalFace& local : faces(out.cells.type(c))) {
      if (local.count != 3) continue;
      const std::array<NodeId, 3> t{n[local.nodes[0]], n[local.nodes[1]], n[local.nodes[2]]};
      triangles.emplace(key_of(t), t);
    }
  }
  for (const Patch& p : mesh.patches) {
    Patch patch{p.name, p.tag, {}, {}};
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
      const auto face = p.faces.nodes(f);
      if (face.size() != 4 || mesh.dimension == 2 || quad_faces.count(key_of(face))) {
        patch.faces.add(p.faces.type(f), face);
        continue;
      }
      bool split_found = false;
      for (std::size_t i = 0; i < 2 && !split_found; ++i) {  // the diagonal from corner i
        const std::array<NodeId, 3> t1{face[i], face[i + 1], face[(i + 2) % 4]};
        const std::array<NodeId, 3> t2{face[i], face[(i + 2) % 4], face[(i + 3) % 4]};
        if (triangles.count(key_of(t1)) && triangles.count(key_of(t2))) {
          patch.faces.add(ElementType::tri3, t1);
          patch.faces.add(ElementType::tri3, t2);
          split_found = true;
        }
      }
      if (!split_found) throw std::invalid_argument("split_cells: patch '" + p.name + "' has a face no cell has any more");
    }
    out.patches.push_back(std::move(patch));
  }
}

}  // namespace

Mesh split_cells(const Mesh& mesh, std::span<const CellSplit> split) {
  if (split.size() != mesh.cell_count()) throw std::invalid_argument("split_cells: one split per cell");
  if (!mesh.node_ids.empty() || !mesh.cell_ids.empty()) throw std::invalid_argument("split_cells: a mesh with ids from a file");
  Mesh out;
  out.dimension = mesh.dimension;
  out.points = mesh.points;
  const std::set<Key> quad_faces = quad_faces_of(mesh, split);

  std::vector<std::size_t> first_piece(mesh.cell_count() + 1, 0);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    first_piece[c] = out.cells.size();
    add_pieces(out, c, mesh.cells.type(c), mesh.cells.nodes(c), split[c], quad_faces);
  }
  first_piece[mesh.cell_count()] = out.cells.size();

  for (const CellGroup& g : mesh.cell_groups) {
    CellGroup group{g.name, g.tag, {}};
    for (CellId c : g.cells) {
      for (auto p = first_piece[static_cast<std::size_t>(c)]; p < first_piece[static_cast<std::size_t>(c) + 1]; ++p) {
        group.cells.push_back(static_cast<CellId>(p));
      }
    }
    out.cell_groups.push_back(std::move(group));
  }
  split_patches(mesh, quad_faces, out);
  out.derive_node_sets();
  return out;
}

}  // namespace hotmesh::mesh
