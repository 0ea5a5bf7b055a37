// hotmesh deform: boundary roles to node constraints and prescribed motions.
#include "boundary_conditions.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hotmesh/geometry/input_error.hpp"
#include "parallel.hpp"

namespace hotmesh::deform::detail {
namespace {

int priority(BoundaryRole role) {
  switch (role) {
    case BoundaryRole::fixed: return 4;
    case BoundaryRole::prescribed: return 3;
    case BoundaryRole::slip: return 1;
    default: return 0;
  }
}

double bounding_diagonal(const Mesh& mesh, std::span<const NodeId> nodes) {
  Vec3 lo = mesh.points[static_cast<std::size_t>(nodes.front())], hi = lo;
  for (NodeId n : nodes) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return norm(hi - lo);
}

/// Best-fit plane (line in 2D) normal of a slip patch; throws if the patch is not planar.
Vec3 slip_normal(const Mesh& mesh, const Patch& patch) {
  const int d = mesh.dimension;
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
  if (d == 2) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance.topLeftCorner<2, 2>());
    normal = {eigen.eigenvectors()(0, 0), eigen.eigenvectors()(1, 0), 0.0};
  } else {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
    normal = {eigen.eigenvectors()(0, 0), eigen.eigenvectors()(1, 0), eigen.eigenvectors()(2, 0)};
  }
  double worst = 0.0;
  for (NodeId n : patch.nodes) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    worst = std::max(worst, std::abs(dot(p - Vec3{centre.x(), centre.y(), centre.z()}, normal)));
  }
  const double size = bounding_diagonal(mesh, patch.nodes);
  if (worst > 1e-6 * size) {
    throw InputError(fmt::format("patch '{}' has role slip but is not planar: a node is {:.3g} off its best-fit {} "
                                 "(patch size {:.3g}); slip keeps nodes on a plane, use sliding for curved walls",
                                 patch.name, worst, d == 2 ? "line" : "plane", size));
  }
  return normal;
}

}  // namespace

Vec3 prescribed_position(const PrescribedNode& p, const Vec3& original, double lambda) {
  const Vec3 moved = p.shape->at(p.parameter, lambda, original).point;
  const Vec3 start = p.shape->at(p.parameter, 0.0, original).point;
  return original + (moved - start);
}

BoundarySetup set_up_boundaries(const Mesh& mesh, std::span<const PatchMotion> patches) {
  BoundarySetup setup{NodeConstraints(mesh.node_count(), mesh.dimension), {}, std::vector<NodeRoleCode>(mesh.node_count(), 0), {}};

  std::vector<const PatchMotion*> motion_of(mesh.patches.size(), nullptr);
  for (const PatchMotion& m : patches) {
    const auto it = std::find_if(mesh.patches.begin(), mesh.patches.end(), [&](const Patch& p) { return p.name == m.patch; });
    if (it == mesh.patches.end()) throw InputError(fmt::format("the mesh has no patch '{}'", m.patch));
    motion_of[static_cast<std::size_t>(it - mesh.patches.begin())] = &m;
    if (m.role == BoundaryRole::prescribed && !m.shape) {
      throw InputError(fmt::format("patch '{}' is prescribed but has no deflection", m.patch));
    }
    if (m.role == BoundaryRole::sliding || m.role == BoundaryRole::passive || m.role == BoundaryRole::periodic) {
      throw InputError(fmt::format("patch '{}': role {} is not available in the solver yet", m.patch, to_string(m.role)));
    }
  }
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    if (!motion_of[p]) throw InputError(fmt::format("mesh patch '{}' has no role", mesh.patches[p].name));
  }

  // The strongest role of each node, and the patch that gives it.
  std::vector<int> owner(mesh.node_count(), -1);
  auto role_priority = [&](NodeId n) {
    const int o = owner[static_cast<std::size_t>(n)];
    return o < 0 ? 0 : priority(motion_of[static_cast<std::size_t>(o)]->role);
  };
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    for (NodeId n : mesh.patches[p].nodes) {
      if (priority(motion_of[p]->role) > role_priority(n)) owner[static_cast<std::size_t>(n)] = static_cast<int>(p);
    }
  }
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    if (owner[n] >= 0) setup.roles[n] = static_cast<NodeRoleCode>(1 + static_cast<int>(motion_of[static_cast<std::size_t>(owner[n])]->role));
  }

  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    const Patch& patch = mesh.patches[p];
    const PatchMotion& m = *motion_of[p];
    if (patch.nodes.empty()) continue;
    switch (m.role) {
      case BoundaryRole::fixed:
        for (NodeId n : patch.nodes) setup.constraints.fix(n);
        break;
      case BoundaryRole::slip: {
        const Vec3 normal = slip_normal(mesh, patch);
        for (NodeId n : patch.nodes) {
          if (owner[static_cast<std::size_t>(n)] >= 0 && role_priority(n) == priority(BoundaryRole::slip)) {
            setup.constraints.constrain(n, normal);
          }
        }
        break;
      }
      case BoundaryRole::prescribed: {
        const double tolerance = m.tolerance > 0.0 ? m.tolerance : 1e-3 * bounding_diagonal(mesh, patch.nodes);
        std::vector<NodeId> nodes;
        for (NodeId n : patch.nodes) {
          if (owner[static_cast<std::size_t>(n)] == static_cast<int>(p)) nodes.push_back(n);
        }
        std::vector<geometry::ShapePoint> found(nodes.size());
#pragma omp parallel for schedule(dynamic, 64) if (static_cast<std::ptrdiff_t>(nodes.size()) >= detail::kParallelNodes)
        for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(nodes.size()); ++i) {
          const auto k = static_cast<std::size_t>(i);
          found[k] = m.shape->project(mesh.points[static_cast<std::size_t>(nodes[k])], 0.0);
        }
        std::size_t off = 0;
        std::string examples;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
          if (found[k].distance > tolerance || !std::isfinite(found[k].distance)) {
            if (off++ < 5) {
              const Vec3& x = mesh.points[static_cast<std::size_t>(nodes[k])];
              examples += fmt::format("\n  node {} at ({:.6g}, {:.6g}, {:.6g}) is {:.3g} away", mesh.node_id(nodes[k]), x.x,
                                      x.y, x.z, found[k].distance);
            }
          }
          setup.prescribed.push_back({nodes[k], found[k].parameter, m.shape.get()});
          setup.constraints.fix(nodes[k]);
        }
        if (off > 0) {
          throw InputError(fmt::format("patch '{}': {} nodes lie farther than {:.3g} from the undeformed shape of its "
                                       "deflection table:{}\nCheck that the table describes this patch (same units, same "
                                       "axis).",
                                       patch.name, off, tolerance, examples));
        }
        break;
      }
      default: break;
    }
  }

  // Fixed wins over prescribed: say so where the deflection would have moved a fixed node.
  for (std::size_t p = 0; p < mesh.patches.size(); ++p) {
    const PatchMotion& m = *motion_of[p];
    if (m.role != BoundaryRole::prescribed) continue;
    std::size_t overruled = 0;
    double largest = 0.0;
    for (NodeId n : mesh.patches[p].nodes) {
      if (owner[static_cast<std::size_t>(n)] == static_cast<int>(p)) continue;
      const Vec3& x = mesh.points[static_cast<std::size_t>(n)];
      const auto at = m.shape->project(x, 0.0);
      const double moved = distance(prescribed_position({n, at.parameter, m.shape.get()}, x, 1.0), x);
      if (moved > 0.0) {
        ++overruled;
        largest = std::max(largest, moved);
      }
    }
    if (overruled > 0) {
      setup.notes.push_back(fmt::format("patch '{}': {} nodes shared with fixed patches stay fixed although the "
                                        "deflection moves them by up to {:.3g}",
                                        mesh.patches[p].name, overruled, largest));
    }
  }
  const bool held = std::any_of(patches.begin(), patches.end(), [&](const PatchMotion& m) {
    return m.role == BoundaryRole::fixed || m.role == BoundaryRole::prescribed;
  });
  if (!held) {
    throw InputError("no patch holds the mesh in place: give at least one patch the role fixed or prescribed");
  }
  return setup;
}

}  // namespace hotmesh::deform::detail
