// hotmesh mesh: cell quality. The scaled Jacobian of a cell is the minimum over its corners
// of det[e_1 .. e_d] / (|e_1| .. |e_d|), e_k the edges leaving the corner (element.hpp), scaled
// so that the ideal shape scores 1. It is <= 0 where a corner is folded or inverted: such a
// cell is "inverted" (ARCHITECTURE.md, method note 9).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::mesh {

/// Scaled corner Jacobians of one element (2D types use the z component of e_1 x e_2), in the
/// order of corner_stencils(type). Returns the number of corners written. A corner with a
/// zero-length edge scores 0.
int scaled_corner_jacobians(ElementType type, const ElementPoints& element,
                            std::array<double, kMaxElementNodes>& out);

/// Minimum scaled corner Jacobian of one element.
double scaled_jacobian(ElementType type, const ElementPoints& element);

/// Scaled Jacobian of every cell at the given point coordinates (parallel over cells).
std::vector<double> scaled_jacobians(const ElementList& cells, std::span<const Vec3> points);

enum class Orientation {
  positive,  ///< every corner Jacobian > 0
  reversed,  ///< every corner Jacobian < 0: a valid cell numbered the other way round
  folded,    ///< mixed signs or a zero corner: degenerate or tangled
};
Orientation orientation(ElementType type, const ElementPoints& element);

struct QualitySummary {
  std::size_t cells = 0;
  double min_scaled_jacobian = 1.0;
  double mean_scaled_jacobian = 1.0;
  CellId worst_cell = -1;
  std::size_t inverted_cells = 0;  ///< scaled Jacobian <= 0
  /// histogram[0]: <= 0; histogram[k], k = 1..10: in ((k-1)/10, k/10]
  std::array<std::size_t, 11> histogram{};
};
QualitySummary summarize_quality(std::span<const double> scaled_jacobians);

}  // namespace hotmesh::mesh
