// hotmesh deform: per-element Lamé parameters of the pseudo-material (the paper's appendix).
//
// Eq. (34) splits Hooke's law into shape and volume change, weighted by 2G and lambda + 2G/3.
// Eq. (35) sets them per element from measures of the element's shape and volume deformation
// relative to the standard cube, computed once on the original mesh from the Jacobian J at
// the element centre (d = 2 or 3):
//     2G           = alpha_s |phi_s|,   |phi_s| = ||Jh||_F ||Jh^-1||_F / d,  Jh = J / det(J)^(1/d)
//     lambda + 2G/3 = alpha_v |phi_v|,  |phi_v| = V_median / V_e
// |phi_s| is 1 for a square or cube and grows with stretching and skew; |phi_v| grows as the
// element shrinks. Both are dimensionless, invariant under uniform scaling of the mesh and
// strictly positive, so G > 0 and the bulk modulus lambda + 2G/3 > 0: the element matrices
// are positive semi-definite with exactly the rigid-body null space. (Plane strain is
// positive definite when lambda + G > 0, which lambda + 2G/3 > 0 implies.)
#pragma once

#include <span>
#include <vector>

#include "hotmesh/deform/mesh_names.hpp"
#include "hotmesh/deform/solver_options.hpp"

namespace hotmesh::deform {

struct Lame {
  double lambda = 0.0;
  double mu = 0.0;  ///< G, the shear modulus
};

/// |phi_s| and V_e of one element from its centre Jacobian. quad4/hex8 as above; tri3, tet4,
/// wedge6 and pyramid5 measure ||T||_F ||T^-1||_F / d with T = J W^-1, W the Jacobian of the
/// type's regular cell (all edges equal), so that a regular cell of any type has |phi_s| = 1
/// (docs/method.md, "Hybrid meshes: triangles, tetrahedra, prisms and pyramids").
struct ElementShape {
  double shape_measure = 1.0;  ///< |phi_s|
  double volume = 0.0;         ///< det J at the centre times the reference volume (2^d, 1/2, 1/6, 1, 4/3)
};
ElementShape element_shape(ElementType type, const ElementPoints& element);

/// Lamé parameters of every cell of `mesh` for the law, measured at `points` (eq. 35's
/// "original mesh": the mesh's own coordinates for a motion, the motion's result for the
/// corner pass that follows it); with options.wall_distance_exponent > 0, stiffened by the
/// distance to the nearest of `moving_wall_nodes` (none given: not stiffened).
std::vector<Lame> element_lame(const Mesh& mesh, std::span<const Vec3> points, const MaterialOptions& options,
                               std::span<const NodeId> moving_wall_nodes = {});
/// The same at the mesh's own coordinates.
std::vector<Lame> element_lame(const Mesh& mesh, const MaterialOptions& options,
                               std::span<const NodeId> moving_wall_nodes = {});

}  // namespace hotmesh::deform
