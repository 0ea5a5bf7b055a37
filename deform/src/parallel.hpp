// hotmesh deform (internal): below these sizes a loop runs on one thread, because starting
// and joining a thread team costs more than the work (and much more on a loaded machine).
#pragma once

#include <cstddef>

namespace hotmesh::deform::detail {

inline constexpr std::ptrdiff_t kParallelVector = 16384;  ///< entries of a vector kernel
inline constexpr std::ptrdiff_t kParallelCells = 256;     ///< cells of an element-matrix loop
/// Multiply-adds of a product with stored element matrices (cells x dofs^2).
inline constexpr std::ptrdiff_t kParallelProduct = 1 << 18;
inline constexpr std::ptrdiff_t kParallelNodes = 2048;    ///< nodes of a nodal loop

}  // namespace hotmesh::deform::detail
