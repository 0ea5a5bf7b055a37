// Tests of checkpoint files (checkpoint.hmc): every field comes back bit for bit, and a
// checkpoint is refused, naming what differs, when an input file changed, for another mesh,
// when damaged, or when it is not a checkpoint at all.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "output_folders.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using ::testing::HasSubstr;

/// A case whose input files exist in `dir`: the case file, the mesh and one table.
Case case_in(const test::TempDir& dir) {
  test::write_text(dir / "case.yaml", "mesh: mesh.msh\n");
  test::write_text(dir / "mesh.msh", "mesh bytes");
  test::write_text(dir / "wall.csv", "x,y,dx,dy\n0,0,0,0\n1,0,0,0.1\n");
  Case c;
  c.file = dir / "case.yaml";
  c.mesh = dir / "mesh.msh";
  PatchSpec wall;
  wall.name = "wall";
  wall.role = PatchRole::sliding;
  wall.deflection = DeflectionSpec{};
  wall.deflection->file = dir / "wall.csv";
  c.patches.push_back(wall);
  return c;
}

deform::MotionCheckpoint some_state(const mesh::Mesh& mesh) {
  deform::MotionCheckpoint s;
  s.increments = 8;
  s.finished_increments = 2;
  s.lambda = 0.3125;
  s.split_pieces = {{3, 0.3125, 0.34375, 2}, {3, 0.34375, 0.375, 2}};
  s.points = mesh.points;
  for (auto& p : s.points) p = (1.0 + 1e-13) * p + geometry::Vec3{0.1, -0.2, 0.0};
  s.previous_points = mesh.points;
  for (auto& p : s.previous_points) p = (1.0 - 1e-13) * p + geometry::Vec3{0.05, -0.1, 0.0};
  s.previous_lambda = 0.25;
  s.sliding = {{3, {0.5, 1.0 / 3.0, 0.0}, {{{.t = 0.25}, geometry::kNoHint, {.t = 0.0, .s = -0.5, .face = 4}}}},
               {7, {1.0, 2.0, 3.0}, {{{.t = 1.0}, {.t = 2.0, .s = 0.75, .face = 1}, {.t = 3.0}}}}};
  deform::IncrementRecord rejected;
  rejected.increment = 3;
  rejected.lambda_begin = 0.25;
  rejected.lambda_end = 0.375;
  rejected.newton = {{1.5, 12, true, 1e-3, 1e-3, 1e-17}, {std::numeric_limits<double>::infinity(), 0, false, 0.0, 0.0, 0.0}};
  rejected.failure = "the Newton-Raphson cycle diverged (\"quoted\")";
  rejected.residual_reduction = std::numeric_limits<double>::quiet_NaN();
  deform::IncrementRecord accepted;
  accepted.increment = 2;
  accepted.split_depth = 0;
  accepted.newton = {{2.0, 40, true, 1e-4, 0.25, 0.1, true}, {1e-5, 0, true, 0.0, 0.0, 0.0}};
  accepted.converged = accepted.accepted = true;
  accepted.residual_reduction = 5e-6;
  accepted.min_scaled_jacobian = 0.7071067811865476;
  accepted.worst_cell = 5;
  accepted.max_normal_slip = 3e-18;
  accepted.seconds = 0.123;
  s.records = {accepted, rejected};
  s.timings = {0.1, 0.2, 0.25, 0.3, 0.4, 0.5, 1.6};
  return s;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(CheckpointFile, RoundTripKeepsEveryFieldBitForBit) {
  test::TempDir dir;
  const Case c = case_in(dir);
  const mesh::Mesh mesh = test::unit_square(3, 2);
  const auto inputs = input_fingerprints(c);
  ASSERT_EQ(inputs.size(), 3u);  // case file, mesh, table
  EXPECT_EQ(inputs[1].bytes, 10u);
  write_checkpoint(dir / "checkpoint.hmc", checkpoint_origin(c, mesh, inputs), some_state(mesh));

  const Checkpoint k = read_checkpoint(dir / "checkpoint.hmc", mesh, inputs);
  const deform::MotionCheckpoint expected = some_state(mesh);
  const deform::MotionCheckpoint& s = k.state;
  EXPECT_EQ(k.info.case_file, c.file.string());
  EXPECT_FALSE(k.info.written_at.empty());
  EXPECT_EQ(s.increments, 8);
  EXPECT_EQ(s.finished_increments, 2);
  EXPECT_TRUE(same_bits(s.lambda, expected.lambda));
  ASSERT_EQ(s.split_pieces.size(), 2u);
  EXPECT_EQ(s.split_pieces[0].increment, 3);
  EXPECT_EQ(s.split_pieces[0].split_depth, 2);
  EXPECT_TRUE(same_bits(s.split_pieces[1].lambda_begin, 0.34375));
  ASSERT_EQ(s.points.size(), expected.points.size());
  EXPECT_EQ(std::memcmp(s.points.data(), expected.points.data(), s.points.size() * sizeof(geometry::Vec3)), 0);
  ASSERT_EQ(s.previous_points.size(), expected.previous_points.size());  // the predictor's secant
  EXPECT_EQ(std::memcmp(s.previous_points.data(), expected.previous_points.data(),
                        s.previous_points.size() * sizeof(geometry::Vec3)), 0);
  EXPECT_TRUE(same_bits(s.previous_lambda, 0.25));
  ASSERT_EQ(s.sliding.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(s.sliding[i].node, expected.sliding[i].node);
    EXPECT_TRUE(same_bits(s.sliding[i].target.y, expected.sliding[i].target.y));
    for (std::size_t h = 0; h < 3; ++h) {
      EXPECT_TRUE(same_bits(s.sliding[i].hints[h].t, expected.sliding[i].hints[h].t));
      EXPECT_TRUE(same_bits(s.sliding[i].hints[h].s, expected.sliding[i].hints[h].s));
      EXPECT_EQ(s.sliding[i].hints[h].face, expected.sliding[i].hints[h].face);
    }
  }
  ASSERT_EQ(s.records.size(), 2u);
  const auto& a = s.records[0];
  EXPECT_TRUE(a.accepted);
  EXPECT_TRUE(same_bits(a.min_scaled_jacobian, 0.7071067811865476));
  EXPECT_TRUE(same_bits(a.newton[0].max_projection, 0.1));
  EXPECT_TRUE(same_bits(a.newton[0].linear_tolerance, 0.25));
  EXPECT_EQ(a.newton[0].pcg_iterations, 40);
  EXPECT_TRUE(a.newton[0].linear_newton_norm);
  EXPECT_FALSE(a.newton[1].linear_newton_norm);
  EXPECT_EQ(a.worst_cell, 5);
  const auto& r = s.records[1];
  EXPECT_FALSE(r.accepted);
  EXPECT_TRUE(std::isnan(r.residual_reduction));
  EXPECT_TRUE(std::isinf(r.newton[1].residual));
  EXPECT_FALSE(r.newton[1].pcg_converged);
  EXPECT_EQ(r.failure, expected.records[1].failure);
  EXPECT_TRUE(same_bits(s.timings.total, 1.6));
  EXPECT_TRUE(same_bits(s.timings.preconditioner, 0.25));

  const CheckpointInfo info = read_checkpoint_info(dir / "checkpoint.hmc");
  EXPECT_EQ(info.finished_increments, 2);
  EXPECT_EQ(info.increments, 8);
}

TEST(CheckpointFile, SizeDoesNotGrowWithTheIncrementsLeft) {
  // Issue 18: the checkpoint listed every increment left (31 bytes each) and was rewritten
  // after each one. After increment 2 of 8 or of 8000, the state is the same but for N.
  test::TempDir dir;
  const Case c = case_in(dir);
  const mesh::Mesh mesh = test::unit_square(3, 2);
  const CheckpointOrigin origin = checkpoint_origin(c, mesh, input_fingerprints(c));
  deform::MotionCheckpoint s = some_state(mesh);
  write_checkpoint(dir / "few.hmc", origin, s);
  s.increments = 8000;
  write_checkpoint(dir / "many.hmc", origin, s);
  EXPECT_EQ(std::filesystem::file_size(dir / "many.hmc"), std::filesystem::file_size(dir / "few.hmc") + 3);
}

TEST(CheckpointFile, ReadsFormatOneListingEveryStepLeft) {
  test::TempDir dir;
  const Case c = case_in(dir);
  const mesh::Mesh mesh = test::unit_square(3, 2);
  const auto inputs = input_fingerprints(c);
  write_checkpoint(dir / "checkpoint.hmc", checkpoint_origin(c, mesh, inputs), some_state(mesh));
  test::rewrite_as_checkpoint_format_1(dir / "checkpoint.hmc");
  ASSERT_THAT(test::read_text(dir / "checkpoint.hmc"), HasSubstr("\"remaining\":[[3,0.3125,0.34375,2],[3,0.34375,0.375,2],"
                                                                  "[4,0.375,0.5,0],"));
  const Checkpoint k = read_checkpoint(dir / "checkpoint.hmc", mesh, inputs);
  const deform::MotionCheckpoint expected = some_state(mesh);
  ASSERT_EQ(k.state.split_pieces.size(), 2u);  // the whole increments 4 to 8 follow from finished_increments
  EXPECT_TRUE(same_bits(k.state.split_pieces[1].lambda_end, 0.375));
  EXPECT_EQ(k.state.records.size(), 2u);
  EXPECT_EQ(k.state.finished_increments, 2);
  EXPECT_EQ(std::memcmp(k.state.points.data(), expected.points.data(), k.state.points.size() * sizeof(geometry::Vec3)), 0);
  EXPECT_EQ(read_checkpoint_info(dir / "checkpoint.hmc").finished_increments, 2);
}

TEST(CheckpointFile, ChangedInputIsRefusedNamingTheFile) {
  test::TempDir dir;
  const Case c = case_in(dir);
  const mesh::Mesh mesh = test::unit_square(3, 2);
  write_checkpoint(dir / "checkpoint.hmc", checkpoint_origin(c, mesh, input_fingerprints(c)), some_state(mesh));
  test::write_text(dir / "wall.csv", "x,y,dx,dy\n0,0,0,0\n1,0,0,0.2\n");  // same size, other bytes
  try {
    read_checkpoint(dir / "checkpoint.hmc", mesh, input_fingerprints(c));
    FAIL() << "a changed table was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "checkpoint.hmc").string() + ": cannot resume"));
    EXPECT_THAT(e.what(), HasSubstr((dir / "wall.csv").string() + " has changed"));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("mesh.msh")));
  }
  // An input more (or less) than the interrupted run had.
  Case more = c;
  more.cad = dir / "extra.step";
  test::write_text(dir / "extra.step", "ISO-10303-21;");
  test::write_text(dir / "wall.csv", "x,y,dx,dy\n0,0,0,0\n1,0,0,0.1\n");
  try {
    read_checkpoint(dir / "checkpoint.hmc", mesh, input_fingerprints(more));
    FAIL() << "a new input was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "extra.step").string() + " is a new input"));
  }
  EXPECT_NO_THROW(read_checkpoint(dir / "checkpoint.hmc", mesh, input_fingerprints(c)));  // restored
}

TEST(CheckpointFile, AnotherMeshIsRefused) {
  test::TempDir dir;
  const Case c = case_in(dir);
  const mesh::Mesh mesh = test::unit_square(3, 2);
  write_checkpoint(dir / "checkpoint.hmc", checkpoint_origin(c, mesh, input_fingerprints(c)), some_state(mesh));
  mesh::Mesh moved = mesh;
  moved.points[4].x += 1e-9;
  try {
    read_checkpoint(dir / "checkpoint.hmc", moved, input_fingerprints(c));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("written for another mesh"));
  }
}

TEST(CheckpointFile, DamagedOrForeignFilesAreRefused) {
  test::TempDir dir;
  const Case c = case_in(dir);
  const mesh::Mesh mesh = test::unit_square(3, 2);
  const auto inputs = input_fingerprints(c);
  write_checkpoint(dir / "checkpoint.hmc", checkpoint_origin(c, mesh, inputs), some_state(mesh));
  const std::string good = test::read_text(dir / "checkpoint.hmc");
  const auto refused = [&](const std::string& bytes, const std::string& message) {
    test::write_text(dir / "bad.hmc", bytes);
    try {
      read_checkpoint(dir / "bad.hmc", mesh, inputs);
      ADD_FAILURE() << "accepted: " << message;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr((dir / "bad.hmc").string()));
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  std::string flipped = good;
  flipped[flipped.size() - 20] ^= 0x01;  // a bit of a previous point
  refused(flipped, "does not match its checksum");
  std::string hint = good;
  hint[hint.size() - 20 - 8 - 3 * 8 * mesh.node_count()] ^= 0x01;  // a bit of a sliding node's hints
  refused(hint, "does not match its checksum");
  refused(good.substr(0, good.size() - 9), "damaged");
  refused(good.substr(0, 30), "cut short");
  refused("hello", "not a hotmesh checkpoint file");
  std::string version = good;
  version.replace(version.find("\"format_version\":4"), 18, "\"format_version\":7");
  refused(version, "checkpoint format 7 is not one this hotmesh reads (1 to 4)");
  EXPECT_THROW(read_checkpoint_info(dir / "bad.hmc"), InputError);
}

}  // namespace
}  // namespace hotmesh::io
