// hotmesh deform: the global stiffness assembled into an Eigen sparse matrix from the same
// element matrices the matrix-free operator stores. A reference for tests and small cases;
// the assembled path of a distributed backend follows the same pattern.
#pragma once

#include <Eigen/SparseCore>

#include "hotmesh/deform/stiffness_operator.hpp"

namespace hotmesh::deform {

/// K as a sparse matrix with the operator's dof numbering.
Eigen::SparseMatrix<double> assemble_sparse(const StiffnessOperator& k);

}  // namespace hotmesh::deform
