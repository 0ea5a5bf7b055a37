// hotmesh deform (internal): the system of one increment of the mesh motion (from the mesh x
// reached so far to stage b) as the Newton solver sees it (NewtonOperator, newton.hpp): the
// residual R(n) = K(n) u(n) - f of each step, from the element matrices of K(n) at the current
// geometry x + u (newton_residual), and after each step the sliding nodes projected back onto
// their boundaries and the periodic slaves after their masters.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "constraints/boundary_conditions.hpp"
#include "constraints/sliding.hpp"
#include "hotmesh/deform/stiffness_operator.hpp"
#include "hotmesh/parallel/rank_exchange.hpp"
#include "motion/newton.hpp"
#include "storage/linear_solver.hpp"

namespace hotmesh::deform::detail {

/// The residual of a Newton step, R(n) = P T^T K(n) u(n) of eq. (7), at s.points: folded onto
/// periodic masters, only its tangential part F_t at sliding nodes (eq. 17); and each node's
/// stiffness D, which scales its norm (scaled_residual_norm). K(n) comes from the node blocks
/// of `k`, updated here at s.points (R = K u by its product); without them from the element
/// pass of the solver's `assembler`, which computes each K_e once for its matrix and for R,
/// each rank its cells, summed over `ranks`. Adds the element work to timings.assembly.
/// With a `reference`, also its residual from the same K(n). Without `matrix_wanted` the
/// assembler computes the residual alone (ElementAssembler).
void newton_residual(const ConstrainedSystem& s, StiffnessOperator* k, ElementAssembler* assembler,
                     const parallel::RankExchange& ranks, std::span<const double> u, std::span<double> r,
                     std::span<double> node_stiffness, MotionTimings& timings, const ReferenceResidual* reference = nullptr,
                     bool matrix_wanted = true);

/// x + u into `out` (d displacements a node in u).
void displace(std::span<const Vec3> x, std::span<const double> u, std::size_t d, std::span<Vec3> out);

class IncrementSystem final : public NewtonOperator {
 public:
  /// From the points `x` to stage `b`; K from the node blocks `k` if not null, else from the
  /// element pass of `assembler` (newton_residual). Adds the element work to timings.assembly
  /// and the projections to timings.projection.
  IncrementSystem(const std::vector<Vec3>& x, double b, const StiffnessKernel& kernel, BoundarySetup& setup,
                  SlidingNodes& sliding, StiffnessOperator* k, ElementAssembler* assembler,
                  const parallel::RankExchange& ranks, MotionTimings& timings)
      : x_(x), b_(b), kernel_(kernel), setup_(setup), sliding_(sliding), k_(k), assembler_(assembler), ranks_(ranks),
        timings_(timings), trial_(x.size()) {}

  std::size_t size() const override { return kernel_.size(); }
  std::size_t dofs_per_node() const override { return static_cast<std::size_t>(kernel_.dofs_per_node()); }
  ConstrainedSystem residual(std::span<const double> u, std::span<double> r, std::span<double> node_stiffness,
                             const ReferenceResidual* reference, bool matrix_wanted) override;
  double normal_slip(std::span<const double> p) const override;
  double restore(std::span<double> u) override;

  /// x + u at the last residual: the increment's new points.
  std::vector<Vec3>& points() { return trial_; }

 private:
  const std::vector<Vec3>& x_;
  double b_;
  const StiffnessKernel& kernel_;
  BoundarySetup& setup_;
  SlidingNodes& sliding_;
  StiffnessOperator* k_;
  ElementAssembler* assembler_;
  const parallel::RankExchange& ranks_;
  MotionTimings& timings_;
  std::vector<Vec3> trial_;
};

}  // namespace hotmesh::deform::detail
