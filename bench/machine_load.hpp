// hotmesh benchmarks: how much of the machine other processes used while a benchmark was
// being timed, so that a table row measured on a busy machine says so. Linux only (reads
// /proc/stat). Used by bench_operator and bench_ramp.
#pragma once

#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <string>

namespace hotmesh::bench {

/// CPU seconds used so far by this process, all threads together, and by its children that
/// have finished (benchmarks that time a command).
inline double own_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  rusage children{};
  getrusage(RUSAGE_CHILDREN, &children);
  const auto seconds = [](const timeval& v) { return static_cast<double>(v.tv_sec) + 1e-6 * static_cast<double>(v.tv_usec); };
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec) + seconds(children.ru_utime) +
         seconds(children.ru_stime);
}

/// CPU seconds the whole machine has been busy since boot (user, nice, system, interrupts and
/// time stolen by the hypervisor), from the first line of /proc/stat; 0 if unreadable.
inline double machine_busy_seconds() {
  std::ifstream stat("/proc/stat");
  std::string cpu;
  long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  if (!(stat >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal)) return 0.0;
  const auto ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  return static_cast<double>(user + nice + system + irq + softirq + steal) / ticks;
}

/// Started at construction; others() is the mean number of cores that other processes kept
/// busy since then (resolution: one clock tick, 10 ms, over the elapsed time).
class LoadProbe {
 public:
  LoadProbe() : busy_(machine_busy_seconds()), own_(own_cpu_seconds()), start_(std::chrono::steady_clock::now()) {}
  double others() const {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double other = (machine_busy_seconds() - busy_) - (own_cpu_seconds() - own_);
    return wall > 0.0 && other > 0.0 ? other / wall : 0.0;
  }

 private:
  double busy_;
  double own_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace hotmesh::bench
