// hotmesh tests: libhotmesh_faults.so, preloaded (LD_PRELOAD) into a hotmesh process by the
// tests that need it killed, or out of memory, at a chosen point of a run; hotmesh itself has
// nothing for them. The tests set it up with faults.hpp. Each fault is asked for by a variable
// of the process's environment, K counting the checkpoints the process has put in place (the
// rename of the written temporary file onto <output>/checkpoint.hmc, io/atomic_file.cpp; one
// after every accepted increment or piece of one):
//
//   HOTMESH_TEST_KILL_AFTER_CHECKPOINT=K: right after its K-th checkpoint the process kills
//     itself with SIGKILL, as the out-of-memory killer or a batch system's time limit would.
//   HOTMESH_TEST_FAIL_ALLOCATION_AFTER_CHECKPOINT=K: after its K-th checkpoint, the process's
//     next C++ allocation of at least kLargeAllocation bytes on its main thread throws
//     std::bad_alloc, once, as when memory runs out. That is deterministic: the main thread
//     does the run's work between steps, and the first such allocation is a vector of the next
//     increment. Worker threads are left alone: an exception that leaves an OpenMP loop ends
//     the process with std::terminate, not with hotmesh's report of memory running out.
//
//   HOTMESH_TEST_HOLD_CAD_CHECK=FILE: a `hotmesh cad` process (the child by which `hotmesh
//     serve` reads a CAD file first, service/cad_check.hpp) waits at its start until FILE
//     exists (at most two minutes): the request that loads the file holds its heavy slot
//     until the test creates FILE, whatever the machine's speed.
//
//   HOTMESH_TEST_ABORT_IN_HDF5_OPEN=1: the process aborts (SIGABRT) when the CGNS library
//     opens an HDF5 file (H5Fopen), as libhdf5 aborted in cg_open on a CGNS file with a
//     damaged link name (issue 46): hotmesh reads CGNS files in a child process first, so that
//     such a fault is an error naming the file (io/src/cgns/cgns_library.hpp, check_in_child).
//
// Only the process that writes the checkpoints is hit: the only one, or rank 0 under mpirun.
// The other ranks run on into the next increment while rank 0 writes, so from outside none
// of them can tell where in its own run a checkpoint put in place falls.
//
// The library replaces rename(3), H5Fopen and the plain operator new and new[] (the aligned ones stay
// libstdc++'s), each passing on to the next definition (libc's, libstdc++'s, or the
// AddressSanitizer runtime's). It is built without sanitizers: it stands in front of the
// sanitizer runtime, and tells it so (__asan_default_options below).
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <climits>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string_view>

namespace {

constexpr std::string_view kCheckpointName = "checkpoint.hmc";  // hotmesh::io::kCheckpointName
constexpr const char* kKillVariable = "HOTMESH_TEST_KILL_AFTER_CHECKPOINT";
constexpr const char* kFailAllocationVariable = "HOTMESH_TEST_FAIL_ALLOCATION_AFTER_CHECKPOINT";

/// From this size on an allocation is one of the run's arrays (a vector over the mesh's nodes),
/// not a small string or node of the bookkeeping around them.
constexpr std::size_t kLargeAllocation = 1024;

std::atomic<int> g_checkpoints{0};
std::atomic<bool> g_fail_next_large_allocation{false};

/// A line on stderr, written at once and without allocating (operator new may be the caller).
[[gnu::format(printf, 1, 2)]] void say(const char* format, ...) {
  char line[256];
  std::va_list arguments;
  va_start(arguments, format);
  const int n = std::vsnprintf(line, sizeof line, format, arguments);
  va_end(arguments);
  if (n <= 0) return;
  const std::size_t size = std::min(static_cast<std::size_t>(n), sizeof line - 1);
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, line, size);
}

/// The K of variable `name`; 0 if it is not set. A value that is not a positive integer is a
/// mistake of the test: the process stops at once rather than run without the fault.
int checkpoint_count(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return 0;
  char* end = nullptr;
  const long k = std::strtol(text, &end, 10);
  if (*end != '\0' || k <= 0 || k > INT_MAX) {
    say("hotmesh_faults: %s must be a positive integer, got '%s'\n", name, text);
    std::abort();
  }
  return static_cast<int>(k);
}

bool names_checkpoint(const char* path) {
  const char* slash = std::strrchr(path, '/');
  return std::string_view(slash != nullptr ? slash + 1 : path) == kCheckpointName;
}

void checkpoint_in_place() {
  const int done = ++g_checkpoints;
  if (done == checkpoint_count(kKillVariable)) {
    say("hotmesh_faults: killing the process after checkpoint %d (%s)\n", done, kKillVariable);
    ::raise(SIGKILL);
  }
  if (done == checkpoint_count(kFailAllocationVariable)) g_fail_next_large_allocation = true;
}

void fail_if_asked(std::size_t size) {
  if (!g_fail_next_large_allocation.load(std::memory_order_relaxed) || size < kLargeAllocation) return;
  if (::gettid() != ::getpid() || !g_fail_next_large_allocation.exchange(false)) return;
  say("hotmesh_faults: failing an allocation of %zu bytes after checkpoint %d (%s)\n", size, g_checkpoints.load(),
      kFailAllocationVariable);
  throw std::bad_alloc();
}

/// The definition of `symbol` that this library's stands in front of.
template <typename Function>
Function next_definition(const char* symbol) {
  void* found = ::dlsym(RTLD_NEXT, symbol);
  if (found == nullptr) {
    say("hotmesh_faults: no %s to pass on to\n", symbol);
    std::abort();
  }
  return std::bit_cast<Function>(found);
}

using RenameFunction = int (*)(const char*, const char*);
using AllocationFunction = void* (*)(std::size_t);

/// Whether this process's command line has the word `word` (a subcommand).
bool command_has(std::string_view word) {
  const int fd = ::open("/proc/self/cmdline", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  char line[4096];
  const ssize_t n = ::read(fd, line, sizeof line - 1);
  ::close(fd);
  for (ssize_t at = 0; at < n;) {
    const std::string_view arg(line + at);
    if (arg == word) return true;
    at += static_cast<ssize_t>(arg.size()) + 1;
  }
  return false;
}

/// HOTMESH_TEST_HOLD_CAD_CHECK: a `hotmesh cad` process waits for the file to exist.
[[gnu::constructor]] void hold_cad_check() {
  const char* file = std::getenv("HOTMESH_TEST_HOLD_CAD_CHECK");
  if (file == nullptr || *file == '\0' || !command_has("cad")) return;
  const timespec tick{0, 10'000'000};
  for (int i = 0; i < 12'000 && ::access(file, F_OK) != 0; ++i) ::nanosleep(&tick, nullptr);
}

}  // namespace

extern "C" int rename(const char* from, const char* to) noexcept {
  static const auto next = next_definition<RenameFunction>("rename");
  const int result = next(from, to);
  if (result == 0 && to != nullptr && names_checkpoint(to)) checkpoint_in_place();
  return result;
}

// libhdf5's H5Fopen (HDF5 1.10: hid_t is a 64-bit integer), which the CGNS library calls.
extern "C" std::int64_t H5Fopen(const char* name, unsigned flags, std::int64_t access) {
  using OpenFunction = std::int64_t (*)(const char*, unsigned, std::int64_t);
  const char* abort_here = std::getenv("HOTMESH_TEST_ABORT_IN_HDF5_OPEN");
  if (abort_here != nullptr && std::string_view(abort_here) == "1") {
    say("hotmesh_faults: aborting in H5Fopen(%s) (HOTMESH_TEST_ABORT_IN_HDF5_OPEN)\n", name);
    std::abort();
  }
  static const auto next = next_definition<OpenFunction>("H5Fopen");
  return next(name, flags, access);
}

// The Itanium C++ ABI's names of operator new(std::size_t) and operator new[](std::size_t) on
// 64-bit Linux.
void* operator new(std::size_t size) {
  fail_if_asked(size);
  static const auto next = next_definition<AllocationFunction>("_Znwm");
  return next(size);
}

void* operator new[](std::size_t size) {
  fail_if_asked(size);
  static const auto next = next_definition<AllocationFunction>("_Znam");
  return next(size);
}

// Under GCC's AddressSanitizer (a shared runtime) this library comes before the runtime in the
// process's list of libraries, which the runtime refuses unless told to accept it. Options in
// ASAN_OPTIONS still take precedence; clang's runtime, linked into the executable, does not
// check the order and keeps its own operator new (faults.hpp: allocation_faults_reach_hotmesh).
extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }
