// Tests that damaged JSON headers of restart and checkpoint files are refused as damaged,
// naming the file: an integer beyond 64 bits, as the fuzz targets wrote into them (JSON holds
// it as a floating-point number, and nlohmann's conversion of that to an integer was
// undefined: UndefinedBehaviorSanitizer stopped the targets, docs/fuzzing.md), and in restart
// files the values that would reach the curve reconstruction unchecked: a degree out of 1..5,
// a fraction, an unknown sample frame, form or role.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/restart_file.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

/// `bytes` of a state file with `from` replaced by `to` in its JSON header (whose length,
/// the u64 after the magic line `magic`, follows).
std::string with_header_edit(const std::string& bytes, std::string_view magic, const std::string& from,
                             const std::string& to) {
  std::uint64_t length = 0;
  std::memcpy(&length, bytes.data() + magic.size(), sizeof length);
  const std::size_t start = magic.size() + sizeof length;
  std::string header = bytes.substr(start, static_cast<std::size_t>(length));
  const std::string arrays = bytes.substr(start + static_cast<std::size_t>(length));
  const auto at = header.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) header.replace(at, from.size(), to);
  length = header.size();
  std::string edited(magic);
  edited.append(reinterpret_cast<const char*>(&length), sizeof length);
  return edited + header + arrays;
}

/// A restart file of `mesh` with one prescribed patch and its table, as a run writes it.
void write_good_restart(const std::filesystem::path& path, const mesh::Mesh& mesh) {
  RestartState state;
  state.mesh_fingerprint = mesh_fingerprint(mesh);
  state.points = mesh.points;
  state.case_file = "case.yaml";
  DeflectionSpec wall;
  wall.file = "wall.csv";
  wall.samples.frame = geometry::SampleFrame::planar;
  wall.samples.points = {{0, 0, 0}, {1, 0, 0}};
  wall.samples.deflections = {{0, 0, 0}, {0, 0.1, 0}};
  wall.samples.ids = {1, 2};
  state.patches = {{"ymin", deform::BoundaryRole::prescribed, wall}};
  write_restart(path, state);
}

constexpr std::string_view kRestartMagic = "HOTMESH-RESTART\n";

// The fuzz target's restart file had the mesh fingerprint 58211565201344638013, beyond 64
// bits: read as an integer it became some other fingerprint, and the file was blamed on
// another mesh.
TEST(StateFileDamage, RestartFingerprintBeyond64Bits) {
  test::TempDir dir;
  const mesh::Mesh mesh = test::unit_square(2, 2);
  write_good_restart(dir / "good.hmr", mesh);
  const std::string good = test::read_text(dir / "good.hmr");
  const std::string fingerprint = "\"mesh_fingerprint\":" + std::to_string(mesh_fingerprint(mesh));
  const auto path = dir / "bad.hmr";
  test::write_text(path, with_header_edit(good, kRestartMagic, fingerprint, "\"mesh_fingerprint\":58211565201344638013"));
  EXPECT_THAT([&] { read_restart(path, mesh); },
              ThrowsMessage<InputError>(HasSubstr(path.string() + ": the restart file's header is damaged")));
}

// The fuzz target's checkpoint had an input file's hash 97219257311668149021: the file was
// said to have changed since the interrupted run.
TEST(StateFileDamage, CheckpointHashBeyond64Bits) {
  test::TempDir dir;
  test::write_text(dir / "case.yaml", "mesh: mesh.msh\n");
  const mesh::Mesh mesh = test::unit_square(2, 2);
  const std::vector<InputFingerprint> inputs{{dir / "case.yaml", 15, 1234}};
  deform::MotionCheckpoint state;
  state.increments = 4;
  state.points = mesh.points;
  write_checkpoint(dir / "good.hmc", {"case.yaml", mesh_fingerprint(mesh), inputs}, state);
  ASSERT_EQ(read_checkpoint(dir / "good.hmc", mesh, inputs).state.increments, 4);
  const auto path = dir / "bad.hmc";
  test::write_text(path, with_header_edit(test::read_text(dir / "good.hmc"), "HOTMESH-CHECKPOINT\n", "\"hash\":1234",
                                          "\"hash\":97219257311668149021"));
  EXPECT_THAT([&] { read_checkpoint(path, mesh, inputs); },
              ThrowsMessage<InputError>(HasSubstr(path.string() + ": the checkpoint file's header is damaged")));
}

TEST(StateFileDamage, RestartTablesAndRolesOutsideWhatARunWrites) {
  test::TempDir dir;
  const mesh::Mesh mesh = test::unit_square(2, 2);
  write_good_restart(dir / "good.hmr", mesh);
  EXPECT_EQ(read_restart(dir / "good.hmr", mesh).patches.at(0).deflection->degree, 1);

  const std::string good = test::read_text(dir / "good.hmr");
  for (const auto& [from, to, what] : {std::tuple{"\"degree\":1", "\"degree\":7", "degree 7 is not 1 to 5"},
                                       std::tuple{"\"degree\":1", "\"degree\":1.0", "expected an integer, got 1.0"},
                                       std::tuple{"\"frame\":0", "\"frame\":9", "unknown frame 9"},
                                       std::tuple{"\"form\":\"curve\"", "\"form\":\"curvy\"", "unknown form 'curvy'"},
                                       std::tuple{"\"role\":\"prescribed\"", "\"role\":\"prescribes\"",
                                                  "patch 'ymin' has an unknown role 'prescribes'"}}) {
    const auto path = dir / "bad.hmr";
    test::write_text(path, with_header_edit(good, kRestartMagic, from, to));
    EXPECT_THAT([&] { read_restart(path, mesh); },
                ThrowsMessage<InputError>(HasSubstr(path.string() + ": the restart file's header is damaged: " + what)))
        << to;
  }
}

}  // namespace
}  // namespace hotmesh::io

namespace hotmesh::io {
namespace {

/// Restart files keep each sliding node's material parameter whole: (t, s) and face for nodes
/// on faces (format 2), and files of format 1, which held t alone, are still read (a coupling
/// loop that updates hotmesh continues from its last iteration).
TEST(RestartFile, KeepsSurfaceParametersAndReadsFormatOne) {
  test::TempDir dir;
  const mesh::Mesh mesh = test::unit_square(2, 2);
  RestartState state;
  state.mesh_fingerprint = mesh_fingerprint(mesh);
  state.points = mesh.points;
  state.case_file = "case.yaml";
  state.sliding = {{1, {.t = 0.25, .s = 0.75, .face = 2}}, {4, {.t = -1.5, .s = 0.0, .face = 0}}};
  write_restart(dir / "two.hmr", state);
  const RestartState read = read_restart(dir / "two.hmr", mesh);
  ASSERT_EQ(read.sliding.size(), 2u);
  EXPECT_EQ(read.sliding[0].node, 1);
  EXPECT_EQ(read.sliding[0].parameter, state.sliding[0].parameter);
  EXPECT_EQ(read.sliding[1].parameter, state.sliding[1].parameter);

  // Format 1: the same arrays without the s and face arrays (a count and 8 + 4 bytes per node each).
  std::string bytes = test::read_text(dir / "two.hmr");
  bytes.resize(bytes.size() - (2 * sizeof(std::uint64_t) + state.sliding.size() * (sizeof(double) + sizeof(std::int32_t))));
  test::write_text(dir / "one.hmr", with_header_edit(bytes, kRestartMagic, "\"format_version\":2", "\"format_version\":1"));
  const RestartState old = read_restart(dir / "one.hmr", mesh);
  ASSERT_EQ(old.sliding.size(), 2u);
  EXPECT_EQ(old.sliding[0].parameter, (geometry::ShapeParameter{.t = 0.25}));
  EXPECT_EQ(old.sliding[1].parameter, (geometry::ShapeParameter{.t = -1.5}));

  test::write_text(dir / "next.hmr", with_header_edit(test::read_text(dir / "two.hmr"), kRestartMagic,
                                                      "\"format_version\":2", "\"format_version\":3"));
  EXPECT_THAT([&] { read_restart(dir / "next.hmr", mesh); },
              ThrowsMessage<InputError>(HasSubstr("restart file format 3 is not one this hotmesh reads (1 to 2)")));
}

}  // namespace
}  // namespace hotmesh::io
