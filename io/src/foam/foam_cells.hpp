// hotmesh io (internal): cells recognised from the faces of an OpenFOAM polyMesh. A cell is
// the set of faces whose owner or neighbour it is; OpenFOAM orients each face (right-hand
// normal) out of its owner, so a cell's faces, those it neighbours reversed, point outward.
// The shapes read, by their faces: tetrahedron (4 triangles), pyramid (1 quad, 4 triangles),
// prism (2 triangles, 3 quads), hexahedron (6 quads); in each, every edge lies in exactly two
// faces, once in each direction, and the faces use exactly 4, 5, 6 or 8 points. The nodes in
// hotmesh's (Gmsh's) order (mesh/element.hpp) are a bottom face (tetrahedron: the first face;
// pyramid: the quad; prism: the first triangle; hexahedron: the first face or a chosen one),
// reversed so that its right-hand normal points into the cell, then the apex (tetrahedron,
// pyramid) or above each bottom node the one node joined to it by an edge leaving the bottom
// face (prism, hexahedron). That order has positive volume for a cell that is not folded.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "foam/foam_file.hpp"
#include "hotmesh/mesh/element.hpp"

namespace hotmesh::io::foam {

/// The five files of a polyMesh, read and checked: face points, owners and neighbours in range.
struct PolyMesh {
  std::vector<geometry::Vec3> points;
  FaceTable faces;
  std::vector<std::int64_t> owner;
  std::vector<std::int64_t> neighbour;  ///< one per internal face (the first faces)
  std::vector<BoundaryPatch> patches;
  std::size_t cell_count = 0;
};

/// The faces of each cell: cell c's are faces[offsets[c] .. offsets[c+1]), each a face index
/// with `owned` telling whether c is its owner.
struct CellFaces {
  std::vector<std::int64_t> offsets;
  std::vector<std::int64_t> faces;
  std::vector<bool> owned;
};
CellFaces cell_faces(const PolyMesh& mesh);

/// A cell of the polyMesh as a hotmesh element: its type and its first node_count(type) nodes;
/// or a polyhedron (its faces in CellFaces).
struct FoamCell {
  mesh::ElementType type = mesh::ElementType::hex8;
  std::array<std::int64_t, 8> nodes{};
  bool polyhedron = false;
};

/// The hex8, wedge6, pyramid5 or tet4 of every cell, or that it is a polyhedron. Throws
/// hotmesh::InputError naming `source` for the first cell whose faces do not close.
std::vector<FoamCell> volume_cells(const PolyMesh& mesh, const CellFaces& cells, const std::string& source);

}  // namespace hotmesh::io::foam
