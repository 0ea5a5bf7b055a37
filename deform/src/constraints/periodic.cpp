// hotmesh deform: rotational periodicity (node pairing and the T^T K T reduction).
#include "constraints/periodic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

#include <fmt/format.h>

#include "support/nearest_point.hpp"

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::deform::detail {

Rotation::Rotation(const geometry::Axis& axis, double angle) : origin_(axis.origin()) {
  // Rodrigues: R = cos a I + sin a [k]x + (1 - cos a) k k^T
  const Vec3 k = axis.direction();
  const double c = std::cos(angle), s = std::sin(angle);
  const std::array<std::array<double, 3>, 3> cross{{{0, -k.z, k.y}, {k.z, 0, -k.x}, {-k.y, k.x, 0}}};
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      r_[i][j] = (i == j ? c : 0.0) + s * cross[i][j] + (1.0 - c) * k[i] * k[j];
    }
  }
}

Vec3 Rotation::vector(const Vec3& v) const {
  return {r_[0][0] * v.x + r_[0][1] * v.y + r_[0][2] * v.z, r_[1][0] * v.x + r_[1][1] * v.y + r_[1][2] * v.z,
          r_[2][0] * v.x + r_[2][1] * v.y + r_[2][2] * v.z};
}

Vec3 Rotation::inverse_vector(const Vec3& v) const {
  return {r_[0][0] * v.x + r_[1][0] * v.y + r_[2][0] * v.z, r_[0][1] * v.x + r_[1][1] * v.y + r_[2][1] * v.z,
          r_[0][2] * v.x + r_[1][2] * v.y + r_[2][2] * v.z};
}

void PeriodicCoupling::add(const Mesh& mesh, const Patch& master, const Patch& slave, const geometry::Axis& axis,
                           double angle, double tolerance) {
  if (slave_of_.empty()) slave_of_.assign(mesh.node_count(), -1);
  const Rotation rotation(axis, angle);
  std::vector<Vec3> targets;
  for (NodeId n : slave.nodes) targets.push_back(mesh.points[static_cast<std::size_t>(n)]);
  const NearestPoint tree(targets);
  std::vector<char> taken(slave.nodes.size(), 0);
  std::size_t unmatched = 0;
  std::string examples;
  std::vector<PeriodicPair> found;
  for (NodeId m : master.nodes) {
    const Vec3 image = rotation.point(mesh.points[static_cast<std::size_t>(m)]);
    const auto nearest = tree.nearest(image);
    const bool ok = nearest.index >= 0 && nearest.distance <= tolerance && !taken[static_cast<std::size_t>(nearest.index)];
    if (!ok) {
      if (unmatched++ < 5) {
        examples += fmt::format("\n  node {} of '{}' turned onto ({:.6g}, {:.6g}, {:.6g}): nearest node of '{}' is {:.3g} away",
                                mesh.node_id(m), master.name, image.x, image.y, image.z, slave.name, nearest.distance);
      }
      continue;
    }
    taken[static_cast<std::size_t>(nearest.index)] = 1;
    found.push_back({m, slave.nodes[static_cast<std::size_t>(nearest.index)], rotations_.size()});
  }
  const auto left = static_cast<std::size_t>(std::count(taken.begin(), taken.end(), 0));
  if (unmatched > 0 || left > 0) {
    throw InputError(fmt::format("periodic patches '{}' and '{}' do not match by a rotation of {:.6g} degrees about the "
                                 "axis (tolerance {:.3g}): {} nodes of '{}' have no partner, {} nodes of '{}' are left "
                                 "over{}\nCheck angle_deg, its sign and the axis.",
                                 master.name, slave.name, angle * 180.0 / std::numbers::pi, tolerance, unmatched, master.name, left,
                                 slave.name, examples));
  }
  for (const PeriodicPair& p : found) {
    if (slave_of_[static_cast<std::size_t>(p.slave)] >= 0 || slave_of_[static_cast<std::size_t>(p.master)] >= 0) {
      throw InputError(fmt::format("node {} is coupled by two periodic pairs; a node can follow one partner only",
                                   mesh.node_id(p.slave)));
    }
    slave_of_[static_cast<std::size_t>(p.slave)] = static_cast<std::int32_t>(pairs_.size());
    pairs_.push_back(p);
  }
  rotations_.push_back(rotation);
}

void PeriodicCoupling::expand(std::span<double> u) const {
  for (const PeriodicPair& p : pairs_) {
    const auto m = static_cast<std::size_t>(p.master) * dim_, s = static_cast<std::size_t>(p.slave) * dim_;
    const Vec3 v = rotations_[p.rotation].vector({u[m], u[m + 1], dim_ == 3 ? u[m + 2] : 0.0});
    for (std::size_t c = 0; c < dim_; ++c) u[s + c] = v[c];
  }
}

void PeriodicCoupling::fold(std::span<double> f) const {
  for (const PeriodicPair& p : pairs_) {
    const auto m = static_cast<std::size_t>(p.master) * dim_, s = static_cast<std::size_t>(p.slave) * dim_;
    const Vec3 v = rotations_[p.rotation].inverse_vector({f[s], f[s + 1], dim_ == 3 ? f[s + 2] : 0.0});
    for (std::size_t c = 0; c < dim_; ++c) {
      f[m + c] += v[c];
      f[s + c] = 0.0;
    }
  }
}

void PeriodicCoupling::fold_nodal(std::span<double> values) const {
  for (const PeriodicPair& p : pairs_) {
    values[static_cast<std::size_t>(p.master)] += values[static_cast<std::size_t>(p.slave)];
    values[static_cast<std::size_t>(p.slave)] = 0.0;
  }
}

void PeriodicCoupling::fold_blocks(std::span<double> blocks) const {
  const std::size_t bb = dim_ * dim_;
  for (const PeriodicPair& p : pairs_) {
    double* bm = blocks.data() + static_cast<std::size_t>(p.master) * bb;
    double* bs = blocks.data() + static_cast<std::size_t>(p.slave) * bb;
    const Rotation& r = rotations_[p.rotation];
    for (std::size_t i = 0; i < dim_; ++i) {  // B_m += R^T B_s R
      for (std::size_t j = 0; j < dim_; ++j) {
        double sum = 0.0;
        for (std::size_t k = 0; k < dim_; ++k) {
          for (std::size_t l = 0; l < dim_; ++l) sum += r.entry(k, i) * bs[k * dim_ + l] * r.entry(l, j);
        }
        bm[i * dim_ + j] += sum;
      }
    }
    std::fill(bs, bs + bb, 0.0);
  }
}

double PeriodicCoupling::mismatch(std::span<const Vec3> points) const {
  double largest = 0.0;
  for (const PeriodicPair& p : pairs_) {
    const Vec3 image = rotations_[p.rotation].point(points[static_cast<std::size_t>(p.master)]);
    largest = std::max(largest, distance(image, points[static_cast<std::size_t>(p.slave)]));
  }
  return largest;
}

}  // namespace hotmesh::deform::detail
