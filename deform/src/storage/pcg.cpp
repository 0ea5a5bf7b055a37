// hotmesh deform: preconditioned conjugate gradients.
#include "hotmesh/deform/pcg.hpp"

#include <algorithm>
#include <cmath>

namespace hotmesh::deform {

PcgResult pcg(const LinearOperator& a, const LinearOperator& m, std::span<const double> b, std::span<double> x,
              const PcgOptions& options) {
  const std::size_t n = a.size();
  std::vector<double> r(n), z(n), d(n), q(n);
  PcgResult result;
  const auto total = [&options](double local) { return options.sum ? options.sum(local) : local; };
  const auto residual_norm = [&](std::span<const double> v) {
    return options.norm ? options.norm(v) : std::sqrt(total(dot(v, v)));
  };

  // r = b - A x; from x = 0 on every process without the product
  const bool from_zero = total(std::ranges::all_of(x, [](double v) { return v == 0.0; }) ? 0.0 : 1.0) == 0.0;
  if (from_zero) {
    std::ranges::copy(b, r.begin());
  } else {
    a.apply(x, q);
    for (std::size_t i = 0; i < n; ++i) r[i] = b[i] - q[i];
  }
  if (options.project) options.project(r);
  double rnorm = residual_norm(r);
  result.initial_residual = rnorm;
  result.final_residual = rnorm;
  if (options.record_history) result.history.push_back(1.0);
  if (rnorm == 0.0) {
    result.converged = true;
    return result;
  }
  const double target = options.relative_tolerance * rnorm;

  m.apply(r, z);
  if (options.project) options.project(z);
  d = z;
  double rz = total(dot(r, z));
  for (int k = 0; k < options.max_iterations; ++k) {
    if (!(rz > 0.0)) {
      result.breakdown = true;
      break;
    }
    a.apply(d, q);
    const double dq = total(dot(d, q));
    if (!(dq > 0.0)) {
      result.breakdown = true;
      break;
    }
    const double alpha = rz / dq;
    axpy(alpha, d, x);   // step 1: update the solution
    axpy(-alpha, q, r);  // step 2: update the residual
    rnorm = residual_norm(r);
    result.iterations = k + 1;
    result.final_residual = rnorm;
    if (options.record_history) result.history.push_back(rnorm / result.initial_residual);
    if (rnorm <= target) {
      result.converged = true;
      break;
    }
    if (!std::isfinite(rnorm)) break;
    m.apply(r, z);
    if (options.project) options.project(z);
    const double rz_next = total(dot(r, z));
    xpby(z, rz_next / rz, d);  // step 3: the next search direction
    rz = rz_next;
  }
  return result;
}

}  // namespace hotmesh::deform
