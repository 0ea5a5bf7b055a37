// hotmesh deform: nodal frames for the assembled linear solve (see nodal_frames.hpp).
#include "constraints/nodal_frames.hpp"

#include <algorithm>
#include <cmath>

#include "hotmesh/deform/linear_algebra.hpp"
#include "hotmesh/mesh/parallel_loops.hpp"

namespace hotmesh::deform::detail {
namespace {

/// Unit vectors completing the orthonormal `count` first columns of q (d x d, row-major).
void complete_basis(std::array<double, 9>& q, int count, int d) {
  const auto set_column = [&](int c, const Vec3& v) {
    for (int i = 0; i < d; ++i) q[static_cast<std::size_t>(i * d + c)] = v[static_cast<std::size_t>(i)];
  };
  const auto column = [&](int c) {
    Vec3 v;
    for (int i = 0; i < d; ++i) v[static_cast<std::size_t>(i)] = q[static_cast<std::size_t>(i * d + c)];
    return v;
  };
  if (d == 2) {
    const Vec3 n = column(0);
    set_column(1, {-n.y, n.x, 0.0});
    return;
  }
  const Vec3 n = column(0);
  if (count == 2) {
    const Vec3 t = cross(n, column(1));
    set_column(2, t / norm(t));
    return;
  }
  // The Cartesian axis least aligned with n, made orthogonal to it; then n x t1.
  const Vec3 a = std::abs(n.x) <= std::abs(n.y) && std::abs(n.x) <= std::abs(n.z) ? Vec3{1, 0, 0}
                 : std::abs(n.y) <= std::abs(n.z)                                  ? Vec3{0, 1, 0}
                                                                                   : Vec3{0, 0, 1};
  Vec3 t1 = a - dot(a, n) * n;
  t1 = t1 / norm(t1);
  set_column(1, t1);
  set_column(2, cross(n, t1));
}

/// out = Q_a^T K_ab Q_b for D x D blocks; k and out have row stride `stride`.
template <std::size_t D>
void turn_block(const double* qa, const double* k, const double* qb, double* out, std::size_t stride) {
  std::array<std::array<double, D>, D> kq{};
  for (std::size_t i = 0; i < D; ++i) {
    for (std::size_t j = 0; j < D; ++j) {
      double s = 0.0;
      for (std::size_t l = 0; l < D; ++l) s += k[i * stride + l] * qb[l * D + j];
      kq[i][j] = s;
    }
  }
  for (std::size_t i = 0; i < D; ++i) {
    for (std::size_t j = 0; j < D; ++j) {
      double s = 0.0;
      for (std::size_t l = 0; l < D; ++l) s += qa[l * D + i] * kq[l][j];
      out[i * stride + j] = s;
    }
  }
}

}  // namespace

NodalFrames::NodalFrames(std::size_t nodes, int dimension)
    : dim_(dimension), owner_(nodes), constrained_(nodes, 0), slot_(nodes, -1) {
  for (std::size_t n = 0; n < nodes; ++n) owner_[n] = static_cast<NodeId>(n);
}

std::span<const double> NodalFrames::frame(NodeId n) const {
  return {q(static_cast<std::size_t>(n)), static_cast<std::size_t>(dim_ * dim_)};
}

void NodalFrames::update(const NodeConstraints& constraints, const PeriodicCoupling& periodic) {
  const int d = dim_;
  const auto dd = static_cast<std::size_t>(d * d);
  const auto nodes = static_cast<std::ptrdiff_t>(owner_.size());
  // The nodes that turn: those with normals (sliding, slip) and the periodic slaves.
  std::int32_t rotated = 0;
  for (std::size_t k = 0; k < owner_.size(); ++k) {
    const auto n = static_cast<NodeId>(k);
    slot_[k] = !constraints.is_fixed(n) && !constraints.normals(n).empty() ? rotated++ : -1;
  }
  for (const PeriodicPair& p : periodic.pairs()) {
    auto& slot = slot_[static_cast<std::size_t>(p.slave)];
    if (slot < 0) slot = rotated++;
  }
  frames_.resize(static_cast<std::size_t>(rotated) * dd);
#pragma omp parallel for schedule(static) if (nodes >= mesh::kParallelNodes)
  for (std::ptrdiff_t i = 0; i < nodes; ++i) {
    const auto n = static_cast<NodeId>(i);
    const auto k = static_cast<std::size_t>(i);
    owner_[k] = n;
    const auto normals = constraints.normals(n);
    if (constraints.is_fixed(n) || normals.empty()) {
      constrained_[k] = static_cast<std::int8_t>(constraints.is_fixed(n) ? d : 0);
      continue;
    }
    std::array<double, 9> q{};
    const int count = static_cast<int>(normals.size());
    for (int c = 0; c < count; ++c) {
      for (int r = 0; r < d; ++r) q[static_cast<std::size_t>(r * d + c)] = normals[static_cast<std::size_t>(c)][static_cast<std::size_t>(r)];
    }
    complete_basis(q, count, d);
    constrained_[k] = static_cast<std::int8_t>(count);
    std::copy(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(dd), frames_.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(slot_[k]) * dd));
  }
  // Slaves: Q_s = R Q_m, the unknowns of the master.
  for (const PeriodicPair& p : periodic.pairs()) {
    const auto s = static_cast<std::size_t>(p.slave), m = static_cast<std::size_t>(p.master);
    owner_[s] = p.master;
    const Rotation& r = periodic.rotation(p.rotation);
    const double* qm = q(m);
    double* qs = frames_.data() + static_cast<std::size_t>(slot_[s]) * dd;
    for (int i = 0; i < d; ++i) {
      for (int j = 0; j < d; ++j) {
        double v = 0.0;
        for (int l = 0; l < d; ++l) v += r.entry(static_cast<std::size_t>(i), static_cast<std::size_t>(l)) * qm[static_cast<std::size_t>(l * d + j)];
        qs[static_cast<std::size_t>(i * d + j)] = v;
      }
    }
  }
}

void NodalFrames::transform_element(std::span<const NodeId> nodes, std::span<const double> ke, std::span<double> out,
                                    std::span<std::int32_t> blocks) const {
  const auto d = static_cast<std::size_t>(dim_);
  const std::size_t corners = nodes.size();
  const std::size_t n = corners * d;
  for (std::size_t a = 0; a < corners; ++a) blocks[a] = static_cast<std::int32_t>(owner(nodes[a]));
  for (std::size_t a = 0; a < corners; ++a) {
    const auto na = static_cast<std::size_t>(nodes[a]);
    for (std::size_t b = 0; b < corners; ++b) {
      const auto nb = static_cast<std::size_t>(nodes[b]);
      const double* k = ke.data() + a * d * n + b * d;
      double* o = out.data() + a * d * n + b * d;
      if (slot_[na] < 0 && slot_[nb] < 0) {
        for (std::size_t i = 0; i < d; ++i) std::copy(k + i * n, k + i * n + d, o + i * n);
      } else if (d == 2) {
        turn_block<2>(q(na), k, q(nb), o, n);
      } else {
        turn_block<3>(q(na), k, q(nb), o, n);
      }
    }
  }
  // Constrained components keep only their diagonal.
  for (std::size_t a = 0; a < corners; ++a) {
    const auto c = static_cast<std::size_t>(constrained(nodes[a]));
    for (std::size_t i = 0; i < c; ++i) {
      const std::size_t r = a * d + i;
      const double diagonal = out[r * n + r];
      for (std::size_t j = 0; j < n; ++j) {
        out[r * n + j] = 0.0;
        out[j * n + r] = 0.0;
      }
      out[r * n + r] = diagonal;
    }
  }
}

void NodalFrames::to_frames(std::span<const double> r, std::span<double> out) const { turn(r, out, true); }

void NodalFrames::from_frames(std::span<const double> p, std::span<double> out) const { turn(p, out, false); }

void NodalFrames::turn(std::span<const double> v, std::span<double> out, bool into_frames) const {
  const auto d = static_cast<std::size_t>(dim_);
  const auto nodes = static_cast<std::ptrdiff_t>(owner_.size());
#pragma omp parallel for schedule(static) if (nodes >= mesh::kParallelNodes)
  for (std::ptrdiff_t i = 0; i < nodes; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double* qk = q(k);
    const auto c = static_cast<std::size_t>(constrained_[k]);
    const bool slave = is_slave(static_cast<NodeId>(i));
    std::array<double, 3> turned{};  // then written: v and out may be the same vector
    for (std::size_t a = 0; a < d; ++a) {
      for (std::size_t b = 0; b < d && !slave; ++b) {
        // Q^T v keeps the unconstrained components a; Q v uses the unconstrained components b.
        if (into_frames ? a >= c : b >= c) turned[a] += (into_frames ? qk[b * d + a] : qk[a * d + b]) * v[k * d + b];
      }
    }
    std::copy(turned.begin(), turned.begin() + static_cast<std::ptrdiff_t>(d), out.begin() + static_cast<std::ptrdiff_t>(k * d));
  }
}

}  // namespace hotmesh::deform::detail
