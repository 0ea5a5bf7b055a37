// Tests of InputError's text (what a terminal shows of a user's bad value) and of the check
// that an input path is a file hotmesh can read without blocking.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <string>

#include "hotmesh/core/input_error.hpp"
#include "test_support.hpp"

namespace hotmesh {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// Issue 18, item 9: a NUL byte cut the message short; raw binary went to the terminal.
TEST(InputError, ControlBytesNulAndBrokenUtf8AreWrittenAsEscapes) {
  const std::string text = std::string("case.yaml:3: patches.a\0b: ", 26) + "\x1b[31mred\x7f \xff\xfe ok";
  const InputError e(text);
  EXPECT_EQ(std::string(e.what()), "case.yaml:3: patches.a\\x00b: \\x1b[31mred\\x7f \\xff\\xfe ok");
}

TEST(InputError, KeepsUtf8TabsAndLines) {
  const InputError e("mesh: Maße\tµm\nsecond line");
  EXPECT_EQ(std::string(e.what()), "mesh: Maße\tµm\nsecond line");
}

// Issue 18, item 9: a 2 MB value was echoed whole.
TEST(InputError, LongLinesAndManyLinesAreCut) {
  const InputError wide("case.yaml:1: mesh: file not found: " + std::string(2'000'000, 'a') + "\nnext");
  const std::string text = wide.what();
  EXPECT_LT(text.size(), 2 * InputError::kMaxLine);
  EXPECT_THAT(text, HasSubstr(" ... (1999035 more bytes)\nnext"));
  std::string many;
  for (int i = 0; i < 1000; ++i) many += "line " + std::to_string(i) + "\n";
  const std::string tall = InputError(many).what();
  EXPECT_THAT(tall, HasSubstr("line 199\n... (800 more lines)"));
  EXPECT_THAT(tall, Not(HasSubstr("line 200")));
}

TEST(InputFile, NamesWhatKeepsAPathFromBeingRead) {
  hotmesh::test::TempDir dir;
  hotmesh::test::write_text(dir / "mesh.msh", "");
  ASSERT_EQ(::mkfifo((dir / "pipe.csv").c_str(), 0600), 0);
  EXPECT_EQ(input_file_problem(dir / "mesh.msh"), "");
  EXPECT_EQ(input_file_problem(dir / "none.msh"), "no such file");
  EXPECT_THAT(input_file_problem(dir.path()), HasSubstr("is a folder"));
  EXPECT_THAT(input_file_problem(dir / "pipe.csv"), HasSubstr("is a named pipe (FIFO)"));
  EXPECT_THAT(input_file_problem("/dev/null"), HasSubstr("is a device"));
  EXPECT_THAT([&] { require_input_file(dir / "pipe.csv"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr((dir / "pipe.csv").string() + ": is a named pipe")));
}

}  // namespace
}  // namespace hotmesh
