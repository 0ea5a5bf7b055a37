// hotmesh deform: the rigid-body motions boundary conditions leave free (rigid_modes.hpp).
#include "constraints/rigid_modes.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace hotmesh::deform::detail {
namespace {

/// Eigenvalues of G below this fraction of the largest belong to free motions. A motion held
/// by a single node of a mesh of 10^8 boundary nodes still stands 1e-8 above the largest;
/// round-off in the normals of a surface that does not hold a motion (a cylinder turning about
/// its axis) leaves it near 1e-30.
constexpr double kFree = 1e-10;

constexpr std::array<const char*, 3> kAxisNames{"x", "y", "z"};

/// A number for a message: round-off below `zero` shown as 0.
std::string number(double v, double zero) { return fmt::format("{:.6g}", std::abs(v) <= zero ? 0.0 : v); }

std::string point(const Vec3& p, int dim, double zero) {
  if (dim == 2) return fmt::format("({}, {})", number(p.x, zero), number(p.y, zero));
  return fmt::format("({}, {}, {})", number(p.x, zero), number(p.y, zero), number(p.z, zero));
}

/// A unit direction, its largest component positive.
Vec3 canonical(Vec3 v) {
  v = v / norm(v);
  const double largest = std::abs(v.x) >= std::max(std::abs(v.y), std::abs(v.z)) ? v.x
                         : std::abs(v.y) >= std::abs(v.z)                        ? v.y
                                                                                 : v.z;
  return largest < 0.0 ? -1.0 * v : v;
}

}  // namespace

RigidModes::RigidModes(const Mesh& mesh)
    : dim_(mesh.dimension), modes_(mesh.dimension == 2 ? 3 : 6), size_(std::max(bounding_diagonal(mesh.points), 1e-300)) {
  for (const Vec3& p : mesh.points) centre_ += p;
  if (!mesh.points.empty()) centre_ = centre_ / static_cast<double>(mesh.points.size());
  if (dim_ == 2) centre_.z = 0.0;
  gram_ = Eigen::MatrixXd::Zero(modes_, modes_);
}

Eigen::MatrixXd RigidModes::modes_at(const Vec3& x) const {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3, modes_);
  const Vec3 r = (x - centre_) / size_;
  for (int c = 0; c < dim_; ++c) m(c, c) = 1.0;
  if (dim_ == 2) {  // about z
    m(0, 2) = -r.y;
    m(1, 2) = r.x;
  } else {
    for (int c = 0; c < 3; ++c) {
      Vec3 axis;
      axis[static_cast<std::size_t>(c)] = 1.0;
      const Vec3 v = cross(axis, r);
      for (int i = 0; i < 3; ++i) m(i, 3 + c) = v[static_cast<std::size_t>(i)];
    }
  }
  return m;
}

void RigidModes::add_row(const Eigen::VectorXd& row) { gram_.noalias() += row * row.transpose(); }

void RigidModes::constrain(const Vec3& x, const Vec3& normal) {
  const double length = norm(normal);
  if (!(length > 0.0)) return;
  const Eigen::Vector3d n(normal.x / length, normal.y / length, dim_ == 2 ? 0.0 : normal.z / length);
  add_row(modes_at(x).transpose() * n);
}

void RigidModes::fix(const Vec3& x) {
  const Eigen::MatrixXd m = modes_at(x);
  for (int c = 0; c < dim_; ++c) add_row(m.row(c).transpose());
}

void RigidModes::tie(const Vec3& xs, const Vec3& xm, const Rotation& rotation) {
  const Eigen::MatrixXd ms = modes_at(xs), mm = modes_at(xm);
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r(i, j) = rotation.entry(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
  }
  const Eigen::MatrixXd gap = ms - r * mm;
  for (int c = 0; c < dim_; ++c) add_row(gap.row(c).transpose());
}

std::vector<std::string> RigidModes::free_motions() const {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram_);
  const Eigen::VectorXd& values = eigen.eigenvalues();  // ascending
  const double largest = std::max(values(modes_ - 1), 0.0);
  Eigen::Index free = 0;
  while (free < modes_ && values(free) <= kFree * largest) ++free;
  if (free == 0) return {};
  const Eigen::MatrixXd null = eigen.eigenvectors().leftCols(free);  // orthonormal, in mode coordinates

  // Split the free space: combinations without rotation (translations), and the rest.
  const Eigen::Index rotations = modes_ - dim_;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(null.bottomRows(rotations), Eigen::ComputeFullV);
  Eigen::Index turning = 0;  // rank of the rotation part
  for (Eigen::Index i = 0; i < svd.singularValues().size(); ++i) turning += svd.singularValues()(i) > 1e-6 ? 1 : 0;
  const Eigen::MatrixXd rotating = null * svd.matrixV().leftCols(turning);
  const Eigen::MatrixXd translating = (null * svd.matrixV().rightCols(free - turning)).topRows(dim_);

  std::vector<std::string> motions;
  const double zero = 1e-9 * size_;
  const Eigen::Index shifts = translating.cols();
  if (shifts == dim_) {
    motions.push_back("translate in any direction");
  } else if (shifts > 0) {
    // Name the coordinate axes the free translations contain, else their directions.
    std::vector<std::string> named;
    for (int c = 0; c < dim_; ++c) {
      if (translating.row(c).norm() >= 1.0 - 1e-6) named.push_back(kAxisNames[static_cast<std::size_t>(c)]);
    }
    if (static_cast<Eigen::Index>(named.size()) == shifts) {
      motions.push_back(fmt::format("translate along {}", fmt::join(named, " and ")));
    } else {
      for (Eigen::Index k = 0; k < shifts; ++k) {
        Vec3 t;
        for (int c = 0; c < dim_; ++c) t[static_cast<std::size_t>(c)] = translating(c, k);
        motions.push_back(fmt::format("translate along {}", point(canonical(t), dim_, 1e-9)));
      }
    }
  }
  for (Eigen::Index k = 0; k < rotating.cols(); ++k) {
    // u(x) = t + w x (x - centre): a rotation about the axis through p = centre + w x t / |w|^2
    // along w, with a shift h = w . t / |w|^2 along it per radian.
    Vec3 t, w;
    for (int c = 0; c < dim_; ++c) t[static_cast<std::size_t>(c)] = rotating(c, k);
    if (dim_ == 2) {
      w = {0.0, 0.0, rotating(2, k) / size_};
    } else {
      for (int c = 0; c < 3; ++c) w[static_cast<std::size_t>(c)] = rotating(3 + c, k) / size_;
    }
    const double w2 = dot(w, w);
    const Vec3 p = centre_ + cross(w, t) / w2;
    if (dim_ == 2) {
      motions.push_back(fmt::format("rotate about the point {}", point(p, 2, zero)));
      continue;
    }
    const double shift = dot(w, t) / w2;
    motions.push_back(fmt::format("rotate about the axis through {} along {}{}", point(p, 3, zero),
                                  point(canonical(w), 3, 1e-9),
                                  std::abs(shift) > zero ? fmt::format(", moving {:.3g} along it per radian", shift) : ""));
  }
  return motions;
}

}  // namespace hotmesh::deform::detail
