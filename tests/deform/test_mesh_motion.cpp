// Tests of the mesh motion (eqs. 7-8, increments, quality checks, splitting): the patch
// test, the rotating inner body that geometric nonlinearity is for, the paper's 2D ramp
// without sliding, determinism, and honest failure.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>

#include <cstring>
#include <numbers>
#include <optional>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/core/input_error.hpp"
#include "test_shapes.hpp"
#include "test_support.hpp"

namespace hotmesh::deform {
namespace {

using ::testing::HasSubstr;

using test::AffineShape;

std::vector<PatchMotion> all_patches(const Mesh& mesh, BoundaryRole role, std::shared_ptr<const geometry::BoundaryShape> shape = {}) {
  std::vector<PatchMotion> motions;
  for (const Patch& p : mesh.patches) motions.push_back({p.name, role, shape});
  return motions;
}

SolverOptions tight() {
  SolverOptions s;
  s.increments = 2;
  s.newton_tolerance = 1e-12;
  s.pcg_tolerance = 1e-14;
  s.max_pcg_iterations = 20000;
  return s;
}

void expect_patch_test_passes(Mesh mesh, const std::array<Vec3, 3>& g) {
  test::jiggle_interior(mesh, 0.3);
  validate_mesh(mesh);
  const auto shape = std::make_shared<AffineShape>(g, Vec3{0.05, -0.02, mesh.dimension == 3 ? 0.03 : 0.0});
  const MaterialOptions uniform{StiffnessLaw::uniform, 1.0, 0.5, false};
  const MotionResult r = move_mesh(mesh, all_patches(mesh, BoundaryRole::prescribed, shape), uniform, tight());
  ASSERT_TRUE(r.success) << r.message;
  double error = 0.0;
  for (std::size_t n = 0; n < mesh.node_count(); ++n) error = std::max(error, distance(r.points[n], shape->moved(mesh.points[n])));
  EXPECT_LT(error, 1e-10);
}

TEST(MeshMotion, PatchTestReproducesAffineMotionInsideDistortedQuads) {
  expect_patch_test_passes(test::unit_square(7, 6), {{{0.1, 0.05, 0}, {-0.08, 0.12, 0}, {0, 0, 0}}});
}

TEST(MeshMotion, PatchTestReproducesAffineMotionInsideDistortedHexes) {
  expect_patch_test_passes(test::unit_cube(4), {{{0.1, 0.05, -0.03}, {-0.08, 0.12, 0.02}, {0.04, -0.05, 0.09}}});
}

TEST(MeshMotion, PatchTestReproducesAffineMotionInsideDistortedHybridCells) {
  const std::array<Vec3, 3> g2{{{0.1, 0.05, 0}, {-0.08, 0.12, 0}, {0, 0, 0}}};
  const std::array<Vec3, 3> g3{{{0.1, 0.05, -0.03}, {-0.08, 0.12, 0.02}, {0.04, -0.05, 0.09}}};
  expect_patch_test_passes(test::hybrid_ring(6, 4, 0.3, 1.0, 0, 0.0, 1.0, 2), g2);       // quads, triangles
  expect_patch_test_passes(test::hybrid_ring(4, 3, 0.3, 1.0, 2, 0.5, 1.0, 1), g3);       // prisms, tetrahedra, pyramids
  const Mesh cube = test::unit_cube(3);
  std::vector<mesh::CellSplit> checkerboard(cube.cell_count(), mesh::CellSplit::keep);
  for (std::size_t c = 0; c < checkerboard.size(); c += 2) checkerboard[c] = mesh::CellSplit::tetrahedra;
  expect_patch_test_passes(mesh::split_cells(cube, checkerboard), g3);  // hexes, pyramids, tetrahedra
}

/// The inner square of a square ring rotated by 45 degrees about z; outer boundary fixed.
std::vector<PatchMotion> rotating_inner_square(const Mesh& mesh, double inner) {
  const std::vector<Vec3> square{{inner, -inner, 0}, {inner, inner, 0}, {-inner, inner, 0}, {-inner, -inner, 0},
                                 {inner, -inner, 0}};
  auto shape = std::make_shared<test::TestCurveShape>(square, test::rotation(std::numbers::pi / 4));
  std::vector<PatchMotion> motions{{"inner", BoundaryRole::prescribed, shape}, {"outer", BoundaryRole::fixed, nullptr}};
  if (mesh.dimension == 3) {
    motions.push_back({"zmin", BoundaryRole::slip, nullptr});
    motions.push_back({"zmax", BoundaryRole::slip, nullptr});
  }
  return motions;
}

/// A boundary-layer-like O-grid around the inner square: rings 30% wider one after the other.
Mesh clustered_ring(int layers = 0) {
  return layers == 0 ? test::square_ring(8, 12, 0.25, 1.0, 0, 0.0, 1.3) : test::square_ring(6, 10, 0.25, 1.0, layers, 0.4, 1.3);
}

void expect_nonlinear_beats_one_linear_step(const Mesh& mesh) {
  const auto motions = rotating_inner_square(mesh, 0.25);
  SolverOptions nonlinear;  // 16 increments, the paper's tolerances
  const MotionResult r = move_mesh(mesh, motions, {}, nonlinear);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.summary.inverted_cells, 0u);
  EXPECT_EQ(r.increments.size(), 16u) << "no increment needed splitting";

  SolverOptions linear;
  linear.increments = 1;
  linear.max_newton_iterations = 1;  // one linear solve at the original geometry
  linear.pcg_tolerance = 1e-10;
  linear.max_increment_splits = 0;
  const MotionResult l = move_mesh(mesh, motions, {}, linear);
  const auto& linear_quality = l.success ? l.quality : l.failed_quality;
  const double linear_min = *std::min_element(linear_quality.begin(), linear_quality.end());
  EXPECT_LT(linear_min, r.summary.min_scaled_jacobian);
  // The rotation really happened: the inner corner (h, -h) ended on the x axis.
  const Vec3 corner = r.points[0];
  EXPECT_NEAR(corner.x, std::sqrt(2.0) * 0.25, 1e-12);
  EXPECT_NEAR(corner.y, 0.0, 1e-12);
}

TEST(MeshMotion, RotatedInnerSquareStaysValidWithGeometricNonlinearity) {
  expect_nonlinear_beats_one_linear_step(clustered_ring());
}

TEST(MeshMotion, RotatedInnerSquareStaysValidIn3D) {
  expect_nonlinear_beats_one_linear_step(clustered_ring(2));
}

TEST(MeshMotion, RotatedInnerSquareStaysValidInHybridMeshes) {
  // Three rings of quads (2D) or prisms (3D) on the body, triangles or tetrahedra outside.
  expect_nonlinear_beats_one_linear_step(test::hybrid_ring(8, 12, 0.25, 1.0, 0, 0.0, 1.3, 3));
  expect_nonlinear_beats_one_linear_step(test::hybrid_ring(6, 10, 0.25, 1.0, 2, 0.4, 1.3, 3));
}

TEST(MeshMotion, SlipNodesStayOnTheirPlane) {
  const Mesh mesh = clustered_ring(2);
  const MotionResult r = move_mesh(mesh, rotating_inner_square(mesh, 0.25), {}, {});
  ASSERT_TRUE(r.success);
  for (NodeId n : mesh.find_patch("zmax")->nodes) EXPECT_NEAR(r.points[static_cast<std::size_t>(n)].z, 0.4, 1e-13);
  for (NodeId n : mesh.find_patch("zmin")->nodes) EXPECT_NEAR(r.points[static_cast<std::size_t>(n)].z, 0.0, 1e-13);
}

/// The paper's Fig. 6 ramp: h = 1, box 2h x h, dx = 2h/57, first cell 0.001h at the wall.
struct Ramp {
  static constexpr double a = 0.975, b = 1.025, height = 0.5;
  static double lift(double x) { return x <= a ? 0.0 : x >= b ? height : height * (x - a) / (b - a); }
};

TEST(MeshMotion, PaperRampWithoutSlidingCompletesWithoutInvertedCells) {
  const auto xs = mesh::uniform_line(0.0, 2.0, 57);
  const auto ys = mesh::stretched_line(0.0, 1.0, 40, 0.001);
  const Mesh mesh = mesh::structured_quads(xs, ys, {"left", "right", "bottom", "top"});
  auto bottom = std::make_shared<test::TestCurveShape>(
      std::vector<Vec3>{{0, 0, 0}, {Ramp::a, 0, 0}, {Ramp::b, 0, 0}, {2, 0, 0}},
      [](const Vec3& p, double lambda) { return p + Vec3{0.0, lambda * Ramp::lift(p.x), 0.0}; });
  const std::vector<PatchMotion> motions{{"left", BoundaryRole::fixed, nullptr},
                                         {"right", BoundaryRole::slip, nullptr},
                                         {"bottom", BoundaryRole::prescribed, bottom},
                                         {"top", BoundaryRole::fixed, nullptr}};
  const MotionResult r = move_mesh(mesh, motions, {}, {});
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.summary.inverted_cells, 0u);
  EXPECT_GT(r.summary.min_scaled_jacobian, 0.0);
  for (NodeId n : mesh.find_patch("bottom")->nodes) {
    const Vec3 x0 = mesh.points[static_cast<std::size_t>(n)];
    EXPECT_NEAR(r.points[static_cast<std::size_t>(n)].y, Ramp::lift(x0.x), 1e-12);
  }
  for (NodeId n : mesh.find_patch("right")->nodes) EXPECT_NEAR(r.points[static_cast<std::size_t>(n)].x, 2.0, 1e-12);
  for (const auto& inc : r.increments) {
    EXPECT_TRUE(inc.converged);
    EXPECT_LE(inc.residual_reduction, 1e-4);
  }
}

TEST(MeshMotion, ResultIsBitIdenticalForAnyThreadCount) {
  // Large enough that element and vector loops run in parallel (mesh/include/hotmesh/mesh/parallel_loops.hpp).
  Mesh mesh = test::square_ring(16, 16, 0.25, 1.0, 5, 0.5, 1.1);
  test::jiggle_interior(mesh, 0.2);
  const auto motions = rotating_inner_square(mesh, 0.25);
  SolverOptions options;  // two Newton steps of one increment: enough to compare
  options.increments = 1;
  options.max_newton_iterations = 2;
  options.max_increment_splits = 0;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const MotionResult one = move_mesh(mesh, motions, {}, options);
  omp_set_num_threads(2);
  const MotionResult two = move_mesh(mesh, motions, {}, options);
  omp_set_num_threads(saved);
  const auto& a = one.success ? one.points : one.failed_points;
  const auto& b = two.success ? two.points : two.failed_points;
  ASSERT_EQ(a.size(), mesh.node_count());
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)), 0);
  EXPECT_NE(std::memcmp(a.data(), mesh.points.data(), a.size() * sizeof(Vec3)), 0);  // it moved
}

/// The inner square of `mesh` turned in `increments`, with every checkpoint of the run.
MotionResult turn_with_checkpoints(const Mesh& mesh, int increments, std::vector<MotionCheckpoint>& checkpoints) {
  SolverOptions options;
  options.increments = increments;
  MotionObservers o;
  o.checkpoint = [&checkpoints](const MotionCheckpoint& c) { checkpoints.push_back(c); };
  return move_mesh(mesh, rotating_inner_square(mesh, 0.25), {}, options, o);
}

bool bitwise_equal(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

/// The peak resident memory of this process so far, in kB.
long peak_kilobytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

TEST(MeshMotion, ManyIncrementsHoldNothingPerIncrementOfTheRun) {
  // Issue 18: `increments: 1000000000` took more than 13 GB before increment 1: the run listed
  // every step to do, and every checkpoint copied the list (32 bytes per increment each).
  const Mesh mesh = clustered_ring();
  SolverOptions options;
  options.increments = 10'000'000;
  struct Stop {};
  std::optional<MotionCheckpoint> first;
  MotionObservers observers;
  observers.checkpoint = [&first](const MotionCheckpoint& c) {
    first = c;
    throw Stop{};  // ends the run (mesh_motion.hpp: an observer's exception propagates)
  };
  const long before = peak_kilobytes();
  EXPECT_THROW(move_mesh(mesh, rotating_inner_square(mesh, 0.25), {}, options, observers), Stop);
  const long growth = peak_kilobytes() - before;
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->increments, 10'000'000);
  EXPECT_EQ(first->finished_increments, 1);
  EXPECT_TRUE(first->split_pieces.empty());
  EXPECT_EQ(first->records.size(), 1u);
  EXPECT_LT(growth, 100'000) << "kB of peak memory for one increment of a 10^7-increment run";
}

TEST(MeshMotion, ResumingAfterAPieceOfASplitIncrementMakesTheSameMoves) {
  // An eighth of a turn of the inner square in one increment: too much at once, so it is split;
  // a checkpoint after the first accepted piece still has the other pieces to do.
  const Mesh mesh = clustered_ring();
  std::vector<MotionCheckpoint> checkpoints;
  const MotionResult straight = turn_with_checkpoints(mesh, 1, checkpoints);
  ASSERT_TRUE(straight.success) << straight.message;
  const auto split = std::find_if(checkpoints.begin(), checkpoints.end(), [](const MotionCheckpoint& c) {
    return !c.split_pieces.empty();
  });
  ASSERT_NE(split, checkpoints.end()) << "no increment was split: the test needs a harder motion";
  EXPECT_EQ(split->finished_increments, split->split_pieces.front().increment - 1);
  EXPECT_GT(split->split_pieces.front().split_depth, 0);
  EXPECT_LT(split->lambda, 1.0);
  const std::size_t accepted = static_cast<std::size_t>(std::count_if(
      straight.increments.begin(), straight.increments.end(), [](const IncrementRecord& r) { return r.accepted; }));
  EXPECT_EQ(checkpoints.size(), accepted);  // one per accepted step
  EXPECT_EQ(checkpoints.back().finished_increments, 1);
  EXPECT_TRUE(checkpoints.back().split_pieces.empty());

  const auto motions = rotating_inner_square(mesh, 0.25);
  SolverOptions options;
  options.increments = 1;
  for (const MotionCheckpoint* from : {&*split, &checkpoints.front(), &checkpoints.back()}) {
    const MotionResult resumed = move_mesh(mesh, motions, {}, options, {}, nullptr, from);
    ASSERT_TRUE(resumed.success) << resumed.message;
    EXPECT_TRUE(bitwise_equal(resumed.points, straight.points)) << "resumed at stage " << from->lambda;
    ASSERT_EQ(resumed.increments.size(), straight.increments.size());
    for (std::size_t i = 0; i < straight.increments.size(); ++i) {
      EXPECT_EQ(resumed.increments[i].newton.size(), straight.increments[i].newton.size()) << i;
      EXPECT_EQ(resumed.increments[i].split_depth, straight.increments[i].split_depth) << i;
      EXPECT_EQ(resumed.increments[i].accepted, straight.increments[i].accepted) << i;
    }
  }
}

TEST(MeshMotion, NewtonObserverSeesEveryStep) {
  const Mesh mesh = clustered_ring();
  SolverOptions options;
  options.increments = 3;
  std::vector<NewtonProgress> steps;
  MotionObservers observers;
  observers.newton = [&steps](const NewtonProgress& p) { steps.push_back(p); };
  const MotionResult r = move_mesh(mesh, rotating_inner_square(mesh, 0.25), {}, options, observers);
  ASSERT_TRUE(r.success) << r.message;
  std::size_t expected = 0;
  for (const auto& inc : r.increments) expected += inc.newton.size() - 1;
  ASSERT_EQ(steps.size(), expected);
  std::size_t at = 0;
  for (const auto& inc : r.increments) {
    for (std::size_t i = 0; i + 1 < inc.newton.size(); ++i, ++at) {
      const NewtonProgress& p = steps[at];
      EXPECT_EQ(p.step.increment, inc.increment);
      EXPECT_EQ(p.increments, 3);
      EXPECT_EQ(p.iteration, static_cast<int>(i + 1));
      EXPECT_EQ(p.pcg_iterations, inc.newton[i].pcg_iterations);
      EXPECT_DOUBLE_EQ(p.residual_reduction, inc.newton[i + 1].residual / inc.newton[0].residual);
      EXPECT_GE(p.seconds, 0.0);
    }
  }
}

TEST(MeshMotion, CheckpointOfAnotherRunIsRefused) {
  const Mesh mesh = clustered_ring();
  std::vector<MotionCheckpoint> checkpoints;
  ASSERT_TRUE(turn_with_checkpoints(mesh, 3, checkpoints).success);
  const auto motions = rotating_inner_square(mesh, 0.25);
  SolverOptions options;
  options.increments = 4;
  try {
    move_mesh(mesh, motions, {}, options, {}, nullptr, &checkpoints.front());
    FAIL() << "resumed with another number of increments";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("written for 3 increments, this run has 4"));
  }
  options.increments = 3;
  MotionCheckpoint other = checkpoints.front();
  other.points.pop_back();
  EXPECT_THROW(move_mesh(mesh, motions, {}, options, {}, nullptr, &other), InputError);
}

TEST(MeshMotion, ImpossibleMotionStopsWithLastValidMeshNamingCellAndIncrement) {
  // The top wall is pushed down through the bottom wall: some increment must fail.
  const Mesh mesh = test::unit_square(6, 6);
  auto top = std::make_shared<test::TestCurveShape>(std::vector<Vec3>{{0, 1, 0}, {1, 1, 0}},
                                                    [](const Vec3& p, double lambda) { return p - Vec3{0, 1.5 * lambda, 0}; });
  const std::vector<PatchMotion> motions{{"xmin", BoundaryRole::slip, nullptr},
                                         {"xmax", BoundaryRole::slip, nullptr},
                                         {"ymin", BoundaryRole::fixed, nullptr},
                                         {"ymax", BoundaryRole::prescribed, top}};
  SolverOptions options;
  options.increments = 4;
  options.max_increment_splits = 2;
  const MotionResult r = move_mesh(mesh, motions, {}, options);
  EXPECT_FALSE(r.success);
  EXPECT_THAT(r.message, HasSubstr("increment"));
  EXPECT_THAT(r.message, HasSubstr("of 4 failed"));
  EXPECT_THAT(r.message, HasSubstr("after splitting it 2 times"));
  EXPECT_LT(r.lambda_reached, 1.0);
  EXPECT_EQ(r.summary.inverted_cells, 0u);  // the mesh kept is valid
  EXPECT_FALSE(r.failed_points.empty());
  EXPECT_TRUE(std::any_of(r.failed_quality.begin(), r.failed_quality.end(), [](double q) { return q <= 0.0; }) ||
              r.message.find("Newton") != std::string::npos);
  EXPECT_FALSE(r.increments.back().accepted);
  EXPECT_EQ(r.increments.back().split_depth, 2);
  // What failed, as measured: inverted cells, or Newton, with the nodes where its residual is
  // largest (issue 45 item 4).
  if (r.failure.kind == MotionFailure::Kind::inverted_cells) {
    EXPECT_TRUE(std::any_of(r.failed_quality.begin(), r.failed_quality.end(), [](double q) { return q <= 0.0; }));
  } else {
    EXPECT_THAT(r.message, HasSubstr("no cell inverted"));
    ASSERT_FALSE(r.failure.largest_residuals.empty());
    EXPECT_THAT(r.message, HasSubstr(fmt::format("the residual is largest at node {}", mesh.node_id(r.failure.largest_residuals[0].node))));
    EXPECT_EQ(r.failure.residual.size(), mesh.node_count());
  }
}

/// The inner square of a clustered ring, rotated as rotating_inner_square does, at `scale`.
MotionResult rotate_ring_at_scale(double scale) {
  Mesh mesh = clustered_ring();
  for (Vec3& p : mesh.points) p = scale * p;
  validate_mesh(mesh);
  const double inner = 0.25 * scale;
  const std::vector<Vec3> square{{inner, -inner, 0}, {inner, inner, 0}, {-inner, inner, 0}, {-inner, -inner, 0},
                                 {inner, -inner, 0}};
  auto shape = std::make_shared<test::TestCurveShape>(square, test::rotation(std::numbers::pi / 8));
  SolverOptions options;
  options.increments = 4;
  const std::vector<PatchMotion> motions{{"inner", BoundaryRole::prescribed, shape},
                                         {"outer", BoundaryRole::fixed, nullptr}};
  return move_mesh(mesh, motions, {}, options);
}

// Issue 18, item 8: the range validate_mesh accepts (1e-30 across to 1e30 from the origin) is
// one the method is scale-invariant in: the same motion at 1e-25 and 1e25 ends in the same
// mesh, scaled, with the same iterations.
TEST(MeshMotion, MovesAMeshTheSameAtEveryScaleItAccepts) {
  const MotionResult unit = rotate_ring_at_scale(1.0);
  ASSERT_TRUE(unit.success) << unit.message;
  for (const double scale : {1e-25, 1e25}) {
    const MotionResult r = rotate_ring_at_scale(scale);
    ASSERT_TRUE(r.success) << scale << ": " << r.message;
    double worst = 0.0;
    for (std::size_t n = 0; n < r.points.size(); ++n) worst = std::max(worst, distance((1.0 / scale) * r.points[n], unit.points[n]));
    EXPECT_LT(worst, 1e-9) << scale;
    ASSERT_EQ(r.increments.size(), unit.increments.size()) << scale;
    for (std::size_t k = 0; k < r.increments.size(); ++k) {
      EXPECT_EQ(r.increments[k].newton.size(), unit.increments[k].newton.size()) << scale << ", increment " << k;
    }
  }
}

TEST(MeshMotion, SetUpErrorsAreInputErrors) {
  const Mesh mesh = test::unit_square(3, 3);
  auto motions = all_patches(mesh, BoundaryRole::fixed);
  motions.pop_back();
  EXPECT_THROW(move_mesh(mesh, motions, {}, {}), InputError);  // a patch without role
  motions = all_patches(mesh, BoundaryRole::fixed);
  motions[0].role = BoundaryRole::prescribed;  // without a shape
  EXPECT_THROW(move_mesh(mesh, motions, {}, {}), InputError);
  Mesh open_ended = mesh;  // slip walls along y only: nothing stops a translation along them
  std::erase_if(open_ended.patches, [](const Patch& p) { return p.name == "ymin" || p.name == "ymax"; });
  EXPECT_THROW(move_mesh(open_ended, all_patches(open_ended, BoundaryRole::slip), {}, {}), InputError);
  // Nodes far from the prescribed shape.
  motions = all_patches(mesh, BoundaryRole::fixed);
  motions[0].role = BoundaryRole::prescribed;
  motions[0].shape = std::make_shared<test::TestCurveShape>(std::vector<Vec3>{{5, 0, 0}, {5, 1, 0}},
                                                            [](const Vec3& p, double) { return p; });
  try {
    move_mesh(mesh, motions, {}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("patch 'xmin': 2 nodes lie farther than"));
  }
}

TEST(MeshMotion, SlipOnCurvedPatchIsRefused) {
  Mesh mesh = test::square_ring(4, 3, 0.3, 1.0);
  for (NodeId n : mesh.find_patch("outer")->nodes) mesh.points[static_cast<std::size_t>(n)] *= 1.0;
  std::vector<PatchMotion> motions{{"inner", BoundaryRole::fixed, nullptr}, {"outer", BoundaryRole::slip, nullptr}};
  try {
    move_mesh(mesh, motions, {}, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("patch 'outer' has role slip but is not planar"));
  }
}

}  // namespace
}  // namespace hotmesh::deform
