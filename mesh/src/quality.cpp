#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

#include <algorithm>
#include <cmath>

namespace hotmesh::mesh {

int scaled_corner_jacobians(ElementType type, const ElementPoints& element,
                            std::array<double, kMaxElementNodes>& out) {
  const auto stencils = corner_stencils(type);
  const double scale = ideal_corner_scale(type);
  const bool planar = dimension(type) == 2;
  int k = 0;
  for (const CornerStencil& s : stencils) {
    const Vec3& c = element.p[s.corner];
    const Vec3 e1 = element.p[s.neighbours[0]] - c;
    const Vec3 e2 = element.p[s.neighbours[1]] - c;
    double det = 0.0;
    double lengths = norm(e1) * norm(e2);
    if (planar) {
      det = e1.x * e2.y - e1.y * e2.x;
    } else {
      const Vec3 e3 = element.p[s.neighbours[2]] - c;
      det = triple(e1, e2, e3);
      lengths *= norm(e3);
    }
    out[static_cast<std::size_t>(k++)] = lengths > 0.0 ? scale * det / lengths : 0.0;
  }
  return k;
}

double scaled_jacobian(ElementType type, const ElementPoints& element) {
  std::array<double, kMaxElementNodes> corners{};
  const int n = scaled_corner_jacobians(type, element, corners);
  return *std::min_element(corners.begin(), corners.begin() + n);
}

std::vector<double> scaled_jacobians(const ElementList& cells, std::span<const Vec3> points) {
  const auto n = static_cast<std::ptrdiff_t>(cells.size());
  std::vector<double> q(cells.size());
#pragma omp parallel for schedule(dynamic, kChunkCells) if (n >= kParallelCells)
  for (std::ptrdiff_t c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(c);
    q[i] = scaled_jacobian(cells.type(i), gather(cells.nodes(i), points));
  }
  return q;
}

Orientation orientation(ElementType type, const ElementPoints& element) {
  std::array<double, kMaxElementNodes> corners{};
  const int n = scaled_corner_jacobians(type, element, corners);
  const auto begin = corners.begin();
  const auto end = corners.begin() + n;
  if (std::all_of(begin, end, [](double j) { return j > 0.0; })) return Orientation::positive;
  if (std::all_of(begin, end, [](double j) { return j < 0.0; })) return Orientation::reversed;
  return Orientation::folded;
}

QualitySummary summarize_quality(std::span<const double> scaled_jacobians) {
  QualitySummary s;
  s.cells = scaled_jacobians.size();
  if (scaled_jacobians.empty()) return s;
  double sum = 0.0;
  s.min_scaled_jacobian = scaled_jacobians[0];
  s.worst_cell = 0;
  for (std::size_t i = 0; i < scaled_jacobians.size(); ++i) {
    const double q = scaled_jacobians[i];
    sum += q;
    if (q < s.min_scaled_jacobian) {
      s.min_scaled_jacobian = q;
      s.worst_cell = static_cast<CellId>(i);
    }
    if (q <= 0.0) {
      ++s.inverted_cells;
      ++s.histogram[0];
    } else {
      const auto bin = static_cast<std::size_t>(std::ceil(std::min(q, 1.0) * 10.0));
      ++s.histogram[std::max<std::size_t>(bin, 1)];
    }
  }
  s.mean_scaled_jacobian = sum / static_cast<double>(scaled_jacobians.size());
  return s;
}

}  // namespace hotmesh::mesh
