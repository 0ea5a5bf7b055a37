// hotmesh mesh: hybrid meshes made from quad and hex meshes by splitting cells, for tests,
// samples and benchmarks of the motion on every cell type (issue 24).
//   quads:  into two triangles along the diagonal 0-2;
//   hexes:  into two prisms (wedge6) along the plane through the edges 0-4 and 2-6, or
//           about a new node at the cell's centre into one pyramid per face that stays a
//           quad and two tetrahedra per face that is triangulated.
// A triangulated face of a hex is split along the diagonal through its corner 0 or 6 (every
// face of a hex has exactly one of them), which is the prisms' diagonal on their end faces.
// On a structured mesh (structured_hexes, test::square_ring: every cell numbered alike) the
// two cells on a face then split it alike, so the result is conforming. A face of a cell
// split about its centre stays a quad (a pyramid's base) where the cell across keeps it a
// quad: a hex, or a prism's side. Patch faces are split as the cells beside them.
#pragma once

#include <cstdint>
#include <span>

#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::mesh {

enum class CellSplit : std::uint8_t {
  keep,        ///< the cell as it is
  triangles,   ///< a quad4 into two tri3
  prisms,      ///< a hex8 into two wedge6
  tetrahedra,  ///< a hex8 about its centre into tet4, and pyramid5 on the faces that stay quads
};

/// `mesh` with cell c split as `split[c]` says (one entry per cell). The new nodes (centres)
/// follow the old ones; cell groups keep the pieces of their cells; cell and node ids of the
/// file are dropped. Throws std::invalid_argument for a split the cell's type has not, or
/// for a mesh with node or cell ids from a file.
Mesh split_cells(const Mesh& mesh, std::span<const CellSplit> split);

}  // namespace hotmesh::mesh
