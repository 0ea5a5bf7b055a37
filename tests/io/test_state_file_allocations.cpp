// Tests that a damaged state file cannot make its reader reserve memory the file does not
// hold, with inputs fuzzing found (tests/data/fuzz/, docs/fuzzing.md): every operator new of
// this test program records the largest size asked for while armed. (Skipped under
// AddressSanitizer, which provides its own operator new; the fuzz targets run with a limit
// on single allocations there.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "allocation_watch.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using ::testing::HasSubstr;

// 27 bytes: the magic line and a header length of 1.7e19 bytes. The header was read into a
// buffer of min(length, 1 GiB) bytes, zeroed, before the file was found to be cut short.
TEST(StateFileAllocations, CheckpointHeaderLengthBeyondTheFileReservesNothing) {
  if (!HOTMESH_WATCH_ALLOCATIONS) GTEST_SKIP() << "operator new belongs to the sanitizer";
#if HOTMESH_WATCH_ALLOCATIONS
  const auto file = test::data_path("fuzz/checkpoint-header-length-beyond-file.hmc");
  ::test::allocations::arm();
  try {
    read_checkpoint_info(file);
    ::test::allocations::armed = false;
    ADD_FAILURE() << "a 27-byte checkpoint was accepted";
  } catch (const InputError& e) {
    ::test::allocations::armed = false;
    EXPECT_THAT(e.what(), HasSubstr(file.string()));
    EXPECT_THAT(e.what(), HasSubstr("cut short"));
  }
  EXPECT_LT(::test::allocations::largest, std::size_t{1} << 20);
#endif
}

}  // namespace
}  // namespace hotmesh::io
