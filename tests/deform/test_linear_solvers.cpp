// Tests of the linear solvers of a Newton step (eq. 8): the choice of `linear: auto`, the AMG
// solvers and the sparse Cholesky factors against Jacobi-PCG, the Newton norm they stop on, and
// the forcing terms of the inexact Newton loop, on small 2D and 3D sectors with fixed, sliding
// and periodic nodes (sector_system.hpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "motion/newton.hpp"
#include "storage/petsc_solver.hpp"
#include "sector_system.hpp"

namespace hotmesh::deform {
namespace {

using namespace sector_test;
using detail::ConstrainedOperator;

/// `linear: auto`: amg with several processes; icc for 2D meshes up to kIccCells cells, beyond
/// amg with a sliding wall and jacobi-pcg without; in 3D jacobi-pcg up to kJacobiPcgCells
/// cells, amg beyond.
TEST(LinearSolverChoice, FollowsTheMeasuredRule) {
  EXPECT_EQ(choose_linear_solver(2, 1000, true, 1).kind, LinearSolverKind::icc);
  EXPECT_EQ(choose_linear_solver(2, 1000, false, 1).kind, LinearSolverKind::icc);
  EXPECT_EQ(choose_linear_solver(2, kIccCells, true, 1).kind, LinearSolverKind::icc);
  EXPECT_EQ(choose_linear_solver(2, kIccCells + 1, true, 1).kind, LinearSolverKind::amg);
  EXPECT_EQ(choose_linear_solver(2, kIccCells + 1, false, 1).kind, LinearSolverKind::jacobi_pcg);
  EXPECT_EQ(choose_linear_solver(2, kIccCells, false, 1).reason, "a 2D mesh of at most 40 000 cells");
  EXPECT_EQ(choose_linear_solver(2, kIccCells + 1, true, 1).reason,
            "a 2D mesh with a sliding wall, more than 40 000 cells");
  EXPECT_EQ(choose_linear_solver(3, 1000, true, 1).kind, LinearSolverKind::jacobi_pcg);
  EXPECT_EQ(choose_linear_solver(2, 1000000, false, 1).kind, LinearSolverKind::jacobi_pcg);
  EXPECT_EQ(choose_linear_solver(2, 1000, false, 2).kind, LinearSolverKind::amg);
  EXPECT_EQ(choose_linear_solver(3, kJacobiPcgCells, true, 1).kind, LinearSolverKind::jacobi_pcg);
  EXPECT_EQ(choose_linear_solver(3, kJacobiPcgCells + 1, false, 1).kind, LinearSolverKind::amg);
  EXPECT_EQ(choose_linear_solver(3, 5000, false, 4).kind, LinearSolverKind::amg);
  EXPECT_EQ(choose_linear_solver(3, kJacobiPcgCells + 1, true, 1).reason, "a 3D mesh of more than 500 000 cells");
}

/// Properties every sector (SectorCells) shows, one solver or all of them.
class SolversIn : public ::testing::TestWithParam<SectorCells> {};

INSTANTIATE_TEST_SUITE_P(TwoAndThreeDimensions, SolversIn,
                         ::testing::Values(SectorCells{2, false}, SectorCells{3, false}, SectorCells{2, true},
                                           SectorCells{3, true}),
                         [](const auto& param_info) { return cells_name(param_info.param); });

/// `linear: direct` in one process.
std::unique_ptr<detail::LinearSolver> make_direct_solver() {
  SolverOptions options;
  options.linear = LinearSolverKind::direct;
  return detail::make_linear_solver(options, parallel::one_process(), nullptr);
}

struct SolverCase {
  SectorCells cells;
  LinearSolverKind linear;
  AmgPackage amg;
};

class LinearSolverOn : public ::testing::TestWithParam<SolverCase> {};

/// One Newton step's system solved to 1e-10 by Jacobi-PCG and by the solver
/// under test: the same p, tangential at sliding nodes, zero at fixed nodes and slaves.
TEST_P(LinearSolverOn, SolvesTheSameStepAsJacobiPcg) {
  const SectorSystem s(GetParam().cells);
  const std::vector<double> rhs = admissible_rhs(s, 4);
  const auto solve = [&](LinearSolverKind kind, AmgPackage amg) {
    SolverOptions options;
    options.linear = kind;
    options.amg = amg;
    auto solver = detail::make_linear_solver(options, parallel::one_process(), &s.stiffness);
    std::vector<double> p(rhs.size(), 1.0);  // overwritten: solves start from p = 0
    MotionTimings timings;
    solver->begin_increment();
    const auto result = solver->solve(s.system(), rhs, p, {1e-11}, timings);
    EXPECT_TRUE(result.converged);
    EXPECT_FALSE(result.breakdown);
    EXPECT_LE(result.reduction, 1e-11);
    EXPECT_GT(result.iterations, 0);
    return p;
  };
  const auto reference = solve(LinearSolverKind::jacobi_pcg, AmgPackage::gamg);
  const auto p = solve(GetParam().linear, GetParam().amg);
  EXPECT_LE(max_difference(p, reference), 1e-8 * max_abs(reference));
  const auto d = static_cast<std::size_t>(s.dimension());
  for (std::size_t n = 0; n < s.mesh.node_count(); ++n) {
    const auto node = static_cast<NodeId>(n);
    Vec3 pn{};
    for (std::size_t i = 0; i < d; ++i) pn[i] = p[n * d + i];
    if (s.constraints.is_fixed(node)) {
      EXPECT_EQ(norm(pn), 0.0);
    }
    for (const Vec3& normal : s.constraints.normals(node)) EXPECT_LT(std::abs(dot(pn, normal)), 1e-14 * max_abs(p));
  }
}

/// A matrix that cannot be factorized (here K with every modulus negated: negative definite)
/// is a breakdown of the solve, which the Newton loop turns into a failed attempt, not an
/// exception out of PETSc, and the solver stays usable.
TEST_P(SolversIn, DirectSolverReportsAFailedFactorizationAsABreakdown) {
  const SectorSystem s(GetParam());
  std::vector<Lame> negated = element_lame(s.mesh, {});
  for (Lame& lame : negated) lame = {-lame.lambda, -lame.mu};
  const StiffnessKernel negative(s.mesh, negated, true);
  const std::vector<double> rhs = admissible_rhs(s, 7);
  auto direct = make_direct_solver();
  MotionTimings timings;
  direct->begin_increment();
  std::vector<double> p(rhs.size(), 1.0);
  const ConstrainedSystem indefinite{negative, s.constraints, s.periodic, s.points, {}};
  detail::LinearSolveResult result;
  ASSERT_NO_THROW(result = direct->solve(indefinite, rhs, p, {1e-10}, timings));
  EXPECT_TRUE(result.breakdown);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 0);  // found at the factorization, before any CG iteration
  EXPECT_EQ(max_abs(p), 0.0);
}

INSTANTIATE_TEST_SUITE_P(
    GamgHypreCholeskyAndIcc, LinearSolverOn,
    ::testing::Values(SolverCase{{2, false}, LinearSolverKind::amg, AmgPackage::gamg},
                      SolverCase{{3, false}, LinearSolverKind::amg, AmgPackage::gamg},
                      SolverCase{{2, false}, LinearSolverKind::amg, AmgPackage::hypre},
                      SolverCase{{3, false}, LinearSolverKind::amg, AmgPackage::hypre},
                      SolverCase{{2, true}, LinearSolverKind::amg, AmgPackage::gamg},
                      SolverCase{{3, true}, LinearSolverKind::amg, AmgPackage::gamg},
                      SolverCase{{2, false}, LinearSolverKind::direct, AmgPackage::gamg},
                      SolverCase{{3, false}, LinearSolverKind::direct, AmgPackage::gamg},
                      SolverCase{{2, true}, LinearSolverKind::direct, AmgPackage::gamg},
                      SolverCase{{3, true}, LinearSolverKind::direct, AmgPackage::gamg},
                      SolverCase{{2, false}, LinearSolverKind::icc, AmgPackage::gamg},
                      SolverCase{{3, false}, LinearSolverKind::icc, AmgPackage::gamg},
                      SolverCase{{2, true}, LinearSolverKind::icc, AmgPackage::gamg},
                      SolverCase{{3, true}, LinearSolverKind::icc, AmgPackage::gamg}),
    [](const auto& param_info) {
      const SolverCase& c = param_info.param;
      return cells_name(c.cells) + (c.linear == LinearSolverKind::direct ? "Direct"
                                    : c.linear == LinearSolverKind::icc  ? "Icc"
                                    : c.amg == AmgPackage::gamg         ? "Gamg"
                                                                        : "Hypre");
    });

/// `linear: direct`: the Cholesky factors of K~ are exact, so CG preconditioned by them stops
/// after one iteration (two at most, for rounding) at a tolerance far below what Jacobi-PCG or
/// a multigrid reaches in one; and again at a later Newton step of the same increment, where
/// the matrix has changed (the factors are made anew, not kept).
TEST_P(SolversIn, DirectSolverIsExactAtEveryNewtonStep) {
  SectorSystem s(GetParam());
  const std::vector<double> rhs = admissible_rhs(s, 6);
  auto direct = make_direct_solver();
  ASSERT_NE(direct->assembler(), nullptr);
  MotionTimings timings;
  direct->begin_increment();
  std::vector<double> p(rhs.size());
  for (int step = 0; step < 2; ++step) {
    SCOPED_TRACE(step);
    const auto result = direct->solve(s.system(), rhs, p, {1e-10}, timings);
    EXPECT_TRUE(result.converged);
    EXPECT_LE(result.iterations, 2);
    EXPECT_LE(result.reduction, 1e-10);
    // The reference: the same system solved by Jacobi-PCG at its current points.
    std::vector<double> reference(rhs.size());
    SolverOptions jacobi_options;
    auto jacobi = detail::make_linear_solver(jacobi_options, parallel::one_process(), &s.stiffness);
    jacobi->begin_increment();
    EXPECT_TRUE(jacobi->solve(s.system(), rhs, reference, {1e-11}, timings).converged);
    EXPECT_LE(max_difference(p, reference), 1e-7 * max_abs(reference));
    // The next Newton step: the mesh has moved by a fraction of p, K with it.
    const auto d = static_cast<std::size_t>(s.dimension());
    const double scale = 0.05 / max_abs(p);
    for (std::size_t n = 0; n < s.points.size(); ++n) {
      for (std::size_t i = 0; i < d; ++i) s.points[n][i] += scale * p[n * d + i];
    }
    s.stiffness.update(s.points);
  }
  EXPECT_GT(timings.preconditioner, 0.0);
}

/// Asked for the Newton norm (as Forcing asks for some solves), each solver stops on
/// ||D^-1 r|| with the system's node stiffness D, not on the plain ||r||: with every
/// seventh node a thousand times stiffer and its force a thousand times larger (as in the
/// smallest cells of a real mesh), those nodes make up the plain norm, yet a loose solve must
/// reduce every node's scaled residual.
TEST_P(SolversIn, EverySolverStopsOnTheResidualScaledByTheNodeStiffness) {
  const SectorSystem s(GetParam());
  const auto d = static_cast<std::size_t>(s.dimension());
  std::vector<double> stiffness(s.mesh.node_count(), 1.0);
  std::vector<double> rhs = random_vector(s.stiffness.size(), 5);
  for (std::size_t n = 3; n < stiffness.size(); n += 7) {
    stiffness[n] = 1e3;
    for (std::size_t i = 0; i < d; ++i) rhs[n * d + i] *= 1e3;
  }
  s.periodic.fold(rhs);
  s.constraints.project(rhs);
  const ConstrainedSystem system{s.stiffness.kernel(), s.constraints, s.periodic, s.points, stiffness};
  const ConstrainedOperator k(s.stiffness, s.constraints, s.periodic);
  const double tolerance = 1e-2;
  for (const auto& [kind, amg] : {std::pair{LinearSolverKind::jacobi_pcg, AmgPackage::gamg},
                                  std::pair{LinearSolverKind::amg, AmgPackage::gamg},
                                  std::pair{LinearSolverKind::amg, AmgPackage::hypre}}) {
    SCOPED_TRACE(kind == LinearSolverKind::jacobi_pcg ? "jacobi-pcg" : amg == AmgPackage::gamg ? "gamg" : "hypre");
    SolverOptions options;
    options.linear = kind;
    options.amg = amg;
    std::vector<double> p(rhs.size());
    const auto solve = [&](bool newton_norm) {
      auto solver = detail::make_linear_solver(options, parallel::one_process(), &s.stiffness);
      MotionTimings timings;
      solver->begin_increment();
      const auto result = solver->solve(system, rhs, p, {tolerance, newton_norm}, timings);
      EXPECT_TRUE(result.converged);
      std::vector<double> r(rhs.size());
      k.apply(p, r);
      for (std::size_t i = 0; i < r.size(); ++i) r[i] = rhs[i] - r[i];
      return std::pair{result.reduction,
                       detail::scaled_residual_norm(r, stiffness, d) / detail::scaled_residual_norm(rhs, stiffness, d)};
    };
    const auto [reported, reduction] = solve(true);
    EXPECT_LE(reduction, tolerance * 1.001);
    EXPECT_NEAR(reported, reduction, 1e-6 * reduction);
    // The same solve stopping on the plain ||r|| leaves the soft nodes' residual too large
    // (the multigrids happen to reduce it enough on this small mesh in 3D, so they are not
    // asked there: 0.007 with GAMG's forward and backward Gauss-Seidel sweeps).
    const auto plain = solve(false);
    if (kind == LinearSolverKind::jacobi_pcg || (amg == AmgPackage::gamg && d == 2)) {
      EXPECT_GT(plain.second, tolerance);
    }
  }
}

/// A channel 2 long and 1 high whose cells shrink to 0.001 at its floor (aspect ratio 50 there,
/// a CFD boundary layer), numbered row by row as a structured mesh is, or shuffled: the floor
/// slides, the inlet and the roof are fixed. K at the mesh's points, with eq. (35)'s stiffness.
struct BoundaryLayer {
  Mesh mesh;
  NodeConstraints constraints;
  detail::PeriodicCoupling periodic{2};
  StiffnessOperator stiffness;

  explicit BoundaryLayer(bool shuffle)
      : mesh(make_mesh(shuffle)), constraints(mesh.node_count(), 2), stiffness(mesh, element_lame(mesh, {}), true) {
    for (std::size_t n = 0; n < mesh.node_count(); ++n) {
      const Vec3& p = mesh.points[n];
      if (p.x == 0.0 || p.y == 1.0) {
        constraints.fix(static_cast<NodeId>(n));
      } else if (p.y == 0.0) {
        constraints.constrain(static_cast<NodeId>(n), {0.0, 1.0, 0.0});
      }
    }
    stiffness.update(mesh.points);
  }
  ConstrainedSystem system() const { return {stiffness.kernel(), constraints, periodic, mesh.points, {}}; }

  static Mesh make_mesh(bool shuffle) {
    const auto xs = mesh::uniform_line(0.0, 2.0, 41);
    const auto ys = mesh::stretched_line(0.0, 1.0, 31, 0.001);
    const Mesh given = mesh::structured_quads(xs, ys, {"inlet", "outlet", "floor", "roof"});
    return shuffle ? test::shuffled_nodes(given, 11) : given;
  }
};

struct LayerSolve {
  detail::LinearSolveResult result;
  std::vector<double> p;
  std::vector<std::string> notes;
};

LayerSolve solve_layer(const BoundaryLayer& layer, LinearSolverKind kind, double tolerance) {
  std::vector<double> rhs = random_vector(layer.stiffness.size(), 3);
  layer.constraints.project(rhs);
  SolverOptions options;
  options.linear = kind;
  auto solver = detail::make_linear_solver(options, parallel::one_process(), &layer.stiffness);
  MotionTimings timings;
  solver->begin_increment();
  LayerSolve out{{}, std::vector<double>(rhs.size()), {}};
  out.result = solver->solve(layer.system(), rhs, out.p, {tolerance}, timings);
  out.notes = solver->notes();
  return out;
}

/// `linear: icc` in the numbering of a structured boundary layer: its incomplete factors hold
/// the stiff coupling across the thin cells, so CG needs a small share of Jacobi-PCG's
/// iterations for the same step (the reason `auto` takes it in 2D).
TEST(IncompleteCholesky, NeedsAFractionOfJacobiPcgsIterationsInABoundaryLayer) {
  const BoundaryLayer layer(false);
  const LayerSolve jacobi = solve_layer(layer, LinearSolverKind::jacobi_pcg, 1e-10);
  const LayerSolve icc = solve_layer(layer, LinearSolverKind::icc, 1e-10);
  ASSERT_TRUE(jacobi.result.converged);
  ASSERT_TRUE(icc.result.converged);
  EXPECT_LT(icc.result.iterations * 10, jacobi.result.iterations) << icc.result.iterations << " against " << jacobi.result.iterations;
  EXPECT_LE(max_difference(icc.p, jacobi.p), 1e-7 * max_abs(jacobi.p));
  EXPECT_TRUE(icc.notes.empty());
}

/// The same channel with its nodes shuffled: ICC in that order needs more than the iterations
/// icc allows, so the solver goes over to the exact factors, still solves the step, and says so.
TEST(IncompleteCholesky, GoesOverToTheExactFactorsWhereTheNumberingHidesTheLayer) {
  const BoundaryLayer layer(true);
  const LayerSolve jacobi = solve_layer(layer, LinearSolverKind::jacobi_pcg, 1e-10);
  const LayerSolve icc = solve_layer(layer, LinearSolverKind::icc, 1e-10);
  ASSERT_TRUE(icc.result.converged);
  EXPECT_GT(icc.result.iterations, 100);  // ICC's, then one or two with the exact factors
  EXPECT_LE(max_difference(icc.p, jacobi.p), 1e-7 * max_abs(jacobi.p));
  ASSERT_EQ(icc.notes.size(), 1U);
  EXPECT_THAT(icc.notes[0], ::testing::HasSubstr("the run went on with linear: direct"));
}

/// The Newton residual's norm weighs a node by the displacement its force stands for: a node
/// a thousand times stiffer, with a thousand times the force, counts as much as a soft one
/// (in the plain norm it would hide the other completely); nodes without stiffness are left out.
TEST(ScaledResidualNorm, DividesEachNodesForceByItsStiffness) {
  const std::vector<double> r{3000.0, 4000.0, 0.3, 0.4, 5.0, 5.0};  // 2D, three nodes
  const std::vector<double> stiffness{1000.0, 0.1, 0.0};
  EXPECT_NEAR(detail::scaled_residual_norm(r, stiffness, 2), std::sqrt(5.0 * 5.0 + 5.0 * 5.0), 1e-12);
}

/// Forcing::next's tolerance, checking the norm: the Newton loop's for the first solve of an
/// increment, the plain one for the later solves these tests give (each decreases enough).
double next_tolerance(detail::Forcing& f, int n, double residual, double initial) {
  const auto target = f.next(n, residual, initial);
  EXPECT_EQ(target.newton_norm, n == 0) << "step " << n << ", residual " << residual;
  return target.tolerance;
}

TEST(Forcing, FixedGivesThePcgToleranceEveryTime) {
  SolverOptions o;
  o.pcg_tolerance = 1e-3;
  detail::Forcing f(o);
  EXPECT_EQ(next_tolerance(f, 0, 1.0, 1.0), 1e-3);
  EXPECT_EQ(next_tolerance(f, 1, 0.9, 1.0), 1e-3);
  EXPECT_EQ(next_tolerance(f, 2, 1e-3, 1.0), 1e-3);
}

/// The first solve of an increment and, with either forcing, the solve after a step without
/// sufficient decrease stop on the Newton loop's own norm ||D^-1 r||, to pcg_tolerance; the
/// solve after a step that decreased enough, on ||r||.
TEST(Forcing, FirstSolveAndSolveAfterAStepWithoutSufficientDecreaseStopOnTheNewtonNorm) {
  SolverOptions o;
  o.pcg_tolerance = 1e-3;
  detail::Forcing f(o);
  EXPECT_TRUE(f.next(0, 1.0, 1.0).newton_norm);
  EXPECT_FALSE(f.next(1, 0.27, 1.0).newton_norm);
  const auto stalled = f.next(2, 0.52, 1.0);  // increment 6 of the 2.7M-cell sector on two ranks
  EXPECT_TRUE(stalled.newton_norm);
  EXPECT_EQ(stalled.tolerance, 1e-3);
  EXPECT_FALSE(f.next(3, 0.005, 1.0).newton_norm);
}

/// Eisenstat-Walker forcing with pcg_tolerance 1e-3 and newton_tolerance 1e-4.
SolverOptions eisenstat_walker_options() {
  SolverOptions o;
  o.pcg_tolerance = 1e-3;
  o.newton_tolerance = 1e-4;
  o.forcing = ForcingTerm::eisenstat_walker;
  return o;
}

TEST(Forcing, EisenstatWalkerLoosensWhileNewtonIsSlowAndNeverGoesBelowThePcgTolerance) {
  SolverOptions o = eisenstat_walker_options();
  detail::Forcing f(o);
  EXPECT_EQ(next_tolerance(f, 0, 1.0, 1.0), 1e-3);          // the first solve of an increment
  EXPECT_DOUBLE_EQ(next_tolerance(f, 1, 0.9, 1.0), 0.1);    // slow: 0.9 * 0.9^2, capped at 0.1
  EXPECT_DOUBLE_EQ(next_tolerance(f, 2, 0.09, 1.0), 0.009);  // fast: 0.9 * 0.1^2
  // Near the Newton tolerance a solve need not reduce the residual far below it.
  EXPECT_DOUBLE_EQ(next_tolerance(f, 3, 9e-4, 1.0), 0.5 * 1e-4 / 9e-4);
  o.newton_tolerance = 1e-12;
  detail::Forcing g(o);
  EXPECT_EQ(next_tolerance(g, 0, 1.0, 1.0), 1e-3);
  EXPECT_EQ(next_tolerance(g, 1, 1e-3, 1.0), 1e-3);  // 0.9 * 1e-6, but never below pcg_tolerance
}

/// A predicted start whose residual is already near the Newton tolerance of the reference
/// (the paper's start): the first solve reduces it only as far as that tolerance needs, within
/// [pcg_tolerance, 0.1]; without a prediction (residual = reference) it is pcg_tolerance.
TEST(Forcing, EisenstatWalkerSolvesAPredictedFirstStepOnlyAsFarAsTheNewtonToleranceNeeds) {
  detail::Forcing f(eisenstat_walker_options());
  const auto first = f.next(0, 2e-3, 1.0);  // 0.5 * 1e-4 * 1 / 2e-3
  EXPECT_DOUBLE_EQ(first.tolerance, 0.025);
  EXPECT_TRUE(first.newton_norm);
  detail::Forcing g(eisenstat_walker_options());
  EXPECT_EQ(next_tolerance(g, 0, 1e-6, 1.0), 0.1);    // capped
  detail::Forcing g2(eisenstat_walker_options());
  EXPECT_EQ(next_tolerance(g2, 0, 0.1, 1.0), 1e-3);   // 5e-4 would be below pcg_tolerance
  detail::Forcing h(eisenstat_walker_options());
  EXPECT_EQ(next_tolerance(h, 0, 1.0, 1.0), 1e-3);    // no prediction
  SolverOptions fixed;
  fixed.pcg_tolerance = 1e-3;
  detail::Forcing k(fixed);
  EXPECT_EQ(next_tolerance(k, 0, 2e-3, 1.0), 1e-3);  // `fixed` keeps pcg_tolerance
}

TEST(Forcing, EisenstatWalkerFallsBackToThePcgToleranceWhenNewtonStalls) {
  detail::Forcing f(eisenstat_walker_options());
  EXPECT_EQ(next_tolerance(f, 0, 1.0, 1.0), 1e-3);
  EXPECT_DOUBLE_EQ(next_tolerance(f, 1, 0.132, 1.0), 0.9 * 0.132 * 0.132);  // decreased: choice 2
  // The step solved to eta left the residual where it was: no sufficient decrease, so the next
  // solve is a full one in the Newton norm, not another loose one (what stalled the 2.7M-cell
  // sector).
  const auto full = f.next(2, 0.147, 1.0);
  EXPECT_EQ(full.tolerance, 1e-3);
  EXPECT_TRUE(full.newton_norm);
  const double short_of_it = 0.147 * (1.0 - 1e-4 * (1.0 - 1e-3)) * (1.0 + 1e-9);
  EXPECT_EQ(f.next(3, short_of_it, 1.0).tolerance, 1e-3);
  // A step that decreases enough brings choice 2 back: 0.9 (1/10)^2.
  EXPECT_NEAR(next_tolerance(f, 4, 0.1 * short_of_it, 1.0), 0.009, 1e-12);
}

}  // namespace
}  // namespace hotmesh::deform
