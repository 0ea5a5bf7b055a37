// hotmesh deform: restoring the worst cell after the corner pass (quality_repair.hpp).
#include "motion/quality_repair.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "hotmesh/mesh/quality.hpp"

namespace hotmesh::deform::detail {
namespace {

/// A compass search stops when its step is this share of where it started.
constexpr double kSmallestStep = 1e-4;
/// The first step of a node's search: this share of its shortest edge.
constexpr double kFirstStep = 0.05;
/// Trial points of one node's search at most.
constexpr int kMostTrials = 400;

/// The cells of every node (CSR: cells of node n are cells[first[n] .. first[n + 1])).
struct NodeCells {
  std::vector<std::size_t> first;
  std::vector<CellId> cells;
  std::span<const CellId> of(NodeId n) const {
    const auto i = static_cast<std::size_t>(n);
    return {cells.data() + first[i], cells.data() + first[i + 1]};
  }
};

NodeCells node_cells(const Mesh& mesh) {
  NodeCells nc;
  nc.first.assign(mesh.node_count() + 1, 0);
  for (const NodeId n : mesh.cells.all_nodes()) ++nc.first[static_cast<std::size_t>(n) + 1];
  for (std::size_t i = 0; i < mesh.node_count(); ++i) nc.first[i + 1] += nc.first[i];
  nc.cells.resize(nc.first.back());
  std::vector<std::size_t> next(nc.first.begin(), nc.first.end() - 1);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    for (const NodeId n : mesh.cells.nodes(c)) nc.cells[next[static_cast<std::size_t>(n)]++] = static_cast<CellId>(c);
  }
  return nc;
}

class Repairer {
 public:
  Repairer(const Mesh& mesh, std::span<Vec3> points, std::span<const char> movable)
      : mesh_(mesh), points_(points), movable_(movable), node_cells_(node_cells(mesh)),
        quality_(mesh::scaled_jacobians(mesh.cells, points)) {}

  const std::vector<double>& quality() const { return quality_; }

  /// One sweep over the cells below `floor`: each movable node of theirs searched once.
  /// Returns the nodes moved.
  std::size_t sweep(double floor) {
    std::vector<NodeId> nodes;
    for (std::size_t c = 0; c < quality_.size(); ++c) {
      if (quality_[c] >= floor) continue;
      for (const NodeId n : mesh_.cells.nodes(c)) {
        if (movable_[static_cast<std::size_t>(n)]) nodes.push_back(n);
      }
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    std::size_t moved = 0;
    for (const NodeId n : nodes) moved += search(n) ? 1u : 0u;
    return moved;
  }

 private:
  double cell_quality(CellId c) const {
    const auto i = static_cast<std::size_t>(c);
    return mesh::scaled_jacobian(mesh_.cells.type(i), mesh::gather(mesh_.cells.nodes(i), points_));
  }

  /// The worst of node n's cells with n at its current point.
  double local_minimum(NodeId n) const {
    double worst = std::numeric_limits<double>::infinity();
    for (const CellId c : node_cells_.of(n)) worst = std::min(worst, cell_quality(c));
    return worst;
  }

  double shortest_edge(NodeId n) const {
    const Vec3& x = points_[static_cast<std::size_t>(n)];
    double shortest = std::numeric_limits<double>::infinity();
    for (const CellId c : node_cells_.of(n)) {
      for (const NodeId m : mesh_.cells.nodes(static_cast<std::size_t>(c))) {
        if (m != n) shortest = std::min(shortest, distance(x, points_[static_cast<std::size_t>(m)]));
      }
    }
    return shortest;
  }

  /// Compass search of the best point for node n (the axis directions, halving the step when
  /// none gains). Returns whether n moved.
  bool search(NodeId n) {
    Vec3& x = points_[static_cast<std::size_t>(n)];
    const Vec3 start = x;
    double best = local_minimum(n);
    const double first = kFirstStep * shortest_edge(n);
    const int dimension = mesh_.dimension;
    int trials = 0;
    for (double step = first; step > kSmallestStep * first && trials < kMostTrials;) {
      bool gained = false;
      for (int axis = 0; axis < dimension; ++axis) {
        for (const double sign : {1.0, -1.0}) {
          const Vec3 before = x;
          x[static_cast<std::size_t>(axis)] += sign * step;
          ++trials;
          const double trial = local_minimum(n);
          if (trial > best) {
            best = trial;
            gained = true;
          } else {
            x = before;
          }
        }
      }
      if (!gained) step *= 0.5;
    }
    for (const CellId c : node_cells_.of(n)) quality_[static_cast<std::size_t>(c)] = cell_quality(c);
    return x != start;
  }

  const Mesh& mesh_;
  std::span<Vec3> points_;
  std::span<const char> movable_;
  NodeCells node_cells_;
  std::vector<double> quality_;
};

}  // namespace

QualityRepair repair_cells_below(const Mesh& mesh, std::span<Vec3> points, std::span<const char> movable, double floor,
                                 int sweeps) {
  Repairer repairer(mesh, points, movable);
  QualityRepair r;
  const auto& q = repairer.quality();
  r.cells_below = static_cast<std::size_t>(std::count_if(q.begin(), q.end(), [&](double v) { return v < floor; }));
  r.min_before = q.empty() ? 1.0 : *std::min_element(q.begin(), q.end());
  for (int s = 0; s < sweeps && r.cells_below > 0; ++s) {
    const std::size_t moved = repairer.sweep(floor);
    r.nodes_moved += moved;
    if (moved == 0 || *std::min_element(q.begin(), q.end()) >= floor) break;
  }
  r.min_after = q.empty() ? 1.0 : *std::min_element(q.begin(), q.end());
  return r;
}

}  // namespace hotmesh::deform::detail
