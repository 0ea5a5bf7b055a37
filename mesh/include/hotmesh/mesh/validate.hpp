// hotmesh mesh: checks a freshly loaded mesh before any work is done on it.
// Rejected, with a message naming the node, cell or patch: references to missing nodes,
// non-finite coordinates, a 2D mesh off its plane, nodes used by no cell, duplicate nodes,
// folded or degenerate cells (a corner Jacobian <= 0 that is not a plain reversal), faces
// shared by more than two cells or by two cells on the same side, boundary faces in no
// patch, patch faces that are not cell faces, two patches with one name.
// Cells whose corner Jacobians are all negative are valid cells numbered the other way
// round: they are renumbered in place (a whole mesh written with the opposite orientation
// convention is therefore accepted), provided the result is consistently oriented.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::mesh {

struct ValidationReport {
  std::size_t reoriented_cells = 0;
  std::size_t boundary_faces = 0;
  std::size_t interior_patch_faces = 0;  ///< patch faces between two cells (baffles)
  std::vector<std::string> notes;        ///< things worth a warning, not an error
};

/// The sizes hotmesh moves meshes at, in the mesh's length unit: from this size across ...
inline constexpr double kSmallestMeshSize = 1e-30;
/// ... to this distance from the origin. The stiffness scales as 1/size^2 and the solvers take
/// squares of it, which overflow or underflow double precision long before 1e+-154.
inline constexpr double kLargestCoordinate = 1e30;
/// A mesh whose size is below this fraction of its distance from the origin keeps too few
/// digits of its cells in its coordinates.
inline constexpr double kSmallestRelativeSize = 1e-10;

struct ValidationOptions {
  /// Two nodes closer than this fraction of the bounding-box diagonal are duplicates.
  double duplicate_tolerance = 1e-10;
};

/// Validates `mesh`, reorients reversed cells and fills the patch node sets.
/// Throws hotmesh::InputError describing the first class of problem found.
ValidationReport validate_mesh(Mesh& mesh, const ValidationOptions& options = {});

}  // namespace hotmesh::mesh
