// hotmesh io (internal): hexahedra recognised from the faces of an OpenFOAM polyMesh. A cell
// is the set of faces whose owner or neighbour it is; OpenFOAM orients each face (right-hand
// normal) out of its owner, so a cell's faces, those it neighbours reversed, point outward.
// A hexahedron has six quadrilateral faces and each of its twelve edges lies in exactly two
// of them; its hex8 nodes (mesh/element.hpp) are a chosen bottom face, reversed so that its
// right-hand normal points into the cell, then above each bottom node the one node joined to
// it by an edge leaving the bottom face. That order has positive volume.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "foam_file.hpp"

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

using Hex = std::array<std::int64_t, 8>;

/// The hex8 nodes of every cell. `bottom_faces` is empty (each cell's first face is its
/// bottom) or gives one face of each cell as its bottom. Throws hotmesh::InputError naming
/// `source` if any cell is not a hexahedron: the first such cell's number and shape, and how
/// many there are.
std::vector<Hex> hexahedra(const PolyMesh& mesh, const CellFaces& cells, std::span<const std::int64_t> bottom_faces,
                           const std::string& source);

}  // namespace hotmesh::io::foam
