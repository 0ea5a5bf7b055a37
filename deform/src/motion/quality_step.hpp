// hotmesh deform (internal): the quality step after an increment (beyond the paper; docs/method.md,
// "Keeping the cells as the flow solver wants them").
//
// The elastic medium keeps cells valid, but a flow solver judges them by the angles between
// their faces and the lines joining cell centres (non-orthogonality) and by how far a face's
// centre lies off those lines (skewness). Where walls move far, the medium shears cells that a
// solver needs orthogonal (OpenFOAM's movingCone: 83 degrees where the undeformed mesh has 19).
// The quality step moves the nodes around the worst faces, one at a time, to where the faces
// around each are best for the solver:
//     E(n) = sum over the faces of n's cells of (tan^2(theta_f) + s_f^2)^2,
// theta_f a face's non-orthogonality and s_f its skewness (mesh/solver_quality.hpp; the square
// weighs the worst faces most), by a
// compass search over the directions the node may move in (every direction for an interior
// node, along its plane for a node of a slip patch). A move is kept only if no cell of the
// node falls below min(the worst scaled Jacobian of its cells before the move, `jacobian_floor`),
// so the step never lowers the mesh's worst scaled Jacobian below what it was given, nor
// inverts a cell. Walls that follow shapes, corners and every other constraint stay exact:
// their nodes never move. Sweeps run worst face first, over the nodes of the cells whose worst
// face is beyond a share of the mesh's worst, until a sweep lowers the sum of E over the mesh
// by less than a share of it. The figures below are those measured on OpenFOAM's movingCone
// (docs/method.md).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::deform::detail {

/// A node the quality step may move, and the orthonormal directions it may move in.
struct MovableNode {
  NodeId node = 0;
  std::array<Vec3, 3> directions{};
  int count = 0;
};

struct QualityStepSettings {
  int max_sweeps = 100;
  /// A cell whose worst face term (tan^2 + s^2)^2 is above this share of the mesh's worst: its
  /// nodes are in the sweep.
  double active_share = 0.05;
  /// A sweep that lowers the sum of the face terms by less than this share ends the step.
  double least_gain = 1e-3;
};

struct QualityStepResult {
  std::size_t nodes_moved = 0;
  int sweeps = 0;
  double worst_before = 0.0;  ///< the largest face term, before and after
  double worst_after = 0.0;
};

/// Moves the `movable` nodes of `mesh` at `points` as above; `faces` are the mesh's faces at
/// `points` (SolverFaces reads them as they move).
QualityStepResult improve_for_solver(const Mesh& mesh, const mesh::SolverFaces& faces, std::span<Vec3> points,
                                     std::span<const MovableNode> movable, double jacobian_floor,
                                     const QualityStepSettings& settings = {});

}  // namespace hotmesh::deform::detail
