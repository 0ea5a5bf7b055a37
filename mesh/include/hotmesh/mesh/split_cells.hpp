// hotmesh mesh: hybrid meshes made from quad and hex meshes by splitting cells, for tests,
// samples and benchmarks of the motion on every cell type (issue 24).
//   quads:  into two triangles along the diagonal 0-2;
//   hexes:  into two prisms (wedge6) standing on the faces 0-1-2-3 and 4-5-6-7, or about a
//           new node at the cell's centre into one pyramid per face that stays a quad and
//           two tetrahedra per face that is triangulated (or into six pyramids, every face
//           kept a quad).
// A triangulated face is split along the diagonal through its node of the smallest number,
// so the two cells on a face split it alike whatever their own numbering: tetrahedra fit any
// conforming hex mesh. Prisms need their two ends split along parallel diagonals, which holds
// on extruded meshes (structured_hexes, test::square_ring); a cell where it does not is
// refused. A face of a cell split about its centre stays a quad (a pyramid's base) where the
// cell across keeps it a quad: a hex, or a prism's side. Patch faces are split as the cells
// beside them.
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
  pyramids,    ///< a hex8 about its centre into six pyramid5, one on each face (all stay quads)
};

/// `mesh` with cell c split as `split[c]` says (one entry per cell). The new nodes (centres)
/// follow the old ones; cell groups keep the pieces of their cells; cell and node ids of the
/// file are dropped. Throws std::invalid_argument for a split the cell's type has not, or
/// for a mesh with node or cell ids from a file.
Mesh split_cells(const Mesh& mesh, std::span<const CellSplit> split);

}  // namespace hotmesh::mesh
