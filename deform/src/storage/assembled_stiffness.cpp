// hotmesh deform: assembly of the element matrices into a sparse matrix, entry by entry.
#include "hotmesh/deform/assembled_stiffness.hpp"

#include <vector>

namespace hotmesh::deform {

Eigen::SparseMatrix<double> assemble_sparse(const StiffnessKernel& k, std::span<const Vec3> points) {
  const auto& cells = k.cells();
  const auto d = static_cast<std::size_t>(k.dofs_per_node());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(cells.all_nodes().size() * d * 8 * d);
  std::vector<double> ke;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto nodes = cells.nodes(c);
    const std::size_t n = nodes.size() * d;
    ke.resize(n * n);
    k.element_matrix(static_cast<CellId>(c), points, ke);
    for (std::size_t r = 0; r < n; ++r) {
      const auto row = static_cast<Eigen::Index>(static_cast<std::size_t>(nodes[r / d]) * d + r % d);
      for (std::size_t s = 0; s < n; ++s) {
        const auto col = static_cast<Eigen::Index>(static_cast<std::size_t>(nodes[s / d]) * d + s % d);
        entries.emplace_back(row, col, ke[r * n + s]);
      }
    }
  }
  const auto size = static_cast<Eigen::Index>(k.size());
  Eigen::SparseMatrix<double> matrix(size, size);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

}  // namespace hotmesh::deform
