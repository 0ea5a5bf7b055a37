// Tests that a damaged state file cannot make its reader reserve memory the file does not
// hold, with inputs fuzzing found (tests/data/fuzz/, docs/fuzzing.md): every operator new of
// this test program records the largest size asked for while armed. (Skipped under
// AddressSanitizer, which provides its own operator new; the fuzz targets run with a limit
// on single allocations there.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <new>

#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "test_support.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define HOTMESH_COUNT_ALLOCATIONS 0
#else
#define HOTMESH_COUNT_ALLOCATIONS 1

namespace {
thread_local bool armed = false;
thread_local std::size_t largest = 0;
}  // namespace

void* operator new(std::size_t size) {
  if (armed) largest = std::max(largest, size);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace hotmesh::io {
namespace {

using ::testing::HasSubstr;

// 27 bytes: the magic line and a header length of 1.7e19 bytes. The header was read into a
// buffer of min(length, 1 GiB) bytes, zeroed, before the file was found to be cut short.
TEST(StateFileAllocations, CheckpointHeaderLengthBeyondTheFileReservesNothing) {
  if (!HOTMESH_COUNT_ALLOCATIONS) GTEST_SKIP() << "operator new belongs to the sanitizer";
#if HOTMESH_COUNT_ALLOCATIONS
  const auto file = test::data_path("fuzz/checkpoint-header-length-beyond-file.hmc");
  largest = 0;
  armed = true;
  try {
    read_checkpoint_info(file);
    armed = false;
    ADD_FAILURE() << "a 27-byte checkpoint was accepted";
  } catch (const InputError& e) {
    armed = false;
    EXPECT_THAT(e.what(), HasSubstr(file.string()));
    EXPECT_THAT(e.what(), HasSubstr("cut short"));
  }
  EXPECT_LT(largest, std::size_t{1} << 20);
#endif
}

}  // namespace
}  // namespace hotmesh::io
