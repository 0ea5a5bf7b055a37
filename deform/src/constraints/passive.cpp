// hotmesh deform: passive surfaces, a linear spring analogy on the surface (section 6.1).
#include "constraints/passive.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <map>
#include <unordered_map>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::deform::detail {

struct PassiveSurface::Factorisation {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
};

namespace {

double entry(const Rotation* r, std::size_t a, std::size_t b) { return r ? r->entry(a, b) : (a == b ? 1.0 : 0.0); }

Vec3 known_value(const RimDisplacement& rim, NodeId n) {
  const std::optional<Vec3> value = rim(n);
  assert(value && "a passive surface's rim lost a node it knew at set-up");
  return value.value_or(Vec3{});
}

}  // namespace

std::pair<std::int64_t, const Rotation*> PassiveSurface::owner(std::size_t i) const {
  if (unknown_[i] >= 0) return {unknown_[i], nullptr};
  if (master_of_[i] >= 0) return {unknown_[static_cast<std::size_t>(master_of_[i])], &rotations_[rotation_of_[i]]};
  return {-1, nullptr};
}

PassiveSurface::PassiveSurface(const Mesh& mesh, std::span<const Vec3> points, const Patch& patch,
                               const RimDisplacement& rim, const PeriodicCoupling& periodic)
    : name_(patch.name), dim_(static_cast<std::size_t>(mesh.dimension)), nodes_(patch.nodes) {
  LocalIndex local;
  for (std::size_t i = 0; i < nodes_.size(); ++i) local[nodes_[i]] = i;
  classify_nodes(rim, periodic, local);
  build_springs(patch, points, local);
  if (unknowns_ == 0) return;
  require_every_node_driven(mesh);
  factorise();
}

void PassiveSurface::classify_nodes(const RimDisplacement& rim, const PeriodicCoupling& periodic,
                                    const LocalIndex& local) {
  const std::size_t n = nodes_.size();
  known_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (rim(nodes_[i])) {
      known_[i] = kFromRim;
      rim_nodes_.push_back(nodes_[i]);
    }
  }

  // Periodic slaves in the surface follow their master: through the master's unknown if the
  // master is in the surface and unknown, else known from the master's rim displacement.
  master_of_.assign(n, -1);
  rotation_of_.assign(n, 0);
  // The rotations it needs, copied: the set-up that owns the PeriodicCoupling may move.
  std::vector<std::int64_t> local_rotation;
  const auto rotation = [&](std::size_t r) {
    if (local_rotation.size() <= r) local_rotation.resize(r + 1, -1);
    if (local_rotation[r] < 0) {
      local_rotation[r] = static_cast<std::int64_t>(rotations_.size());
      rotations_.push_back(periodic.rotation(r));
    }
    return static_cast<std::size_t>(local_rotation[r]);
  };
  for (const PeriodicPair& p : periodic.pairs()) {
    const auto s = local.find(p.slave), m = local.find(p.master);
    if (s == local.end() || known_[s->second]) continue;
    const bool master_known = m != local.end() ? known_[m->second] != 0 : rim(p.master).has_value();
    if (master_known) {  // a master on the rim, in the surface or not
      known_[s->second] = kTied;
      ties_.push_back({s->second, p.master, m != local.end() ? static_cast<std::int64_t>(m->second) : -1, rotation(p.rotation)});
      if (m == local.end()) rim_nodes_.push_back(p.master);
    } else if (m != local.end()) {
      master_of_[s->second] = static_cast<std::int64_t>(m->second);
      rotation_of_[s->second] = rotation(p.rotation);
    }
  }
  // Unknowns: nodes neither known nor slaves of a surface node.
  unknown_.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!known_[i] && master_of_[i] < 0) unknown_[i] = static_cast<std::int64_t>(unknowns_++);
  }
}

/// Springs along face edges (each edge once), stiffness 1 / length.
void PassiveSurface::build_springs(const Patch& patch, std::span<const Vec3> points, const LocalIndex& local) {
  std::map<std::pair<NodeId, NodeId>, double> edges;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    const auto face = patch.faces.nodes(f);
    const std::size_t count = face.size() == 2 ? 1 : face.size();
    for (std::size_t e = 0; e < count; ++e) {
      NodeId a = face[e], b = face[(e + 1) % face.size()];
      if (a > b) std::swap(a, b);
      edges[{a, b}] = 1.0 / std::max(distance(points[static_cast<std::size_t>(a)], points[static_cast<std::size_t>(b)]), 1e-300);
    }
  }
  springs_.reserve(edges.size());
  for (const auto& [edge, k] : edges) springs_.push_back({local.at(edge.first), local.at(edge.second), k});
}

/// Every part of the surface must be reached from its rim along springs (or periodic ties).
void PassiveSurface::require_every_node_driven(const Mesh& mesh) const {
  const std::size_t n = nodes_.size();
  std::vector<std::vector<std::size_t>> next(n);
  for (const Spring& s : springs_) {
    next[s.a].push_back(s.b);
    next[s.b].push_back(s.a);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (master_of_[i] >= 0) {
      next[i].push_back(static_cast<std::size_t>(master_of_[i]));
      next[static_cast<std::size_t>(master_of_[i])].push_back(i);
    }
  }
  std::vector<char> reached(known_);
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < n; ++i) {
    if (known_[i]) queue.push_back(i);
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
                                 name_, mesh.node_id(nodes_[static_cast<std::size_t>(stray - reached.begin())])));
  }
}

/// Energy sum k |u_a - u_b|^2 / 2 with u = T U + u_known: the matrix sum (T_a - T_b)^T k (T_a - T_b).
void PassiveSurface::factorise() {
  const std::size_t d = dim_;
  std::vector<Eigen::Triplet<double>> triplets;
  for (const Spring& s : springs_) {
    const std::array<std::size_t, 2> ends{s.a, s.b};
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
                                    static_cast<Eigen::Index>(static_cast<std::size_t>(uy) * d + j), s.stiffness * sx * sy * v);
            }
          }
        }
      }
    }
  }
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(unknowns_ * d), static_cast<Eigen::Index>(unknowns_ * d));
  a.setFromTriplets(triplets.begin(), triplets.end());
  auto factors = std::make_shared<Factorisation>();
  factors->ldlt.compute(a);
  if (factors->ldlt.info() != Eigen::Success) {
    throw InputError(fmt::format("passive patch '{}': part of it touches no fixed, prescribed or sliding wall, so "
                                 "nothing drives its motion; give it another role",
                                 name_));
  }
  factors_ = std::move(factors);
}

std::vector<Vec3> PassiveSurface::solve(const RimDisplacement& rim) const {
  const std::size_t d = dim_, n = nodes_.size();
  std::vector<Vec3> result(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (known_[i] == kFromRim) result[i] = known_value(rim, nodes_[i]);
  }
  for (const Tie& t : ties_) {
    const Vec3 master = t.local_master >= 0 ? result[static_cast<std::size_t>(t.local_master)] : known_value(rim, t.master);
    result[t.slave] = rotations_[t.rotation].vector(master);
  }
  if (unknowns_ == 0) return result;

  // The right-hand side -(T_a - T_b)^T k (uk_a - uk_b) from the known parts (zero for unknown nodes).
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(unknowns_ * d));
  for (const Spring& s : springs_) {
    const Vec3 known_gap = result[s.a] - result[s.b];
    const std::array<std::size_t, 2> ends{s.a, s.b};
    for (std::size_t x = 0; x < 2; ++x) {
      const auto [ux, rx] = owner(ends[x]);
      if (ux < 0) continue;
      const double sx = x == 0 ? 1.0 : -1.0;
      for (std::size_t i = 0; i < d; ++i) {
        double v = 0.0;
        for (std::size_t c = 0; c < d; ++c) v += entry(rx, c, i) * known_gap[c];
        rhs[static_cast<Eigen::Index>(static_cast<std::size_t>(ux) * d + i)] -= s.stiffness * sx * v;
      }
    }
  }
  const Eigen::VectorXd u = factors_->ldlt.solve(rhs);
  if (!u.allFinite()) {
    throw InputError(fmt::format("passive patch '{}': part of it touches no fixed, prescribed or sliding wall, so "
                                 "nothing drives its motion; give it another role",
                                 name_));
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
