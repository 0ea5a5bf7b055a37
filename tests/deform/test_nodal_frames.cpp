// Tests of the constraints of a Newton step's linear solve as nodal frames (sliding normals
// first, periodic slaves sharing their masters' unknowns), the operator assembled in them into
// PETSc against the node-block projected operator P T^T K T P, PCGAMG's near-null space, and
// the amg solver's element pass, on small 2D and 3D sectors (sector_system.hpp).
#include <gtest/gtest.h>

#include <optional>

#include "motion/increment_system.hpp"
#include "storage/petsc_solver.hpp"
#include "sector_system.hpp"

namespace hotmesh::deform {
namespace {

using namespace sector_test;
using detail::ConstrainedOperator;

class FramesIn : public ::testing::TestWithParam<SectorCells> {};

TEST_P(FramesIn, AreOrthonormalWithTheConstrainedNormalsFirstAndSlavesTurnedByTheRotation) {
  const SectorSystem s(GetParam());
  const NodalFrames f = s.frames();
  const auto d = static_cast<std::size_t>(s.dimension());
  std::size_t two_normals = 0, slaves = 0;
  for (std::size_t n = 0; n < s.mesh.node_count(); ++n) {
    const auto node = static_cast<NodeId>(n);
    const auto q = f.frame(node);
    for (std::size_t i = 0; i < d; ++i) {
      for (std::size_t j = 0; j < d; ++j) {
        double qtq = 0.0;
        for (std::size_t l = 0; l < d; ++l) qtq += q[l * d + i] * q[l * d + j];
        EXPECT_NEAR(qtq, i == j ? 1.0 : 0.0, 1e-14) << n;
      }
    }
    if (f.is_slave(node)) {
      ++slaves;
      continue;
    }
    const auto normals = s.constraints.normals(node);
    EXPECT_EQ(f.constrained(node), s.constraints.is_fixed(node) ? s.dimension() : static_cast<int>(normals.size()));
    if (normals.size() == 2) ++two_normals;
    for (std::size_t k = 0; k < normals.size(); ++k) {
      for (std::size_t l = 0; l < d; ++l) EXPECT_NEAR(q[l * d + k], normals[k][l], 1e-14) << n;
    }
  }
  EXPECT_EQ(slaves, s.periodic.pairs().size());
  if (s.dimension() == 3) {
    EXPECT_GT(two_normals, 0u);
  }
  for (const auto& p : s.periodic.pairs()) {
    EXPECT_EQ(f.owner(p.slave), p.master);
    const auto qs = f.frame(p.slave), qm = f.frame(p.master);
    for (std::size_t i = 0; i < d; ++i) {
      for (std::size_t j = 0; j < d; ++j) {
        double rq = 0.0;
        for (std::size_t l = 0; l < d; ++l) rq += s.periodic.rotation(p.rotation).entry(i, l) * qm[l * d + j];
        EXPECT_NEAR(qs[i * d + j], rq, 1e-14);
      }
    }
  }
}

TEST_P(FramesIn, AssembledOperatorAgreesWithTheProjectedNodeBlockOperator) {
  const SectorSystem s(GetParam());
  const NodalFrames f = s.frames();
  const auto x = admissible(f, random_vector(s.stiffness.size(), 1));
  // Node blocks: y = P T^T K T P x in Cartesian components, then written in the frames.
  std::vector<double> cartesian(x.size()), y(x.size()), expected(x.size());
  f.from_frames(x, cartesian);
  ConstrainedOperator(s.stiffness, s.constraints, s.periodic).apply(cartesian, y);
  f.to_frames(y, expected);
  const auto assembled = detail::assembled_frame_product(s.system(), f, x);
  EXPECT_LE(max_difference(assembled, expected), 1e-12 * max_abs(expected));
  EXPECT_GT(max_abs(expected), 0.0);
  // Assembled again into the same matrix (every Newton step after the first): the same.
  const auto again = detail::assembled_frame_product(s.system(), f, x, true);
  EXPECT_LE(max_difference(again, expected), 1e-12 * max_abs(expected));
}

TEST_P(FramesIn, ConstrainedComponentsKeepOnlyAPositiveDiagonalAndNodesWithoutUnknownsAreLeftOut) {
  const SectorSystem s(GetParam());
  const NodalFrames f = s.frames();
  const auto d = static_cast<std::size_t>(s.dimension());
  // x~ on the constrained components only: the normals of sliding nodes, fixed nodes, slaves.
  auto x = random_vector(s.stiffness.size(), 2);
  std::size_t normals = 0, left_out = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto node = static_cast<NodeId>(i / d);
    const bool constrained = f.is_slave(node) || i % d < static_cast<std::size_t>(f.constrained(node));
    x[i] = constrained ? 1.0 + 0.5 * x[i] : 0.0;  // away from zero on the constrained ones
  }
  const auto y = detail::assembled_frame_product(s.system(), f, x);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto node = static_cast<NodeId>(i / d);
    if (f.is_slave(node) || f.constrained(node) == s.dimension()) {
      EXPECT_EQ(y[i], 0.0) << i;  // no unknowns at all: not in the matrix
      ++left_out;
    } else if (x[i] == 0.0) {
      EXPECT_EQ(y[i], 0.0) << i;  // an unknown: no coupling to the constrained components
    } else {
      EXPECT_GT(y[i] / x[i], 0.0) << i;  // a constrained normal: its own positive diagonal
      ++normals;
    }
  }
  EXPECT_GT(normals, 0u);
  EXPECT_GT(left_out, 0u);
}

TEST_P(FramesIn, SolutionsStayTangentialAtSlidingNodesAndMatchAcrossPeriodicFaces) {
  const SectorSystem s(GetParam());
  const NodalFrames f = s.frames();
  const auto d = static_cast<std::size_t>(s.dimension());
  std::vector<double> p(s.stiffness.size());
  f.from_frames(random_vector(p.size(), 3), p);
  for (std::size_t n = 0; n < s.mesh.node_count(); ++n) {
    const auto node = static_cast<NodeId>(n);
    Vec3 pn{};
    for (std::size_t i = 0; i < d; ++i) pn[i] = p[n * d + i];
    if (s.constraints.is_fixed(node)) {
      EXPECT_EQ(norm(pn), 0.0) << n;  // fixed nodes and slaves
    }
    for (const Vec3& normal : s.constraints.normals(node)) EXPECT_LT(std::abs(dot(pn, normal)), 1e-15) << n;
  }
  s.periodic.expand(p);
  for (const auto& pair : s.periodic.pairs()) {
    const auto m = static_cast<std::size_t>(pair.master) * d, sl = static_cast<std::size_t>(pair.slave) * d;
    const Vec3 turned = s.periodic.rotation(pair.rotation).vector({p[m], p[m + 1], d == 3 ? p[m + 2] : 0.0});
    for (std::size_t i = 0; i < d; ++i) EXPECT_NEAR(p[sl + i], turned[i], 1e-15);
  }
}

/// PCGAMG's near-null space: the d translations written in the frames, orthonormal. Without
/// constraints K vanishes on them; with them they live on the unknowns only, and at every
/// free Cartesian node they are one and the same combination of the translations.
TEST_P(FramesIn, NearNullSpaceIsTheTranslationsOnTheUnknowns) {
  const SectorSystem s(GetParam());
  const auto d = static_cast<std::size_t>(s.dimension());
  const NodeConstraints free(s.mesh.node_count(), s.dimension());
  const detail::PeriodicCoupling none(d);
  NodalFrames f(s.mesh.node_count(), s.dimension());
  f.update(free, none);
  const auto rigid = detail::assembled_near_null_space(s.mesh.cells, f);
  ASSERT_EQ(rigid.size(), d);
  std::vector<double> y(s.stiffness.size()), diagonal(s.stiffness.size());
  s.stiffness.diagonal(diagonal);
  for (std::size_t i = 0; i < d; ++i) {
    for (std::size_t j = 0; j < d; ++j) EXPECT_NEAR(dot(rigid[i], rigid[j]), i == j ? 1.0 : 0.0, 1e-12);
    s.stiffness.apply(rigid[i], y);  // K z = 0: the element matrices vanish on rigid motions
    EXPECT_LT(max_abs(y), 1e-10 * diagonal[0]) << i;
  }
  const NodalFrames constrained = s.frames();
  const auto modes = detail::assembled_near_null_space(s.mesh.cells, constrained);
  ASSERT_EQ(modes.size(), d);
  std::optional<std::size_t> cartesian;  // the first free node without a rotated frame
  for (std::size_t n = 0; n < s.mesh.node_count(); ++n) {
    const auto node = static_cast<NodeId>(n);
    const auto q = constrained.frame(node);
    if (constrained.constrained(node) == 0 && !constrained.is_slave(node) && q[0] == 1.0 && q[d + 1] == 1.0) {
      cartesian = n;
      break;
    }
  }
  ASSERT_TRUE(cartesian.has_value());
  for (std::size_t k = 0; k < d; ++k) {
    const auto& mode = modes[k];
    for (std::size_t j = 0; j < d; ++j) EXPECT_NEAR(dot(mode, modes[j]), k == j ? 1.0 : 0.0, 1e-12);
    for (std::size_t i = 0; i < mode.size(); ++i) {
      const auto node = static_cast<NodeId>(i / d);
      const auto q = constrained.frame(node);
      if (constrained.is_slave(node) || i % d < static_cast<std::size_t>(constrained.constrained(node))) {
        EXPECT_EQ(mode[i], 0.0) << i;
      } else if (constrained.constrained(node) == 0 && q[0] == 1.0 && q[d + 1] == 1.0) {
        EXPECT_NEAR(mode[i], mode[*cartesian * d + i % d], 1e-15) << i;
      }
    }
  }
}

/// The Newton residual R = P T^T K u of the amg solver's single element pass (element
/// matrices computed, not stored) equals the node-block operator's, and the matrix it assembled on
/// the way solves the same step. Both passes give each node's stiffness as the trace of its
/// diagonal block over d, folded onto periodic masters (the rotation keeps the trace).
TEST_P(FramesIn, AmgElementPassGivesTheResidualAndMatrixOfTheNodeBlocks) {
  SectorSystem s(GetParam());
  auto u = random_vector(s.stiffness.size(), 5);
  s.periodic.expand(u);
  SolverOptions options;
  std::vector<double> expected(u.size()), r(u.size());
  const std::size_t d = static_cast<std::size_t>(s.stiffness.dofs_per_node()), nodes = u.size() / d;
  std::vector<double> stiffness_blocks(nodes), stiffness_streamed(nodes);
  MotionTimings timings;
  const parallel::RankExchange& one = parallel::one_process();
  auto jacobi = detail::make_linear_solver(options, one, &s.stiffness);
  detail::newton_residual(s.system(), &s.stiffness, jacobi->assembler(), one, u, expected, stiffness_blocks, timings);
  options.linear = LinearSolverKind::amg;
  const ConstrainedSystem on_the_fly = s.system();
  auto amg = detail::make_linear_solver(options, one, nullptr);
  ASSERT_NE(amg->assembler(), nullptr);
  detail::newton_residual(on_the_fly, nullptr, amg->assembler(), one, u, r, stiffness_streamed, timings);
  EXPECT_LE(max_difference(r, expected), 1e-12 * max_abs(expected));
  std::vector<double> blocks(nodes * d * d), traces(nodes, 0.0);
  s.stiffness.diagonal_blocks(blocks);
  s.periodic.fold_blocks(blocks);
  for (std::size_t n = 0; n < nodes; ++n) {
    for (std::size_t i = 0; i < d; ++i) traces[n] += blocks[n * d * d + i * d + i] / static_cast<double>(d);
  }
  EXPECT_LE(max_difference(stiffness_blocks, traces), 1e-12 * max_abs(traces));
  EXPECT_LE(max_difference(stiffness_streamed, traces), 1e-12 * max_abs(traces));
  EXPECT_GT(timings.assembly, 0.0);
  std::vector<double> p_amg(u.size()), p_jacobi(u.size());
  for (double& x : r) x = -x;
  EXPECT_TRUE(amg->solve(on_the_fly, r, p_amg, {1e-11}, timings).converged);
  EXPECT_TRUE(jacobi->solve(s.system(), r, p_jacobi, {1e-11}, timings).converged);
  EXPECT_LE(max_difference(p_amg, p_jacobi), 1e-8 * max_abs(p_jacobi));
}

/// The element pass without the matrix (a residual that likely ends the Newton loop) gives the
/// residual and node stiffness of the full pass bit for bit, and the next solve assembles the
/// matrix at that pass's points itself: after a full pass at other points, a residual alone
/// at these points, and a solve, the step is the one a solver that assembled here gives.
TEST_P(FramesIn, AmgResidualWithoutTheMatrixLeavesTheSolveToAssembleIt) {
  SectorSystem s(GetParam());
  auto u = random_vector(s.stiffness.size(), 7);
  s.periodic.expand(u);
  std::vector<Vec3> moved = s.points;
  for (std::size_t n = 0; n < moved.size(); ++n) moved[n].x += 0.01 * std::sin(static_cast<double>(n));
  const ConstrainedSystem start = s.system();
  const ConstrainedSystem here{s.stiffness.kernel(), s.constraints, s.periodic, moved, {}};
  SolverOptions options;
  options.linear = LinearSolverKind::amg;
  const parallel::RankExchange& one = parallel::one_process();
  const std::size_t nodes = u.size() / static_cast<std::size_t>(s.stiffness.dofs_per_node());
  MotionTimings timings;
  const auto step = [&](detail::LinearSolver& solver, std::span<const double> r) {
    std::vector<double> rhs(r.size()), p(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) rhs[i] = -r[i];
    EXPECT_TRUE(solver.solve(here, rhs, p, {1e-10}, timings).converged);
    return p;
  };
  auto full = detail::make_linear_solver(options, one, nullptr);
  std::vector<double> r_full(u.size()), stiffness_full(nodes);
  detail::newton_residual(here, nullptr, full->assembler(), one, u, r_full, stiffness_full, timings);
  const auto p_full = step(*full, r_full);

  auto lazy = detail::make_linear_solver(options, one, nullptr);
  std::vector<double> r_lazy(u.size()), stiffness_lazy(nodes), r_start(u.size()), stiffness_start(nodes);
  detail::newton_residual(start, nullptr, lazy->assembler(), one, u, r_start, stiffness_start, timings);
  detail::newton_residual(here, nullptr, lazy->assembler(), one, u, r_lazy, stiffness_lazy, timings, nullptr, false);
  EXPECT_EQ(r_lazy, r_full);
  EXPECT_EQ(stiffness_lazy, stiffness_full);
  EXPECT_GT(max_difference(r_start, r_full), 1e-6 * max_abs(r_full));  // the points matter
  const auto p_lazy = step(*lazy, r_lazy);
  EXPECT_LE(max_difference(p_lazy, p_full), 1e-8 * max_abs(p_full));
}

INSTANTIATE_TEST_SUITE_P(TwoAndThreeDimensions, FramesIn,
                         ::testing::Values(SectorCells{2, false}, SectorCells{3, false}, SectorCells{2, true},
                                           SectorCells{3, true}),
                         [](const auto& param_info) { return cells_name(param_info.param); });

}  // namespace
}  // namespace hotmesh::deform
