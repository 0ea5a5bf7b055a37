// hotmesh geometry: partition-of-unity RBF interpolation of scattered vector data (see
// scattered_field.hpp for the method and why). Here: merging duplicates, the octree of patches,
// the local solves and the evaluation.
//
// Patch j has centre c_j, radius R_j and the points p_i with |p_i - c_j| < R_j (i in I_j). Its
// interpolant is
//   s_j(x) = sum_{i in I_j} lambda_i |x - p_i|^3 + c_0 + sum_{k=1..d} c_k z_k(x),
//   z_k(x) = v_k . (x - m) / sigma_k,
// with m the centroid of the points, v_k their principal directions and sigma_k the RMS
// extents along them, keeping the d directions with sigma_k > flatness * sigma_1 and above the
// coordinates' rounding (the affine hull; the z_k are whitened so the polynomial block is well
// conditioned). The coefficients solve, for each component of the values f,
//   [ A    P ] [ lambda ]   [ f ]     A_ik = |p_i - p_k|^3,   P_i = [1  z_1(p_i) .. z_d(p_i)],
//   [ P^T  0 ] [   c    ] = [ 0 ],
// which has one solution: r^3 is conditionally positive definite of order 2 and the points
// are unisolvent for linear polynomials on their hull (Wendland, Scattered Data Approximation,
// 2005, chapter 8). The field is the Shepard blend
//   s(x) = sum_j psi_j(x) s_j(x) / sum_j psi_j(x),   psi_j(x) = psi(|x - c_j| / R_j),
//   psi(r) = (1 - r)^4 (4 r + 1) for r < 1, 0 beyond   (Wendland's C2 function).
// psi_j(p_i) > 0 exactly when i is in I_j (the same test |x - c_j|^2 < R_j^2 decides both), so
// s(p_i) = f_i; a linear f is reproduced by every s_j and so by s.
#include "hotmesh/geometry/scattered_field.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "reconstruct/scattered_samples.hpp"

namespace hotmesh::geometry {

namespace {

using Index = std::uint32_t;

/// Deepest octree level: cells 2^-32 of the bounding cube (points closer are merged long before).
constexpr int kMaxDepth = 32;
/// A grown ball reaches this factor beyond its min_patch_points-th nearest point, which so
/// gets a weight well above zero.
constexpr double kGrowth = 1.1;
const double kSqrt3 = std::sqrt(3.0);

double squared_distance(const Vec3& a, const Vec3& b) {
  const Vec3 d = a - b;
  return dot(d, d);
}

/// Wendland's C2 function psi(r), r = sqrt(d2 / r2) < 1.
double wendland(double d2, double r2) {
  const double r = std::sqrt(d2 / r2);
  const double t = 1.0 - r;
  return t * t * t * t * (4.0 * r + 1.0);
}

/// The corners of the points' bounding box.
std::array<Vec3, 2> bounding_box(const std::vector<Vec3>& points) {
  std::array<Vec3, 2> box{points.front(), points.front()};
  for (const Vec3& p : points) {
    for (int k = 0; k < 3; ++k) {
      box[0][k] = std::min(box[0][k], p[k]);
      box[1][k] = std::max(box[1][k], p[k]);
    }
  }
  return box;
}

std::string format(const Vec3& v) {
  std::ostringstream out;
  out.precision(9);
  out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return out.str();
}

}  // namespace

Hull affine_hull(const std::vector<Vec3>& points, std::span<const Index> members, double flatness, double noise) {
  Hull hull;
  for (const Index i : members) hull.centroid += points[i];
  hull.centroid = hull.centroid / static_cast<double>(members.size());
  Eigen::MatrixX3d centred(static_cast<Eigen::Index>(members.size()), 3);
  for (Eigen::Index r = 0; r < centred.rows(); ++r) {
    const Vec3 q = points[members[static_cast<std::size_t>(r)]] - hull.centroid;
    centred.row(r) << q.x, q.y, q.z;
  }
  const Eigen::JacobiSVD<Eigen::MatrixX3d> svd(centred, Eigen::ComputeFullV);
  const double rms = 1.0 / std::sqrt(static_cast<double>(members.size()));
  for (int k = 0; k < 3; ++k) {
    hull.axes[static_cast<std::size_t>(k)] = {svd.matrixV()(0, k), svd.matrixV()(1, k), svd.matrixV()(2, k)};
    if (k >= svd.singularValues().size()) break;  // fewer than 3 points
    hull.extent[static_cast<std::size_t>(k)] = svd.singularValues()(k) * rms;
    const double extent = hull.extent[static_cast<std::size_t>(k)];
    if (extent > flatness * hull.extent[0] && extent > noise) hull.dimension = k + 1;
  }
  return hull;
}

double rounding(const std::vector<Vec3>& points, const ScatteredFieldOptions& options) {
  double largest = 0.0;
  for (const Vec3& p : points) largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return options.coordinate_precision * largest;
}

namespace {

void check_options(const ScatteredFieldOptions& o) {
  if (o.min_patch_points < 1 || o.max_patch_points < o.min_patch_points) {
    throw std::invalid_argument("scattered field: need 1 <= min_patch_points <= max_patch_points");
  }
  if (!(o.overlap >= 1.05 && o.overlap <= 4.0)) {
    throw std::invalid_argument("scattered field: overlap must be 1.05 to 4");
  }
  if (!(o.flatness > 0.0 && o.flatness < 1.0)) {
    throw std::invalid_argument("scattered field: flatness must be in (0, 1)");
  }
  if (!(o.coordinate_precision >= 0.0 && o.coordinate_precision < 1.0)) {
    throw std::invalid_argument("scattered field: coordinate_precision must be in [0, 1)");
  }
  if (!(o.same_point >= 0.0 && o.same_value >= 0.0)) {
    throw std::invalid_argument("scattered field: duplicate tolerances must not be negative");
  }
}

/// The samples with points closer than the same-point tolerance merged into the first of them
/// (its index returned); throws InputError if their values differ. A hash grid of cells the
/// size of the tolerance: a point's duplicates lie in its own or a neighbouring cell.
std::vector<Index> distinct_samples(const std::vector<Vec3>& points, const std::vector<Vec3>& values,
                                    const ScatteredFieldOptions& options) {
  if (points.empty()) return {};
  const auto [lo, hi] = bounding_box(points);
  double largest_value = 0.0;
  for (const Vec3& v : values) largest_value = std::max(largest_value, norm(v));
  const double tolerance = options.same_point * distance(lo, hi);
  const double value_tolerance = options.same_value * largest_value;
  const double cell = tolerance > 0.0 ? tolerance : 1.0;  // all points equal, or no merging tolerance

  using Key = std::array<std::int64_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      const auto mix = [](std::uint64_t h, std::int64_t v) {
        return (h ^ static_cast<std::uint64_t>(v)) * 0x100000001b3ULL;
      };
      return static_cast<std::size_t>(mix(mix(mix(0xcbf29ce484222325ULL, k[0]), k[1]), k[2]));
    }
  };
  std::unordered_map<Key, std::vector<Index>, KeyHash> cells;
  cells.reserve(points.size());
  std::vector<Index> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    Key key;
    for (std::size_t k = 0; k < 3; ++k) key[k] = static_cast<std::int64_t>(std::floor((points[i][k] - lo[k]) / cell));
    std::int64_t same = -1;
    for (int n = 0; n < 27 && same < 0; ++n) {
      const Key near{key[0] + n % 3 - 1, key[1] + n / 3 % 3 - 1, key[2] + n / 9 - 1};
      const auto found = cells.find(near);
      if (found == cells.end()) continue;
      for (const Index j : found->second) {
        if (squared_distance(points[i], points[j]) <= tolerance * tolerance) {
          same = j;
          break;
        }
      }
    }
    if (same < 0) {
      cells[key].push_back(static_cast<Index>(i));
      kept.push_back(static_cast<Index>(i));
    } else if (distance(values[i], values[static_cast<std::size_t>(same)]) > value_tolerance) {
      throw InputError("scattered data: samples " + std::to_string(same) + " and " + std::to_string(i) +
                       " (counting from 0) are at the same point " + format(points[i]) +
                       " but have different values " + format(values[static_cast<std::size_t>(same)]) + " and " +
                       format(values[i]));
    }
  }
  return kept;
}

}  // namespace

struct ScatteredField::Impl {
  /// An octree cell with points. A leaf is a patch: centre and radius of its ball. An inner
  /// node's radius bounds the balls of all patches below it.
  struct Node {
    Vec3 centre;
    double radius = 0.0;
    double radius2 = 0.0;  ///< radius * radius: the one value both the set-up and the weights test against
    Index first_child = 0;
    Index children = 0;
    std::int32_t patch = -1;
  };
  /// s_j(x) = constant + gradient . (x - origin) + sum_i lambda_i |x - origin - q_i|^3, with
  /// q_i = p_i - origin.
  struct Patch {
    Vec3 origin;
    Vec3 constant;
    std::array<Vec3, 3> gradient;  ///< one row per component of the values
    std::size_t first = 0;         ///< into kernels: q_x, q_y, q_z, lambda_x, lambda_y, lambda_z, count each
    std::size_t count = 0;
  };

  class Builder;

  std::vector<Node> nodes;  ///< nodes[0] is the root; the children of a node are contiguous
  std::vector<Patch> patches;
  std::vector<double> kernels;  ///< the patches' points and coefficients, as columns (SIMD)

  Vec3 patch_value(const Patch& p, const Vec3& x) const {
    const Vec3 y = x - p.origin;
    Vec3 s = p.constant + Vec3{dot(p.gradient[0], y), dot(p.gradient[1], y), dot(p.gradient[2], y)};
    // In chunks on the stack; Eigen's array sqrt is vectorised (std::sqrt is not, for errno).
    constexpr Eigen::Index kChunk = 64;
    const auto n = static_cast<Eigen::Index>(p.count);
    for (Eigen::Index start = 0; start < n; start += kChunk) {
      const Eigen::Index m = std::min(kChunk, n - start);
      const auto column = [&](Eigen::Index k) {
        const double* data = kernels.data() + p.first + static_cast<std::size_t>(k * n + start);
        return Eigen::Map<const Eigen::ArrayXd>(data, m);
      };
      Eigen::Array<double, Eigen::Dynamic, 1, 0, kChunk, 1> r3 =
          (column(0) - y.x).square() + (column(1) - y.y).square() + (column(2) - y.z).square();
      r3 *= r3.sqrt();
      s += Vec3{(column(3) * r3).sum(), (column(4) * r3).sum(), (column(5) * r3).sum()};
    }
    return s;
  }

  /// Sum over the patches whose balls hold x of psi_j(x) s_j(x), and of psi_j(x).
  Vec3 blend(const Vec3& x, double& weight) const {
    std::array<Index, 8 * (kMaxDepth + 1)> stack;  // a node's children replace it: depth * 7 + 1 at most
    std::size_t top = 0;
    stack[top++] = 0;
    Vec3 sum;
    weight = 0.0;
    while (top > 0) {
      const Node& node = nodes[stack[--top]];
      const double d2 = squared_distance(x, node.centre);
      if (!(d2 < node.radius2)) continue;
      if (node.patch >= 0) {
        const double w = wendland(d2, node.radius2);
        sum += w * patch_value(patches[static_cast<std::size_t>(node.patch)], x);
        weight += w;
      } else {
        for (Index c = 0; c < node.children; ++c) stack[top++] = node.first_child + c;
      }
    }
    return sum;
  }

  /// The patch whose ball is nearest to x (smallest |x - c_j| - R_j) and that gap: branch and
  /// bound, an inner node's |x - c| - radius being a lower bound for the patches below it.
  std::pair<const Patch*, double> nearest_patch(const Vec3& x) const {
    std::array<Index, 8 * (kMaxDepth + 1)> stack;
    std::size_t top = 0;
    stack[top++] = 0;
    double best = std::numeric_limits<double>::infinity();
    std::int32_t found = 0;
    while (top > 0) {
      const Node& node = nodes[stack[--top]];
      const double gap = std::sqrt(squared_distance(x, node.centre)) - node.radius;
      if (!(gap < best)) continue;
      if (node.patch >= 0) {
        best = gap;
        found = node.patch;
      } else {
        for (Index c = 0; c < node.children; ++c) stack[top++] = node.first_child + c;
      }
    }
    return {&patches[static_cast<std::size_t>(found)], best};
  }
};

/// Builds the octree of patches and solves their systems (depth first, children contiguous).
class ScatteredField::Impl::Builder {
 public:
  Builder(const std::vector<Vec3>& points, const std::vector<Vec3>& values, const ScatteredFieldOptions& options,
          Impl& out, ScatteredFieldReport& report)
      : points_(points), values_(values), options_(options), out_(out), report_(report),
        rounding_(rounding(points, options)) {}

  void build() {
    const auto [lo, hi] = bounding_box(points_);
    const double half = 0.5 * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    std::vector<Index> all(points_.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
    out_.nodes.emplace_back();
    const Vec3 centre = 0.5 * (lo + hi);
    // The root's ball holds every point: the cube lies inside it.
    grow(0, centre, half, all, filter(all, centre, ball_radius(half)), 0);
  }

 private:
  /// A ball that holds every point within it: an ancestor's, for growing a patch's ball.
  struct Ancestor {
    Vec3 centre;
    double radius;
    const std::vector<Index>* members;
  };

  double ball_radius(double half) const { return options_.overlap * kSqrt3 * half; }

  /// The points of `candidates` inside the ball (centre, radius): |p - centre|^2 < radius^2.
  std::vector<Index> filter(const std::vector<Index>& candidates, const Vec3& centre, double radius) const {
    const double r2 = radius * radius;
    std::vector<Index> inside;
    for (const Index i : candidates) {
      if (squared_distance(points_[i], centre) < r2) inside.push_back(i);
    }
    return inside;
  }

  /// Node `id` for the cube (centre, half side) holding `cell` points, whose ball holds `ball`.
  /// A child's ball lies inside its parent's (overlap >= 1), so it is filtered from it.
  void grow(Index id, const Vec3& centre, double half, const std::vector<Index>& cell, const std::vector<Index>& ball,
            int depth) {
    out_.nodes[id].centre = centre;
    if (ball.size() <= options_.max_patch_points || depth == kMaxDepth) {
      make_patch(id, centre, ball_radius(half), ball);
      return;
    }
    std::array<std::vector<Index>, 8> octants;
    for (const Index i : cell) {
      const Vec3& p = points_[i];
      octants[(p.x >= centre.x ? 1u : 0u) | (p.y >= centre.y ? 2u : 0u) | (p.z >= centre.z ? 4u : 0u)].push_back(i);
    }
    const auto first = static_cast<Index>(out_.nodes.size());
    Index count = 0;
    for (const auto& octant : octants) count += octant.empty() ? 0u : 1u;
    out_.nodes.resize(out_.nodes.size() + count);
    out_.nodes[id].first_child = first;
    out_.nodes[id].children = count;
    ancestors_.push_back({centre, ball_radius(half), &ball});
    Index child = first;
    for (std::size_t o = 0; o < 8; ++o) {
      if (octants[o].empty()) continue;
      const double h = 0.5 * half;
      const Vec3 c = centre + Vec3{o & 1u ? h : -h, o & 2u ? h : -h, o & 4u ? h : -h};
      grow(child++, c, h, octants[o], filter(ball, c, ball_radius(h)), depth + 1);
    }
    ancestors_.pop_back();
    double bound = 0.0;
    for (Index c = first; c < first + count; ++c) {
      bound = std::max(bound, distance(centre, out_.nodes[c].centre) + out_.nodes[c].radius);
    }
    bound *= 1.0 + 1e-12;  // rounding must not hide a patch's ball
    out_.nodes[id].radius = bound;
    out_.nodes[id].radius2 = bound * bound;
  }

  /// Leaf `id` becomes a patch: its ball, grown to min_patch_points points if it holds fewer
  /// (from the nearest ancestor whose ball holds the grown one), and the local solve.
  void make_patch(Index id, const Vec3& centre, double radius, std::vector<Index> members) {
    const std::size_t wanted = std::min(options_.min_patch_points, points_.size());
    for (auto a = ancestors_.rbegin(); members.size() < wanted && a != ancestors_.rend(); ++a) {
      std::vector<double> d2;
      d2.reserve(a->members->size());
      for (const Index i : *a->members) d2.push_back(squared_distance(points_[i], centre));
      std::nth_element(d2.begin(), d2.begin() + static_cast<std::ptrdiff_t>(wanted - 1), d2.end());
      const double grown = kGrowth * std::sqrt(d2[wanted - 1]);
      if (a + 1 == ancestors_.rend() || distance(centre, a->centre) + grown < a->radius) {
        radius = grown;
        members = filter(*a->members, centre, radius);
      }
    }
    Node& node = out_.nodes[id];
    node.radius = radius;
    node.radius2 = radius * radius;
    node.patch = static_cast<std::int32_t>(out_.patches.size());
    out_.patches.push_back(solve(members));
  }

  /// The patch interpolant through `members` (the system in the comment at the top).
  Patch solve(const std::vector<Index>& members) {
    const Hull hull = affine_hull(points_, members, options_.flatness, rounding_);
    const auto n = static_cast<Eigen::Index>(members.size());
    const Eigen::Index d = hull.dimension;
    Patch patch;
    patch.origin = hull.centroid;
    patch.first = out_.kernels.size();
    patch.count = members.size();
    std::vector<Vec3> q;
    for (const Index i : members) q.push_back(points_[i] - hull.centroid);

    double scale = 0.0;  // kernel argument in units of the patch size: entries of A at most 8
    for (const Vec3& v : q) scale = std::max(scale, norm(v));
    if (scale == 0.0) scale = 1.0;
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + 1 + d, n + 1 + d);
    Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(n + 1 + d, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3& qi = q[static_cast<std::size_t>(i)];
      for (Eigen::Index k = 0; k < i; ++k) {
        const double r = distance(qi, q[static_cast<std::size_t>(k)]) / scale;
        m(i, k) = m(k, i) = r * r * r;
      }
      m(i, n) = m(n, i) = 1.0;
      for (Eigen::Index k = 0; k < d; ++k) {
        const auto sk = static_cast<std::size_t>(k);
        m(i, n + 1 + k) = m(n + 1 + k, i) = dot(hull.axes[sk], qi) / hull.extent[sk];
      }
      const Vec3& f = values_[members[static_cast<std::size_t>(i)]];
      rhs.row(i) << f.x, f.y, f.z;
    }
    const Eigen::MatrixX3d c = Eigen::PartialPivLU<Eigen::MatrixXd>(m).solve(rhs);

    const double kernel_scale = 1.0 / (scale * scale * scale);
    for (std::size_t k = 0; k < 3; ++k) {
      for (const Vec3& qi : q) out_.kernels.push_back(qi[k]);
    }
    for (Eigen::Index k = 0; k < 3; ++k) {
      for (Eigen::Index i = 0; i < n; ++i) out_.kernels.push_back(c(i, k) * kernel_scale);
    }
    patch.constant = {c(n, 0), c(n, 1), c(n, 2)};
    for (std::size_t comp = 0; comp < 3; ++comp) {
      for (Eigen::Index k = 0; k < d; ++k) {
        const auto sk = static_cast<std::size_t>(k);
        patch.gradient[comp] += hull.axes[sk] * (c(n + 1 + k, static_cast<Eigen::Index>(comp)) / hull.extent[sk]);
      }
    }

    for (const Index i : members) {
      const double residual = distance(out_.patch_value(patch, points_[i]), values_[i]);
      report_.max_residual = std::max(report_.max_residual, residual);
    }
    report_.flat_patches += hull.dimension < 3 ? 1 : 0;
    report_.largest_patch = std::max(report_.largest_patch, members.size());
    return patch;
  }

  const std::vector<Vec3>& points_;
  const std::vector<Vec3>& values_;
  const ScatteredFieldOptions& options_;
  Impl& out_;
  ScatteredFieldReport& report_;
  double rounding_;  ///< extents below this are the coordinates' rounding
  std::vector<Ancestor> ancestors_;
};

DistinctSamples distinct_finite_samples(std::vector<Vec3> points, std::vector<Vec3> values,
                                        const ScatteredFieldOptions& options) {
  if (points.size() != values.size()) {
    throw std::invalid_argument("scattered field: " + std::to_string(points.size()) + " points but " +
                                std::to_string(values.size()) + " values");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!is_finite(points[i]) || !is_finite(values[i])) {
      throw InputError("scattered data: sample " + std::to_string(i) + " (counting from 0) has a coordinate or value " +
                       "that is not a finite number: point " + format(points[i]) + ", value " + format(values[i]));
    }
  }
  const std::size_t samples = points.size();
  const std::vector<Index> kept = distinct_samples(points, values, options);
  if (kept.size() < points.size()) {
    for (std::size_t j = 0; j < kept.size(); ++j) {
      points[j] = points[kept[j]];
      values[j] = values[kept[j]];
    }
    points.resize(kept.size());
    values.resize(kept.size());
  }
  return {std::move(points), std::move(values), samples - kept.size()};
}

ScatteredField::ScatteredField(std::vector<Vec3> sample_points, std::vector<Vec3> sample_values,
                               const ScatteredFieldOptions& options) {
  check_options(options);
  report_.samples = sample_points.size();
  DistinctSamples distinct = distinct_finite_samples(std::move(sample_points), std::move(sample_values), options);
  std::vector<Vec3>& points = distinct.points;
  const std::vector<Vec3>& values = distinct.values;
  report_.points = points.size();
  report_.merged_duplicates = distinct.merged;
  std::vector<Index> all(points.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
  if (points.size() < 3) {
    throw InputError("scattered data: a field over a surface needs at least 3 distinct points not on one line, got " +
                     std::to_string(points.size()) + " (of " + std::to_string(report_.samples) + " samples)");
  }
  const Hull hull = affine_hull(points, all, options.flatness, rounding(points, options));
  if (hull.dimension < 2) {
    throw InputError("scattered data: a field over a surface needs at least 3 points not on one line; all " +
                     std::to_string(points.size()) + " distinct points lie on the line through " +
                     format(hull.centroid) + " along " + format(hull.axes[0]));
  }

  auto impl = std::make_shared<Impl>();
  Impl::Builder(points, values, options, *impl, report_).build();
  report_.patches = impl->patches.size();
  report_.mean_patch = static_cast<double>(impl->kernels.size() / 6) / static_cast<double>(impl->patches.size());
  impl_ = std::move(impl);
}

Vec3 ScatteredField::operator()(const Vec3& x) const {
  if (!is_finite(x)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  double weight = 0.0;
  const Vec3 sum = impl_->blend(x, weight);
  if (weight > 0.0) return sum / weight;
  return impl_->patch_value(*impl_->nearest_patch(x).first, x);
}

double ScatteredField::outside(const Vec3& x) const {
  return std::max(0.0, impl_->nearest_patch(x).second);
}

}  // namespace hotmesh::geometry
