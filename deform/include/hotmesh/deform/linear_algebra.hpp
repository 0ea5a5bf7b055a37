// hotmesh deform: the small abstract operator the solvers work with, and vector kernels
// whose results do not depend on the number of threads (reductions are summed in fixed
// chunks, the chunk sums in order), so a run is bit-identical on any machine size.
#pragma once

#include <cstddef>
#include <span>

namespace hotmesh::deform {

/// y = A x for vectors of size(). Const and callable from one thread at a time.
class LinearOperator {
 public:
  virtual ~LinearOperator() = default;
  virtual std::size_t size() const = 0;
  virtual void apply(std::span<const double> x, std::span<double> y) const = 0;
};

double dot(std::span<const double> a, std::span<const double> b);
double norm2(std::span<const double> a);  ///< Euclidean norm
/// y += alpha x
void axpy(double alpha, std::span<const double> x, std::span<double> y);
/// y = x + beta y
void xpby(std::span<const double> x, double beta, std::span<double> y);

}  // namespace hotmesh::deform
