// hotmesh mesh: the mesh model every module works on.
// Points, cells (quad4 in the x-y plane for 2D, hex8 for 3D, with tet4/wedge6/pyramid5 and
// tri3 representable), named boundary patches as lists of faces, and the node sets derived
// from the patches. Filled by io's readers and checked by validate_mesh().
// A 3D cell of a file that is none of these types (a polyhedron: OpenFOAM's, such as
// snappyHexMesh's split hexahedra) is held as its faces (Polyhedra) and stands in `cells` as
// its pieces about points added at its centre and at the centres of its faces of more than
// four points (see Polyhedra), so that everything that works on elements works on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/mesh/element.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::mesh {

using geometry::Vec3;
using NodeId = std::int32_t;  ///< 0-based index into Mesh::points
using CellId = std::int32_t;  ///< 0-based index into Mesh::cells

/// A list of elements of possibly mixed types, stored flat: the nodes of element i are
/// nodes()[offset(i) .. offset(i+1)).
class ElementList {
 public:
  void reserve(std::size_t elements, std::size_t nodes);
  /// Gives back the room the lists grew beyond their elements (a reader that could not
  /// reserve: up to half of them).
  void shrink_to_fit();
  void add(ElementType type, std::span<const NodeId> nodes);
  void add(ElementType type, std::initializer_list<NodeId> nodes) {
    add(type, std::span<const NodeId>(nodes.begin(), nodes.size()));
  }

  std::size_t size() const { return types_.size(); }
  bool empty() const { return types_.empty(); }
  ElementType type(std::size_t i) const { return types_[i]; }
  std::span<const NodeId> nodes(std::size_t i) const {
    return {nodes_.data() + offsets_[i], nodes_.data() + offsets_[i + 1]};
  }
  std::span<NodeId> nodes(std::size_t i) {
    return {nodes_.data() + offsets_[i], nodes_.data() + offsets_[i + 1]};
  }
  /// All node references, element after element.
  std::span<const NodeId> all_nodes() const { return nodes_; }
  std::span<const ElementType> types() const { return types_; }

  friend bool operator==(const ElementList&, const ElementList&) = default;

 private:
  std::vector<ElementType> types_;
  std::vector<std::int64_t> offsets_{0};
  std::vector<NodeId> nodes_;
};

/// A named part of the boundary: the faces (edges in 2D) that carry one boundary role.
struct Patch {
  std::string name;
  int tag = 0;                ///< number of the group in the mesh file (Gmsh physical tag)
  ElementList faces;          ///< line2 in 2D; tri3 / quad4 in 3D
  std::vector<NodeId> nodes;  ///< sorted, unique nodes of faces (derive_node_sets())

  friend bool operator==(const Patch&, const Patch&) = default;
};

/// A named zone of cells (a Gmsh physical group of cells), kept so files round-trip.
struct CellGroup {
  std::string name;
  int tag = 0;
  std::vector<CellId> cells;

  friend bool operator==(const CellGroup&, const CellGroup&) = default;
};

/// The polyhedra of a 3D mesh: the file's cells that are none of the element types, and those
/// of a type whose corners are not all positive (a snapped hexahedron with a concave corner,
/// which OpenFOAM takes). Polyhedron k (file cell `cells[k]`) has the outward faces
/// face_nodes[face_offsets[j] .. face_offsets[j+1]) for j in [faces[k], faces[k+1]), and stands
/// in Mesh::cells as its pieces: about a point added at its centre, a tet4 on each triangle,
/// a pyramid5 on each quad and, on a face of more points (or a quad on which the pyramid would
/// not be positive), a tet4 on each edge about a point added at the face's centre (one point for the
/// face, shared by the two cells on it; on a boundary face its patch's faces are the
/// triangles about it). Every piece's faces
/// are thus the faces of its neighbours: the pieces conform with each other and with the
/// hexahedra, prisms, pyramids and tetrahedra beside them. The first piece of file cell c is
/// Mesh::cells[c]; the others follow the file's cells. Points [0, file_points) are the file's,
/// the centres added follow them: only the file's are written back.
struct Polyhedra {
  std::size_t file_points = 0;
  std::size_t file_cells = 0;
  std::vector<CellId> cells;              ///< the file cells that are polyhedra, ascending
  std::vector<CellId> piece_of;           ///< for Mesh::cells[file_cells + i]: its file cell
  std::vector<std::int64_t> faces{0};     ///< per polyhedron, its range of faces (offsets)
  std::vector<std::int64_t> face_offsets{0};
  std::vector<NodeId> face_nodes;

  bool empty() const { return cells.empty(); }
  /// The file cell a cell of Mesh::cells is (or is a piece of).
  CellId file_cell(CellId c) const {
    const auto i = static_cast<std::size_t>(c);
    return i < file_cells || piece_of.empty() ? c : piece_of[i - file_cells];
  }

  friend bool operator==(const Polyhedra&, const Polyhedra&) = default;
};

struct Mesh {
  int dimension = 3;           ///< 2: quads and triangles in the x-y plane; 3: volume cells
  std::vector<Vec3> points;    ///< z = 0 (or one constant) in 2D
  ElementList cells;
  std::vector<Patch> patches;
  std::vector<CellGroup> cell_groups;
  /// Numbers of nodes and cells in the file they came from (Gmsh tags), for messages and for
  /// writing the file back; empty means 1, 2, 3, ...
  std::vector<std::int64_t> node_ids;
  std::vector<std::int64_t> cell_ids;
  Polyhedra polyhedra;  ///< empty but for files with polyhedral cells (OpenFOAM)

  std::size_t node_count() const { return points.size(); }
  std::size_t cell_count() const { return cells.size(); }
  std::int64_t node_id(NodeId n) const {
    return node_ids.empty() ? std::int64_t{n} + 1 : node_ids[static_cast<std::size_t>(n)];
  }
  std::int64_t cell_id(CellId c) const {
    return cell_ids.empty() ? std::int64_t{c} + 1 : cell_ids[static_cast<std::size_t>(c)];
  }
  const Patch* find_patch(std::string_view patch_name) const;

  /// Fills Patch::nodes from Patch::faces for every patch.
  void derive_node_sets();

  friend bool operator==(const Mesh&, const Mesh&) = default;
};

/// Length of the diagonal of the axis-aligned box around `points` (0 for no points): the
/// length scale that relative tolerances and reported distances refer to.
double bounding_diagonal(std::span<const Vec3> points);
/// The same for the points of the nodes `nodes` only.
double bounding_diagonal(std::span<const Vec3> points, std::span<const NodeId> nodes);

/// The points of one element, gathered from a coordinate array.
struct ElementPoints {
  std::array<Vec3, kMaxElementNodes> p{};
  int count = 0;
};
inline ElementPoints gather(std::span<const NodeId> nodes, std::span<const Vec3> points) {
  ElementPoints e;
  e.count = static_cast<int>(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) e.p[i] = points[static_cast<std::size_t>(nodes[i])];
  return e;
}

}  // namespace hotmesh::mesh
