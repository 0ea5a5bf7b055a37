// hotmesh deform: the element stiffness matrix of the paper's appendix, eq. (28) evaluated by
// the Gauss rule (30) with n = 2:
//     K_e = sum_g w_g B_g^T E B_g  [* det J_g, unless the Jacobian is dropped (Stein et al.)]
// for the bilinear quad in plane strain (2x2 points) and the trilinear hex (2x2x2 points),
// with B from the current coordinates. At a Gauss point, with g_a = grad N_a, the isotropic
// E of eqs. (32)-(33) gives the 2x2 or 3x3 block coupling nodes a and b
//     K_ab,ij = lambda g_a,i g_b,j + G (g_a,j g_b,i + delta_ij g_a . g_b).
#pragma once

#include <span>

#include "hotmesh/deform/material.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform {

/// Degrees of freedom of a solver cell: 8 for quad4, 24 for hex8; throws InputError otherwise.
int element_dofs(ElementType type);

/// Writes K_e row-major into k (element_dofs(type)^2 values); dof a*d + i is component i of
/// corner a. The determinant enters as |det J_g| when kept, so the matrix stays positive
/// semi-definite for tangled cells met during a Newton iteration.
void element_stiffness(ElementType type, const ElementPoints& element, const Lame& lame, bool drop_jacobian,
                       std::span<double> k);

}  // namespace hotmesh::deform
