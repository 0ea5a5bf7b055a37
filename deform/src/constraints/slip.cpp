// hotmesh deform: slip patches, each held on its best-fit plane (eq. 11).
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "constraints/boundary_builder.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::deform::detail {

namespace {

/// Best-fit plane (line in 2D) of a slip patch; throws if the patch is not planar.
SlipPlane slip_plane(const Mesh& mesh, const Patch& patch) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (NodeId n : patch.nodes) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    centre += Eigen::Vector3d(p.x, p.y, p.z);
  }
  centre /= static_cast<double>(patch.nodes.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (NodeId n : patch.nodes) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    const Eigen::Vector3d r = Eigen::Vector3d(p.x, p.y, p.z) - centre;
    covariance += r * r.transpose();
  }
  Vec3 normal;
  if (mesh.dimension == 2) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance.topLeftCorner<2, 2>());
    normal = {eigen.eigenvectors()(0, 0), eigen.eigenvectors()(1, 0), 0.0};
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    normal = {eigen.eigenvectors()(0, 0), eigen.eigenvectors()(1, 0), eigen.eigenvectors()(2, 0)};
  }
  const Vec3 origin{centre.x(), centre.y(), centre.z()};
  double worst = 0.0;
  for (NodeId n : patch.nodes) worst = std::max(worst, std::abs(dot(mesh.points[static_cast<std::size_t>(n)] - origin, normal)));
  const double size = bounding_diagonal(mesh.points, patch.nodes);
  if (worst > 1e-6 * size) {
    throw InputError(fmt::format("patch '{}' has role slip but is not planar: a node is {:.3g} off its best-fit {} "
                                 "(patch size {:.3g}); slip keeps nodes on a plane, use sliding for curved walls",
                                 patch.name, worst, mesh.dimension == 2 ? "line" : "plane", size));
  }
  return {origin, normal / norm(normal)};
}

}  // namespace

/// Slip planes: constrain slip nodes now; sliding nodes collect them below.
void BoundaryBuilder::constrain_slip_nodes() {
  for (std::size_t p = 0; p < mesh_.patches.size(); ++p) {
    if (motion_of_[p]->role != BoundaryRole::slip || mesh_.patches[p].nodes.empty()) continue;
    plane_of_[p] = static_cast<int>(setup_.slip_planes.size());
    setup_.slip_planes.push_back(slip_plane(mesh_, mesh_.patches[p]));
    for (NodeId n : mesh_.patches[p].nodes) {
      if (has_role(n, BoundaryRole::slip)) setup_.constraints.constrain(n, setup_.slip_planes.back().normal);
    }
  }
}

}  // namespace hotmesh::deform::detail
