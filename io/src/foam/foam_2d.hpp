// hotmesh io (internal): one-cell-thick OpenFOAM cases as 2D meshes of quads and triangles.
// The faces on the `empty` patches (two planes normal to x, y or z) or on the two `wedge`
// patches (two planes through the symmetry axis) give every cell a back and a front face; the
// back faces, in the 2D frame of the back plane, are the 2D mesh, and each front point
// follows the back point it is joined to by a cell edge (a point on a wedge's axis, on both
// planes, follows itself).
#pragma once

#include "foam/foam_cells.hpp"
#include "foam/foam_write_back.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::io::foam {

/// True if some `empty` or `wedge` patch has faces.
bool is_2d(const PolyMesh& mesh);

struct FlatMesh {
  mesh::Mesh mesh;
  PointMap map;
};

/// The 2D mesh of a one-cell-thick case. Throws hotmesh::InputError naming `source` if the
/// mesh is not one (planes, cells with other than one face on each, ...).
FlatMesh flatten(const PolyMesh& mesh, const CellFaces& cells, const std::string& source);

}  // namespace hotmesh::io::foam
