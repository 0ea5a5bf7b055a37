// hotmesh app: how the OpenMP threads of `hotmesh deform` wait, and why this is the program's
// business, not a library's. Threads that spin while they wait (libgomp's default: 300 000
// turns before sleeping) make a run on a shared machine many times slower than one thread
// (docs/performance.md, threads on a shared machine), so `hotmesh deform` waits passively
// unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT.
//
// libgomp reads both once, in its constructor, as the program is loaded, and offers no call to
// change them later. A setenv() before it is lost too: the only code that runs earlier, the
// program's .preinit_array, runs before the C library has set `environ` from the stack, and
// the C library then sets it over what was added. So the hotmesh program starts itself again,
// once, in its place (execve, the same pid, arguments and environment, with
// OMP_WAIT_POLICY=passive and the marker HOTMESH_DEFAULT_WAIT_POLICY=passive added), from a
// .preinit_array entry in main.cpp, before any constructor has run: the dynamic loading of
// its 140 libraries once more, 80 to 95 ms (docs/performance.md), and only where a
// thread may wait. The entry is in the program's own file: the libraries, and so the tests,
// the fuzz targets, the benchmarks and any program or module built on them, never restart.
#pragma once

#include <string>

namespace hotmesh::app {

/// From the program's .preinit_array, with its argc, argv and envp: when the command (the first
/// argument not starting with '-') is `deform` and the environment sets none of
/// OMP_WAIT_POLICY, GOMP_SPINCOUNT and the marker, starts the program again in its place
/// waiting passively. It does not where that gains nothing: one thread (`--threads 1`,
/// OMP_NUM_THREADS=1), which never waits, or an affinity of one core, as mpirun gives each of
/// 2 ranks, where libgomp spins only 100 turns (so no rank of a job on this machine's 2 cores
/// restarts); nor where it cannot: when the kernel did not start the program itself (run by
/// the dynamic loader, `ld.so hotmesh ...`: /proc/self/exe would be the loader) or under
/// valgrind (execve would start valgrind's tool in its place). wait_policy() then says why.
/// Returns in the restarted program, or when it did not restart. Uses nothing but its
/// arguments, static storage, getauxval, sched_getaffinity and execve: the C library is not
/// yet started.
void restart_waiting_passively(int argc, char** argv, char** envp);

/// How this process's OpenMP threads wait, for the log and report.json: "passive (hotmesh's
/// default)", "OMP_WAIT_POLICY=active (set by the user)", or libgomp's default and why
/// hotmesh did not change it.
std::string wait_policy();

}  // namespace hotmesh::app
