// hotmesh parallel: the threads of a run, from the cores that are free.
#include "hotmesh/parallel/threads.hpp"

#include <sched.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

namespace hotmesh::parallel {
namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double own_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Busy CPU seconds since boot (user, nice, system, interrupts, steal) of the CPUs this
/// process may run on, from their lines of /proc/stat; -1 if unreadable.
double busy_seconds() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  const bool masked = sched_getaffinity(0, sizeof(allowed), &allowed) == 0;
  std::ifstream stat("/proc/stat");
  if (!stat) return -1.0;
  long long ticks = 0;
  for (std::string line; std::getline(stat, line);) {
    if (line.rfind("cpu", 0) != 0 || line.size() < 4 || line[3] < '0' || line[3] > '9') continue;
    std::istringstream fields(line.substr(3));
    std::size_t cpu = 0;
    long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
    if (!(fields >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal)) continue;
    if (masked && (cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed))) continue;
    ticks += user + nice + system + irq + softirq + steal;
  }
  return static_cast<double>(ticks) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// The CPU quota of the process's cgroup (v2: "QUOTA PERIOD" in cpu.max) in cores, or 0 for none.
double cgroup_quota() {
  std::ifstream groups("/proc/self/cgroup");
  std::string line, path;
  while (std::getline(groups, line)) {
    if (line.rfind("0::", 0) == 0) path = line.substr(3);
  }
  if (path.empty()) return 0.0;
  std::ifstream max("/sys/fs/cgroup" + path + "/cpu.max");
  std::string quota;
  double period = 0.0;
  if (!(max >> quota >> period) || quota == "max" || period <= 0.0) return 0.0;
  return std::atof(quota.c_str()) / period;
}

}  // namespace

ThreadChoice choose_threads(const ThreadInputs& in, const std::function<double()>& others_busy) {
  if (in.request.count > 0) return {in.request.count, in.request.from, std::nullopt};
  if (in.cores <= 1) return {1, "the process may use 1 core", std::nullopt};
  if (in.nodes < in.pay_from) {
    return {1, fmt::format("a mesh of {} nodes: threads pay from {}", in.nodes, in.pay_from), std::nullopt};
  }
  if (in.processes > 1) {
    return {std::max(1, in.cores / in.processes),
            fmt::format("{} processes share {} cores", in.processes, in.cores), std::nullopt};
  }
  const double busy = std::max(0.0, others_busy());
  const int threads = std::clamp(static_cast<int>(std::floor(in.cores - busy + kBusyCore)), 1, in.cores);
  const std::string reason = fmt::format("{} cores, other processes keep {:.1f} of them busy", in.cores, busy);
  return {threads, reason, busy};
}

int machine_cores() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  int cores = sched_getaffinity(0, sizeof(allowed), &allowed) == 0 ? CPU_COUNT(&allowed)
                                                                    : static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
  if (const double quota = cgroup_quota(); quota > 0.0) cores = std::min(cores, static_cast<int>(std::floor(quota)));
  return std::max(1, cores);
}

int local_processes(int job_processes) {
  if (job_processes <= 1) return 1;
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  return local ? std::clamp(std::atoi(local), 1, job_processes) : job_processes;
}

LoadProbe::LoadProbe() : busy_(busy_seconds()), own_(own_cpu_seconds()), start_(steady_seconds()) {}

double LoadProbe::others(double at_least) const {
  if (busy_ < 0.0) return 0.0;
  const double waited = steady_seconds() - start_;
  if (waited < at_least) std::this_thread::sleep_for(std::chrono::duration<double>(at_least - waited));
  const double wall = steady_seconds() - start_;
  const double other = (busy_seconds() - busy_) - (own_cpu_seconds() - own_);
  return wall > 0.0 ? std::max(0.0, other / wall) : 0.0;
}

}  // namespace hotmesh::parallel
