// hotmesh deform: deterministic parallel vector kernels.
#include "hotmesh/deform/linear_algebra.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

#include <cmath>
#include <vector>

namespace hotmesh::deform {
namespace {
constexpr std::size_t kChunk = 4096;
}

double dot(std::span<const double> a, std::span<const double> b) {
  const std::size_t n = a.size();
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<double> partial(chunks, 0.0);
#pragma omp parallel for schedule(dynamic) if (static_cast<std::ptrdiff_t>(n) >= mesh::kParallelVector)
  for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(chunks); ++c) {
    const std::size_t begin = static_cast<std::size_t>(c) * kChunk;
    const std::size_t end = std::min(n, begin + kChunk);
    double s = 0.0;
    for (std::size_t i = begin; i < end; ++i) s += a[i] * b[i];
    partial[static_cast<std::size_t>(c)] = s;
  }
  double sum = 0.0;
  for (double p : partial) sum += p;
  return sum;
}

double norm2(std::span<const double> a) { return std::sqrt(dot(a, a)); }

void axpy(double alpha, std::span<const double> x, std::span<double> y) {
#pragma omp parallel for schedule(dynamic, mesh::kChunkVector) if (static_cast<std::ptrdiff_t>(x.size()) >= mesh::kParallelVector)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(x.size()); ++i) {
    y[static_cast<std::size_t>(i)] += alpha * x[static_cast<std::size_t>(i)];
  }
}

void xpby(std::span<const double> x, double beta, std::span<double> y) {
#pragma omp parallel for schedule(dynamic, mesh::kChunkVector) if (static_cast<std::ptrdiff_t>(x.size()) >= mesh::kParallelVector)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(x.size()); ++i) {
    const auto k = static_cast<std::size_t>(i);
    y[k] = x[k] + beta * y[k];
  }
}

}  // namespace hotmesh::deform
