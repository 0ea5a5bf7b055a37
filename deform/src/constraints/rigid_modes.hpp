// hotmesh deform (internal): which rigid-body motions the boundary conditions leave free.
// The elastic analogy has the rigid-body motions (2D: two translations and the rotation about
// z; 3D: three and three) as its null space; the boundary conditions must remove them all, or
// the mesh's position is not determined and the stiffness on the free degrees of freedom is
// singular. A motion m is removed when some constraint sees it: a fixed node in every
// direction, a slip or sliding node along its normals, a periodic pair u_s = R u_m through
// m(x_s) - R m(x_m). With the rows r_k = n . m_k(x) of every constraint, the motions left free
// are the null space of G = sum r r^T (one small symmetric matrix, one pass over the
// constrained nodes), with the modes taken about the mesh's centroid and scaled by its size so
// that translations and rotations weigh alike.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "constraints/periodic.hpp"
#include "hotmesh/deform/mesh_names.hpp"

namespace hotmesh::deform::detail {

class RigidModes {
 public:
  explicit RigidModes(const Mesh& mesh);

  /// A node at x that may not move along `normal` (any length).
  void constrain(const Vec3& x, const Vec3& normal);
  /// A node at x that may not move at all.
  void fix(const Vec3& x);
  /// A slave at xs that follows its master at xm: u_s = R u_m.
  void tie(const Vec3& xs, const Vec3& xm, const Rotation& rotation);

  /// The rigid-body motions nothing removes, in a user's words ("translate along x", "rotate
  /// about the axis through (0, 0, 0.5) along (0, 0, 1)"); empty when every one is removed.
  std::vector<std::string> free_motions() const;

 private:
  /// m_k(x) for every mode k: translations e_c, rotations e_c x (x - centre) / size.
  Eigen::MatrixXd modes_at(const Vec3& x) const;  ///< 3 x modes
  void add_row(const Eigen::VectorXd& row);

  int dim_;
  Eigen::Index modes_;  ///< 3 in 2D, 6 in 3D
  Vec3 centre_;
  double size_;
  Eigen::MatrixXd gram_;
};

}  // namespace hotmesh::deform::detail
