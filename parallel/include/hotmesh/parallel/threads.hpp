// hotmesh parallel: how many OpenMP threads a run uses, and how they wait. On a machine that
// runs other work beside hotmesh (a flow solver, a build), a second thread can cost more than
// it gives: every parallel loop ends in a barrier that waits for the slowest thread, and a
// thread whose core another process holds is late by a time slice. So, unless the user gave
// a count (`--threads`, `solver.threads`, OMP_NUM_THREADS), a run takes one thread per core
// that is actually free, and one thread for a mesh below the size where threads pay
// (measured, docs/performance.md "Threads on a shared machine"); waiting threads sleep at once
// instead of spinning for their core (OMP_WAIT_POLICY=passive), unless the user said otherwise:
// that is the hotmesh program's choice (app/cli/passive_wait.hpp), since libgomp reads it as it is
// loaded, and a library cannot make it for the program that links it.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

namespace hotmesh::parallel {

/// Nodes of a mesh from which a second thread gains at least a tenth of a whole run on an idle
/// machine (bench_busy --sweep, 2 cores, 2026-12-07): 3D ducts sliding over CAD faces
/// (jacobi-pcg) broke even at 3 190 nodes and gained 14 % at 6 048 and 29 % at 21 777; 2D ramps
/// (icc, threaded in the element pass and the vector work around PETSc's solves) broke even at
/// 2 378 nodes and gained 12 % at 9 315. Below them a run takes one thread unless told.
inline constexpr std::size_t kThreadsPayNodes2d = 8000;
inline constexpr std::size_t kThreadsPayNodes3d = 5000;
/// A core counts as free while other processes keep less than this share of it busy.
inline constexpr double kBusyCore = 0.25;

/// A count of threads the user asked for.
struct ThreadRequest {
  int count = 0;     ///< > 0: exactly this many; 0: hotmesh chooses
  std::string from;  ///< who asked, as the user wrote it: "--threads 1", "solver.threads: 2", "OMP_NUM_THREADS=2"
};

/// What the choice is made from.
struct ThreadInputs {
  ThreadRequest request;
  int cores = 1;                  ///< cores the process may use: its affinity, within its CPU quota
  int processes = 1;              ///< processes of the job sharing those cores (mpirun)
  std::size_t nodes = 0;          ///< nodes of the mesh
  std::size_t pay_from = 0;       ///< nodes from which threads pay (kThreadsPayNodes2d or 3d)
};

struct ThreadChoice {
  int threads = 1;
  std::string reason;                 ///< why, for the log and report.json: "2 cores free", ...
  std::optional<double> others_busy;  ///< cores other processes kept busy, when it was looked at
};

/// The threads of a run: the user's count as given; else one thread on one core, or below
/// `pay_from` nodes; the job's share of the cores with several processes; else the cores
/// other processes leave free (`others_busy()`: how many of the cores they keep busy, asked
/// only then). Pure, for tests; the command passes machine_cores() and a LoadProbe.
ThreadChoice choose_threads(const ThreadInputs& in, const std::function<double()>& others_busy);

/// Cores this process may run on: the CPUs of its affinity mask (sched_getaffinity), at most
/// its cgroup's CPU quota (cpu.max), at least 1.
int machine_cores();

/// Processes of the job on this machine (mpirun's local size), 1 without a launcher.
int local_processes(int job_processes);

/// Started at construction; others() is the mean number of this process's cores that other
/// processes kept busy since then, from /proc/stat (user, system, interrupts and time stolen
/// by the hypervisor, less this process's own CPU time), over at least `at_least` seconds
/// (it sleeps for the rest: the counts tick every 10 ms). Without /proc/stat, 0.
class LoadProbe {
 public:
  LoadProbe();
  double others(double at_least = 0.1) const;

 private:
  double busy_;
  double own_;
  double start_;
};

}  // namespace hotmesh::parallel
