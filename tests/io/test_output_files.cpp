// Tests of the "nothing lost" guarantees: atomic writes, output folders, inputs never replaced.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <string>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/output_folder.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using ::testing::HasSubstr;

TEST(AtomicFile, TargetKeepsOldContentUntilCommit) {
  test::TempDir dir;
  test::write_text(dir / "out.txt", "old");
  {
    AtomicFile file(dir / "out.txt");
    file.stream() << "new";
    EXPECT_EQ(test::read_text(dir / "out.txt"), "old");
    file.commit();
  }
  EXPECT_EQ(test::read_text(dir / "out.txt"), "new");
}

TEST(AtomicFile, AbandonedWriteLeavesTargetAndNoTemporary) {
  test::TempDir dir;
  test::write_text(dir / "out.txt", "last valid");
  try {
    AtomicFile file(dir / "out.txt");
    file.stream() << "half writ";
    throw std::runtime_error("run failed midway");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(test::read_text(dir / "out.txt"), "last valid");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(AtomicFile, UnwritableFolderIsAnInputError) {
  EXPECT_THROW(AtomicFile("/nonexistent-folder/out.txt"), InputError);
}

TEST(ReadFile, NamesFileThatCannotBeRead) {
  try {
    read_file("/nonexistent/mesh.msh");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/mesh.msh: no such file"));
  }
}

// Issue 18, item 7: a FIFO as an input blocked hotmesh forever (open() waits for a writer).
TEST(ReadFile, RefusesNamedPipesAndFoldersWithoutWaiting) {
  test::TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "mesh.msh").c_str(), 0600), 0);
  EXPECT_THAT([&] { read_file(dir / "mesh.msh"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("mesh.msh: is a named pipe (FIFO), not a regular file")));
  EXPECT_THAT([&] { read_file(dir.path()); }, ::testing::ThrowsMessage<InputError>(HasSubstr("is a folder")));
  EXPECT_THAT([&] { read_file("/dev/zero"); }, ::testing::ThrowsMessage<InputError>(HasSubstr("/dev/zero: is a device")));
}

/// A process id that no process has now: a child that has ended.
pid_t ended_process() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

TEST(AtomicFile, StaleTemporariesOfEndedRunsAreRemovedThoseOfLiveOnesKept) {
  test::TempDir dir;
  const std::string dead = "checkpoint.hmc.tmp-" + std::to_string(ended_process()) + "-0";
  const std::string live = "checkpoint.hmc.tmp-" + std::to_string(::getppid()) + "-3";
  const std::string other = "notes.txt.tmp-" + std::to_string(ended_process()) + "-0";
  const std::string in_subfolder = "polyMesh/points.tmp-" + std::to_string(ended_process()) + "-0";
  std::filesystem::create_directories(dir / "polyMesh");
  for (const auto& name : {dead, live, other, in_subfolder}) test::write_text(dir / name, "x");
  const std::array<std::string, 3> names{"checkpoint.hmc", "report.json", "polyMesh/points"};
  remove_stale_temporaries(dir.path(), names);
  EXPECT_FALSE(std::filesystem::exists(dir / dead));
  EXPECT_FALSE(std::filesystem::exists(dir / in_subfolder));  // an output in a subfolder (OpenFOAM's polyMesh/)
  EXPECT_TRUE(std::filesystem::exists(dir / live));
  EXPECT_TRUE(std::filesystem::exists(dir / other));  // not one of the outputs
}

TEST(OutputFolder, CreatesMissingFolder) {
  test::TempDir dir;
  const std::array<std::filesystem::path, 1> inputs{dir / "case.yaml"};
  const OutputFolder folder = prepare_output_folder(dir / "a" / "b", inputs, false);
  EXPECT_TRUE(std::filesystem::is_directory(dir / "a" / "b"));
  EXPECT_EQ(folder.path(), dir / "a" / "b");
}

TEST(OutputFolder, FoldersItCreatedGoAgainIfNothingWasWritten) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "runs");
  { const OutputFolder unused = prepare_output_folder(dir / "runs" / "a" / "b/", {}, false); }
  EXPECT_TRUE(std::filesystem::is_directory(dir / "runs"));  // was there before
  EXPECT_FALSE(std::filesystem::exists(dir / "runs" / "a"));
  {
    const OutputFolder written = prepare_output_folder(dir / "runs" / "c", {}, false);
    test::write_text(dir / "runs" / "c" / "report.json", "{}");
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "runs" / "c" / "report.json"));
  {
    OutputFolder kept = prepare_output_folder(dir / "runs" / "d", {}, false);
    kept.keep();
  }
  EXPECT_TRUE(std::filesystem::is_directory(dir / "runs" / "d"));
}

TEST(OutputFolder, RefusesAFolderItCannotWriteIn) {
  // Root writes in any folder its permissions close; sysfs refuses new files to everyone.
  test::TempDir dir;
  std::filesystem::path closed = dir / "closed";
  std::filesystem::create_directories(closed);
  std::filesystem::permissions(closed, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (::geteuid() == 0) closed = "/sys";
  try {
    const OutputFolder unused = prepare_output_folder(closed, {}, false);
    FAIL() << "accepted " << closed;
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(closed.string() + ": cannot write in the output folder"));
  }
  std::filesystem::permissions(dir / "closed", std::filesystem::perms::owner_all);
}

TEST(OutputFolder, RefusesFolderHoldingAnInputUnlessForced) {
  test::TempDir dir;
  test::write_text(dir / "case.yaml", "");
  std::filesystem::create_directories(dir / "sub");
  test::write_text(dir / "sub" / "mesh.msh", "");
  const std::array<std::filesystem::path, 2> inputs{dir / "case.yaml", dir / "sub" / "mesh.msh"};
  EXPECT_THROW(static_cast<void>(prepare_output_folder(dir.path(), inputs, false)), InputError);
  EXPECT_THROW(static_cast<void>(prepare_output_folder(dir / "sub" / ".", inputs, false)), InputError);
  EXPECT_NO_THROW(static_cast<void>(prepare_output_folder(dir / "out", inputs, false)));
  EXPECT_NO_THROW(static_cast<void>(prepare_output_folder(dir.path(), inputs, true)));
}

TEST(OutputFolder, RefusesAFileAsFolder) {
  test::TempDir dir;
  test::write_text(dir / "file", "");
  EXPECT_THROW(static_cast<void>(prepare_output_folder(dir / "file", {}, true)), InputError);
}

TEST(OutputFolder, NeverReplacesAnInputEvenThroughAnotherSpelling) {
  test::TempDir dir;
  test::write_text(dir / "mesh.msh", "");
  const std::array<std::filesystem::path, 1> inputs{dir / "mesh.msh"};
  EXPECT_THROW(refuse_overwriting_input(dir / "." / "mesh.msh", inputs), InputError);
  EXPECT_NO_THROW(refuse_overwriting_input(dir / "other.msh", inputs));
}

}  // namespace
}  // namespace hotmesh::io
