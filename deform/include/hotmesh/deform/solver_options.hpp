// hotmesh deform: options of the elastic mesh-motion solve, with their defaults. The case
// file (io) fills them; the solver reads them. One struct per concern, no global settings.
#pragma once

namespace hotmesh::deform {

/// Increments, Newton-Raphson (eqs. 7-8) and the inner PCG solves (section 3).
struct SolverOptions {
  int increments = 16;              ///< N: the prescribed motion is applied in N steps
  double newton_tolerance = 1e-4;   ///< stop at ||R|| <= tol * ||R0|| (the paper's value)
  int max_newton_iterations = 30;
  double pcg_tolerance = 1e-3;      ///< relative residual of each inner linear solve
  int max_pcg_iterations = 5000;
  int threads = 0;                  ///< OpenMP threads; 0: all available cores
};

/// Pseudo-material of the elastic medium: eq. (35), 2G = alpha_s |phi_s|,
/// lambda + 2G/3 = alpha_v |phi_v|.
struct MaterialOptions {
  double alpha_s = 1.0;   ///< weight of shape (deviatoric) stiffness
  double alpha_v = 0.01;  ///< weight of volume stiffness; the paper keeps it 1-3 orders lower
};

}  // namespace hotmesh::deform
