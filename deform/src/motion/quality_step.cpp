// hotmesh deform: the quality step after an increment (quality_step.hpp).
#include "motion/quality_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"
#include "hotmesh/mesh/quality.hpp"

namespace hotmesh::deform::detail {
namespace {

/// The first step of a node's search: this share of its shortest edge; the search stops when
/// the step is kSmallestStep of that.
constexpr double kFirstStep = 0.25;
constexpr double kSmallestStep = 1e-3;
constexpr int kMostTrials = 20;  // a node is visited again in the next sweep
/// A face whose line between cell centres is (nearly) in its plane: as bad as any.
constexpr double kLeastCosine = 1e-2;
constexpr double kWorstTerm = 1.0 / (kLeastCosine * kLeastCosine);
constexpr std::size_t kNoSlot = static_cast<std::size_t>(-1);

/// (tan^2(theta) + s^2)^2 of a face (theta for internal faces only: a boundary face's angle is
/// one a solver corrects at the wall, and checkMesh's figure leaves it out).
double face_term(const mesh::FaceMeasures& m, bool internal) {
  double t = m.skewness * m.skewness;
  if (internal) t += m.cosine > kLeastCosine ? (1.0 - m.cosine * m.cosine) / (m.cosine * m.cosine) : kWorstTerm;
  return t * t;
}

class QualityStep {
 public:
  QualityStep(const Mesh& mesh, const mesh::SolverFaces& faces, std::span<Vec3> points,
              std::span<const MovableNode> movable, double jacobian_floor)
      : mesh_(mesh), faces_(faces), points_(points), movable_(movable), floor_(jacobian_floor),
        around_(mesh.cells, mesh.node_count()), face_terms_(faces.size()) {
    std::vector<mesh::CellMeasures> cells(faces.cells());
    const auto n_cells = static_cast<std::ptrdiff_t>(cells.size());
#pragma omp parallel for schedule(static) if (n_cells >= mesh::kParallelCells)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) cells[static_cast<std::size_t>(c)] = faces.cell(static_cast<std::size_t>(c));
    const auto n_faces = static_cast<std::ptrdiff_t>(faces.size());
#pragma omp parallel for schedule(static) if (n_faces >= mesh::kParallelCells)
    for (std::ptrdiff_t i = 0; i < n_faces; ++i) {
      const auto f = static_cast<std::size_t>(i);
      const CellId b = faces.neighbour(f);
      face_terms_[f] = face_term(faces.face(f, cells[static_cast<std::size_t>(faces.owner(f))],
                                            b >= 0 ? &cells[static_cast<std::size_t>(b)] : nullptr),
                                 b >= 0);
    }
  }

  double worst() const { return face_terms_.empty() ? 0.0 : *std::max_element(face_terms_.begin(), face_terms_.end()); }
  double total() const { return std::accumulate(face_terms_.begin(), face_terms_.end(), 0.0); }

  /// One sweep over the movable nodes of the cells whose worst face term is above `threshold`,
  /// those of the worst cells first. Returns the nodes moved.
  std::size_t sweep(double threshold) {
    std::vector<std::pair<double, std::size_t>> order;  // (the worst term of the node's cells, index in movable)
    for (std::size_t k = 0; k < movable_.size(); ++k) {
      double worst = 0.0;
      for (const CellId c : around_.of(static_cast<std::size_t>(movable_[k].node))) worst = std::max(worst, cell_term(c));
      if (worst > threshold) order.emplace_back(worst, k);
    }
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::size_t moved = 0;
    for (const auto& [worst, k] : order) moved += search(movable_[k]) ? 1u : 0u;
    return moved;
  }

 private:
  /// The worst face term of the solver's cell that mesh cell c is (or is a piece of).
  double cell_term(CellId c) const {
    double worst = 0.0;
    for (const std::uint32_t f : faces_.of_cell(faces_.of_mesh_cell(static_cast<std::size_t>(c)))) {
      worst = std::max(worst, face_terms_[f]);
    }
    return worst;
  }

  /// What moving one node changes: its cells (of the mesh, for their scaled Jacobians), the
  /// solver's cells they are, the faces of those, and the solver's cells across those faces
  /// (measured once: they do not move).
  struct Neighbourhood {
    std::vector<CellId> cells;
    std::vector<std::size_t> solver_cells;  ///< slots [0, moving) of `measured`, then those across
    std::size_t moving = 0;
    std::vector<std::uint32_t> faces;
    std::vector<mesh::CellMeasures> measured;
    std::vector<std::size_t> owner_slot, neighbour_slot;  ///< per face; neighbour_slot npos on the boundary
  };

  Neighbourhood neighbourhood(NodeId n) const {
    Neighbourhood h;
    const auto cells = around_.of(static_cast<std::size_t>(n));
    h.cells.assign(cells.begin(), cells.end());
    for (const CellId c : h.cells) h.solver_cells.push_back(faces_.of_mesh_cell(static_cast<std::size_t>(c)));
    std::sort(h.solver_cells.begin(), h.solver_cells.end());
    h.solver_cells.erase(std::unique(h.solver_cells.begin(), h.solver_cells.end()), h.solver_cells.end());
    h.moving = h.solver_cells.size();
    for (std::size_t s = 0; s < h.moving; ++s) {
      for (const std::uint32_t f : faces_.of_cell(h.solver_cells[s])) h.faces.push_back(f);
    }
    std::sort(h.faces.begin(), h.faces.end());
    h.faces.erase(std::unique(h.faces.begin(), h.faces.end()), h.faces.end());
    const auto slot = [&](std::size_t c) {
      const auto it = std::find(h.solver_cells.begin(), h.solver_cells.end(), c);
      if (it != h.solver_cells.end()) return static_cast<std::size_t>(it - h.solver_cells.begin());
      h.solver_cells.push_back(c);
      return h.solver_cells.size() - 1;
    };
    for (const std::uint32_t f : h.faces) {
      h.owner_slot.push_back(slot(static_cast<std::size_t>(faces_.owner(f))));
      const CellId b = faces_.neighbour(f);
      h.neighbour_slot.push_back(b >= 0 ? slot(static_cast<std::size_t>(b)) : kNoSlot);
    }
    h.measured.resize(h.solver_cells.size());
    for (std::size_t s = h.moving; s < h.solver_cells.size(); ++s) h.measured[s] = faces_.cell(h.solver_cells[s]);
    return h;
  }

  /// The node's figure E(n) at its current point, and the worst scaled Jacobian of its cells;
  /// writes the face terms into `terms`.
  std::pair<double, double> evaluate(Neighbourhood& h, std::vector<double>& terms) const {
    double jacobian = std::numeric_limits<double>::infinity();
    for (const CellId cell : h.cells) {
      const auto c = static_cast<std::size_t>(cell);
      jacobian = std::min(jacobian, mesh::scaled_jacobian(mesh_.cells.type(c), mesh::gather(mesh_.cells.nodes(c), points_)));
    }
    for (std::size_t s = 0; s < h.moving; ++s) h.measured[s] = faces_.cell(h.solver_cells[s]);
    double sum = 0.0;
    terms.resize(h.faces.size());
    for (std::size_t k = 0; k < h.faces.size(); ++k) {
      const bool internal = h.neighbour_slot[k] != kNoSlot;
      const auto m = faces_.face(h.faces[k], h.measured[h.owner_slot[k]], internal ? &h.measured[h.neighbour_slot[k]] : nullptr);
      terms[k] = face_term(m, internal);
      sum += terms[k];
    }
    return {sum, jacobian};
  }

  double shortest_edge(NodeId n) const {
    const Vec3& x = points_[static_cast<std::size_t>(n)];
    double shortest = std::numeric_limits<double>::infinity();
    for (const CellId c : around_.of(static_cast<std::size_t>(n))) {
      for (const NodeId m : mesh_.cells.nodes(static_cast<std::size_t>(c))) {
        if (m != n) shortest = std::min(shortest, distance(x, points_[static_cast<std::size_t>(m)]));
      }
    }
    return shortest;
  }

  /// Compass search of E(n) along the node's directions, halving the step when no direction
  /// gains; a trial is taken only if it lowers E and keeps the cells' scaled Jacobians.
  bool search(const MovableNode& node) {
    Neighbourhood h = neighbourhood(node.node);
    std::vector<double> terms, trial_terms;
    Vec3& x = points_[static_cast<std::size_t>(node.node)];
    const Vec3 start = x;
    auto [best, jacobian] = evaluate(h, terms);
    const double keep = std::min(jacobian, floor_);
    const double first = kFirstStep * shortest_edge(node.node);
    int trials = 0;
    for (double step = first; step > kSmallestStep * first && trials < kMostTrials;) {
      bool gained = false;
      for (int k = 0; k < node.count; ++k) {
        for (const double sign : {1.0, -1.0}) {
          const Vec3 before = x;
          x = before + (sign * step) * node.directions[static_cast<std::size_t>(k)];
          ++trials;
          const auto [e, j] = evaluate(h, trial_terms);
          if (e < best && j >= keep) {
            best = e;
            terms.swap(trial_terms);
            gained = true;
          } else {
            x = before;
          }
        }
      }
      if (!gained) step *= 0.5;
    }
    for (std::size_t k = 0; k < h.faces.size(); ++k) face_terms_[h.faces[k]] = terms[k];
    return x != start;
  }

  const Mesh& mesh_;
  const mesh::SolverFaces& faces_;
  std::span<Vec3> points_;
  std::span<const MovableNode> movable_;
  double floor_;
  NodeCells around_;
  std::vector<double> face_terms_;
};

}  // namespace

QualityStepResult improve_for_solver(const Mesh& mesh, const mesh::SolverFaces& faces, std::span<Vec3> points,
                                     std::span<const MovableNode> movable, double jacobian_floor,
                                     const QualityStepSettings& settings) {
  QualityStep step(mesh, faces, points, movable, jacobian_floor);
  QualityStepResult r;
  r.worst_before = r.worst_after = step.worst();
  while (r.sweeps < settings.max_sweeps && !movable.empty()) {
    const double before = step.total();
    const std::size_t moved = step.sweep(settings.active_share * step.worst());
    ++r.sweeps;
    r.nodes_moved += moved;
    r.worst_after = step.worst();
    if (moved == 0 || step.total() > (1.0 - settings.least_gain) * before) break;
  }
  return r;
}

}  // namespace hotmesh::deform::detail
