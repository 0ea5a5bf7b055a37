// hotmesh deform (internal): below these sizes a loop runs on one thread, because starting
// and joining a thread team costs more than the work. It costs far more on a loaded machine,
// where OpenMP threads that spin while they wait steal the time slices of the others: a
// small case on a busy machine then runs tens of times slower in parallel than serially.
#pragma once

#include <cstddef>

namespace hotmesh::deform::detail {

inline constexpr std::ptrdiff_t kParallelVector = 1 << 16;   ///< entries of a vector kernel
inline constexpr std::ptrdiff_t kParallelNodes = 1 << 15;    ///< nodes of a cheap nodal loop
inline constexpr std::ptrdiff_t kParallelCells = 256;        ///< cells of an element-matrix loop
inline constexpr std::ptrdiff_t kParallelProjections = 256;  ///< nodes projected on boundaries
/// Multiply-adds of a product with stored element matrices (cells x dofs^2).
inline constexpr std::ptrdiff_t kParallelProduct = 1 << 18;

}  // namespace hotmesh::deform::detail
