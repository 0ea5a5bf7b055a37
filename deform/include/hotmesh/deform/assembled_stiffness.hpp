// hotmesh deform: the global stiffness assembled into an Eigen sparse matrix, entry by entry
// from the element kernel's matrices: the textbook assembly, a reference for tests of the
// node-block storage (stiffness_operator.hpp) on small cases.
#pragma once

#include <span>

#include <Eigen/SparseCore>

#include "hotmesh/deform/stiffness_operator.hpp"

namespace hotmesh::deform {

/// K at `points` as a sparse matrix with the operator's dof numbering (node after node).
Eigen::SparseMatrix<double> assemble_sparse(const StiffnessKernel& k, std::span<const Vec3> points);

}  // namespace hotmesh::deform
