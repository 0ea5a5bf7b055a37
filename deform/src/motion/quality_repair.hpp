// hotmesh deform (internal): restoring the worst cell after the corner pass (beyond the paper).
//
// The corner pass moves a few wall nodes along their walls onto the walls' corners; the
// elastic medium follows, and a cell the motion had already sheared may shear a little more
// (on the ramp sample, the mesh line rising from the node that takes corner A: 0.512 against
// the motion's 0.521). The pass must not cost quality, so where it left cells below the
// motion's worst cell, the interior nodes of those cells are moved one at a time to where the
// worst of their own cells is best (a compass search of that local minimum), until no cell is
// below it or no node gains. Each move raises its node's local minimum, so no cell ends below
// where the pass left the worst one, and none inverts. Boundary nodes never move: walls,
// corners and every constraint stay exact.
#pragma once

#include <cstddef>
#include <span>

#include "hotmesh/deform/mesh_motion.hpp"

namespace hotmesh::deform::detail {

struct QualityRepair {
  std::size_t cells_below = 0;  ///< cells below the floor before the repair
  std::size_t nodes_moved = 0;
  double min_before = 0.0;      ///< worst scaled Jacobian before and after
  double min_after = 0.0;
};

/// Moves the nodes with `movable[n]` of cells below `floor` (scaled Jacobian) at `points`, as
/// above, in at most `sweeps` sweeps over the cells below it.
QualityRepair repair_cells_below(const Mesh& mesh, std::span<Vec3> points, std::span<const char> movable, double floor,
                                 int sweeps);

}  // namespace hotmesh::deform::detail
