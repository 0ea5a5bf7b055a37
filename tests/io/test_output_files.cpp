// Tests of the "nothing lost" guarantees: atomic writes, output folders, inputs never replaced.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>

#include "hotmesh/geometry/input_error.hpp"
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
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/mesh.msh: cannot open"));
  }
}

TEST(OutputFolder, CreatesMissingFolder) {
  test::TempDir dir;
  const std::array<std::filesystem::path, 1> inputs{dir / "case.yaml"};
  prepare_output_folder(dir / "a" / "b", inputs, false);
  EXPECT_TRUE(std::filesystem::is_directory(dir / "a" / "b"));
}

TEST(OutputFolder, RefusesFolderHoldingAnInputUnlessForced) {
  test::TempDir dir;
  test::write_text(dir / "case.yaml", "");
  std::filesystem::create_directories(dir / "sub");
  test::write_text(dir / "sub" / "mesh.msh", "");
  const std::array<std::filesystem::path, 2> inputs{dir / "case.yaml", dir / "sub" / "mesh.msh"};
  EXPECT_THROW(prepare_output_folder(dir.path(), inputs, false), InputError);
  EXPECT_THROW(prepare_output_folder(dir / "sub" / ".", inputs, false), InputError);
  EXPECT_NO_THROW(prepare_output_folder(dir / "out", inputs, false));
  EXPECT_NO_THROW(prepare_output_folder(dir.path(), inputs, true));
}

TEST(OutputFolder, RefusesAFileAsFolder) {
  test::TempDir dir;
  test::write_text(dir / "file", "");
  EXPECT_THROW(prepare_output_folder(dir / "file", {}, true), InputError);
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
