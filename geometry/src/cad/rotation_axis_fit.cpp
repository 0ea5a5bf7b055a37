// hotmesh geometry (internal): least-squares axis of revolution through the linear line complex
// of the surface normals (see rotation_axis_fit.hpp).
#include "cad/rotation_axis_fit.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace hotmesh::geometry::detail {

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// The axis of a Plücker vector (a, c) after removing its pitch (the helical part).
std::optional<Axis> axis_of(const Vector6& v, const Vec3& centroid, double scale) {
  Vec3 a{v(0), v(1), v(2)};
  Vec3 c{v(3), v(4), v(5)};
  const double length = norm(a);
  if (!(length > 1e-6)) return std::nullopt;
  a = a / length;
  c = c / length;
  c = c - dot(a, c) * a;
  const Vec3 foot = cross(a, c);  // the axis' point nearest to the (scaled) centroid
  const Vec3 ax{std::abs(a.x), std::abs(a.y), std::abs(a.z)};
  const double largest = ax.x >= ax.y && ax.x >= ax.z ? a.x : (ax.y >= ax.z ? a.y : a.z);
  return Axis(centroid + scale * foot, largest < 0 ? -a : a);
}

}  // namespace

double max_meridional_angle(const Axis& axis, std::span<const Vec3> points, std::span<const Vec3> normals,
                            double min_radius) {
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = points[i] - axis.origin();
    const Vec3 radial = d - dot(d, axis.direction()) * axis.direction();
    const double r = norm(radial);
    if (r <= min_radius) continue;
    const Vec3 circumferential = cross(axis.direction(), radial / r);
    worst = std::max(worst, std::asin(std::min(1.0, std::abs(dot(normals[i], circumferential)))));
  }
  return worst;
}

std::optional<Axis> fit_rotation_axis(std::span<const Vec3> points, std::span<const Vec3> normals,
                                      double angle_tolerance) {
  if (points.size() < 8 || normals.size() != points.size()) return std::nullopt;
  Vec3 centroid;
  for (const Vec3& p : points) centroid += p;
  centroid = centroid / static_cast<double>(points.size());
  double scale = 0.0;
  for (const Vec3& p : points) scale = std::max(scale, distance(p, centroid));
  if (!(scale > 0.0)) return std::nullopt;

  Matrix6 m = Matrix6::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 q = (points[i] - centroid) / scale;
    const Vec3 moment = cross(q, normals[i]);
    Vector6 row;
    row << moment.x, moment.y, moment.z, normals[i].x, normals[i].y, normals[i].z;
    m += row * row.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(m);
  const auto& values = eigen.eigenvalues();
  // Mean squared residual at the angle tolerance: below it an eigenvector fits.
  const double null = static_cast<double>(points.size()) * angle_tolerance * angle_tolerance;
  if (values(2) <= null) return std::nullopt;  // three or more fitting complexes: sphere, plane

  // A cylinder also fits the complex of lines orthogonal to its axis, (0, a): of the two
  // smallest eigenvectors try the one with the larger direction part first.
  std::optional<Axis> best;
  double best_angle = angle_tolerance;
  for (int k = 0; k < 2; ++k) {
    if (k == 1 && values(1) > null) break;
    const std::optional<Axis> axis = axis_of(eigen.eigenvectors().col(k), centroid, scale);
    if (!axis) continue;
    const double angle = max_meridional_angle(*axis, points, normals, 1e-3 * scale);
    if (angle <= best_angle) {
      best = axis;
      best_angle = angle;
    }
  }
  return best;
}

}  // namespace hotmesh::geometry::detail
