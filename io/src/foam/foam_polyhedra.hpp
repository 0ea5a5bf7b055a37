// hotmesh io (internal): the cells of an OpenFOAM polyMesh that hotmesh moves as pieces
// (mesh::Polyhedra), as OpenFOAM's own motion solvers decompose cells (cellDecomposition):
// the polyhedra, and the cells of a standard type that are not that element with positive
// corners (snappyHexMesh's snapped hexahedra with a concave corner, which OpenFOAM takes). A
// point is added at each such cell's centre, and at the centre of each of its faces with more
// than four points or of a quad on which its pyramid would not be positive (the cell across
// such a quad is cut too); a cut cell stands as a tetrahedron on each triangle, a pyramid on
// each other quad, and a tetrahedron on each edge of a face with a centre point about it, all
// with their apex at the cell's centre. The centres are OpenFOAM's (primitiveMesh): a face's
// the area-weighted centroid of the triangles from its edges to the mean of its points, a
// cell's the volume-weighted centroid of the pyramids from its faces to the mean of their
// centres.
#pragma once

#include <cstdint>
#include <vector>

#include "foam/foam_cells.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::io::foam {

/// The cells of a 3D polyMesh as elements: `cells[c]` standing for cell c (a cut cell's
/// first piece), then the cut cells' other pieces; the centre points added after the
/// file's; and, per face, the point at its centre (-1 for faces that have none).
struct VolumeElements {
  mesh::ElementList cells;
  std::vector<geometry::Vec3> added_points;
  std::vector<std::int64_t> face_centre;
  mesh::Polyhedra polyhedra;
};

VolumeElements volume_elements(const PolyMesh& mesh, const CellFaces& cells, const std::vector<FoamCell>& elements);

}  // namespace hotmesh::io::foam
