// hotmesh deform: passive surfaces, a linear spring analogy on the surface (section 6.1).
#include "passive.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <unordered_map>

#include "hotmesh/geometry/input_error.hpp"

namespace hotmesh::deform::detail {

std::vector<Vec3> passive_displacements(const Mesh& mesh, std::span<const Vec3> points, const Patch& patch,
                                        const RimDisplacement& rim, const PeriodicCoupling& periodic) {
  const std::size_t d = static_cast<std::size_t>(mesh.dimension);
  // Local numbering of the surface's nodes, and what is known about each.
  std::unordered_map<NodeId, std::size_t> local;
  for (std::size_t i = 0; i < patch.nodes.size(); ++i) local[patch.nodes[i]] = i;
  const std::size_t n = patch.nodes.size();
  std::vector<std::optional<Vec3>> known(n);
  for (std::size_t i = 0; i < n; ++i) known[i] = rim(patch.nodes[i]);

  // Periodic slaves in the surface follow their master: through the master's unknown if the
  // master is in the surface and unknown, else known from the master's rim displacement.
  std::vector<std::int64_t> master_of(n, -1);
  std::vector<std::size_t> rotation_of(n, 0);
  for (const PeriodicPair& p : periodic.pairs()) {
    const auto s = local.find(p.slave), m = local.find(p.master);
    if (s == local.end() || known[s->second]) continue;
    if (m != local.end()) {
      master_of[s->second] = static_cast<std::int64_t>(m->second);
      rotation_of[s->second] = p.rotation;
    } else if (const auto km = rim(p.master)) {
      known[s->second] = periodic.rotation(p.rotation).vector(*km);
    }
  }
  // Unknowns: nodes neither known nor slaves of a surface node.
  std::vector<std::int64_t> unknown(n, -1);
  std::size_t unknowns = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!known[i] && master_of[i] < 0) unknown[i] = static_cast<std::int64_t>(unknowns++);
  }
  std::vector<Vec3> result(n);
  for (std::size_t i = 0; i < n; ++i) result[i] = known[i].value_or(Vec3{});
  if (unknowns == 0) return result;

  // The displacement of node i as unknowns: u_i = T_i U, T_i = I (own), R (slave), 0 (known).
  auto owner = [&](std::size_t i) -> std::pair<std::int64_t, const Rotation*> {
    if (unknown[i] >= 0) return {unknown[i], nullptr};
    if (master_of[i] >= 0) return {unknown[static_cast<std::size_t>(master_of[i])], &periodic.rotation(rotation_of[i])};
    return {-1, nullptr};
  };
  const auto entry = [](const Rotation* r, std::size_t a, std::size_t b) { return r ? r->entry(a, b) : (a == b ? 1.0 : 0.0); };

  // Springs along face edges (each edge once), stiffness 1 / length.
  std::map<std::pair<NodeId, NodeId>, double> springs;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto nodes = patch.faces.nodes(f);
    const std::size_t count = nodes.size() == 2 ? 1 : nodes.size();
    for (std::size_t e = 0; e < count; ++e) {
      NodeId a = nodes[e], b = nodes[(e + 1) % nodes.size()];
      if (a > b) std::swap(a, b);
      springs[{a, b}] = 1.0 / std::max(distance(points[static_cast<std::size_t>(a)], points[static_cast<std::size_t>(b)]), 1e-300);
    }
  }
  // Every part of the surface must be reached from its rim along springs (or periodic ties).
  {
    std::vector<std::vector<std::size_t>> next(n);
    for (const auto& [edge, k] : springs) {
      next[local[edge.first]].push_back(local[edge.second]);
      next[local[edge.second]].push_back(local[edge.first]);
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (master_of[i] >= 0) {
        next[i].push_back(static_cast<std::size_t>(master_of[i]));
        next[static_cast<std::size_t>(master_of[i])].push_back(i);
      }
    }
    std::vector<char> reached(n, 0);
    std::vector<std::size_t> queue;
    for (std::size_t i = 0; i < n; ++i) {
      if (known[i]) {
        reached[i] = 1;
        queue.push_back(i);
      }
    }
    for (std::size_t q = 0; q < queue.size(); ++q) {
      for (std::size_t j : next[queue[q]]) {
        if (!reached[j]) {
          reached[j] = 1;
          queue.push_back(j);
        }
      }
    }
    const auto stray = std::find(reached.begin(), reached.end(), 0);
    if (stray != reached.end()) {
      throw InputError(fmt::format("passive patch '{}': part of it (node {} and its neighbours) touches no fixed, "
                                   "prescribed or sliding wall, so nothing drives its motion; give it another role",
                                   patch.name, mesh.node_id(patch.nodes[static_cast<std::size_t>(stray - reached.begin())])));
    }
  }

  // Energy sum k |u_a - u_b|^2 / 2 with u = T U + u_known: (T_a - T_b)^T k (T_a - T_b) U = -(T_a - T_b)^T k (uk_a - uk_b).
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(unknowns * d));
  for (const auto& [edge, k] : springs) {
    const std::size_t ia = local[edge.first], ib = local[edge.second];
    const std::array<std::size_t, 2> ends{ia, ib};
    const Vec3 known_gap = result[ia] - result[ib];  // known parts (zero for unknown nodes)
    for (std::size_t x = 0; x < 2; ++x) {
      const auto [ux, rx] = owner(ends[x]);
      if (ux < 0) continue;
      const double sx = x == 0 ? 1.0 : -1.0;
      for (std::size_t y = 0; y < 2; ++y) {
        const auto [uy, ry] = owner(ends[y]);
        if (uy < 0) continue;
        const double sy = y == 0 ? 1.0 : -1.0;
        for (std::size_t i = 0; i < d; ++i) {
          for (std::size_t j = 0; j < d; ++j) {
            double v = 0.0;  // (T_x^T T_y)_ij
            for (std::size_t c = 0; c < d; ++c) v += entry(rx, c, i) * entry(ry, c, j);
            if (v != 0.0) {
              triplets.emplace_back(static_cast<Eigen::Index>(static_cast<std::size_t>(ux) * d + i),
                                    static_cast<Eigen::Index>(static_cast<std::size_t>(uy) * d + j), k * sx * sy * v);
            }
          }
        }
      }
      for (std::size_t i = 0; i < d; ++i) {
        double v = 0.0;
        for (std::size_t c = 0; c < d; ++c) v += entry(rx, c, i) * known_gap[c];
        rhs[static_cast<Eigen::Index>(static_cast<std::size_t>(ux) * d + i)] -= k * sx * v;
      }
    }
  }
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(unknowns * d), static_cast<Eigen::Index>(unknowns * d));
  a.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  const Eigen::VectorXd u = solver.info() == Eigen::Success ? Eigen::VectorXd(solver.solve(rhs)) : Eigen::VectorXd();
  if (solver.info() != Eigen::Success || !u.allFinite()) {
    throw InputError(fmt::format("passive patch '{}': part of it touches no fixed, prescribed or sliding wall, so "
                                 "nothing drives its motion; give it another role",
                                 patch.name));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto [ui, r] = owner(i);
    if (ui < 0) continue;
    Vec3 own;
    for (std::size_t c = 0; c < d; ++c) own[c] = u[static_cast<Eigen::Index>(static_cast<std::size_t>(ui) * d + c)];
    result[i] = r ? r->vector(own) : own;
  }
  return result;
}

}  // namespace hotmesh::deform::detail
