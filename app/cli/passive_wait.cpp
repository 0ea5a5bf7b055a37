// hotmesh app: `hotmesh deform` waits passively unless the user says otherwise (passive_wait.hpp).
#include "cli/passive_wait.hpp"

#include <sched.h>
#include <sys/auxv.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace hotmesh::app {
namespace {

constexpr std::string_view kPolicy = "OMP_WAIT_POLICY=";
constexpr std::string_view kSpinCount = "GOMP_SPINCOUNT=";
constexpr std::string_view kMarker = "HOTMESH_DEFAULT_WAIT_POLICY=";
constexpr std::string_view kPreload = "LD_PRELOAD=";
constexpr std::string_view kOneThread = "OMP_NUM_THREADS=1";

/// Why the program did not restart, when it would have; for wait_policy(). Static storage,
/// constant-initialized: set before any constructor runs.
const char* g_not_restarted = nullptr;

bool starts_with(const char* text, std::string_view prefix) {
  return std::strncmp(text, prefix.data(), prefix.size()) == 0;
}

/// Why the restart would cost its time for nothing, or null: `--threads 1` among the arguments
/// after the command (one thread never waits), or the process may use one core, as mpirun
/// binds each of 2 ranks (more threads than cores: libgomp then spins 100 turns at most).
const char* one_thread(int argc, char** argv, int command) {
  for (int i = command + 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--threads=1") == 0 || (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc &&
                                                      std::strcmp(argv[i + 1], "1") == 0)) {
      return "one thread (--threads 1): no thread waits";
    }
  }
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0 && CPU_COUNT(&allowed) == 1) {
    return "the process may use 1 core, where libgomp spins at most 100 turns";
  }
  return nullptr;
}

}  // namespace

void restart_waiting_passively(int argc, char** argv, char** envp) {
  static char policy[] = "OMP_WAIT_POLICY=passive";
  static char marker[] = "HOTMESH_DEFAULT_WAIT_POLICY=passive";
  static std::array<char*, 4096> environment;
  int command = 1;
  while (command < argc && argv[command][0] == '-') ++command;
  if (command >= argc || std::strcmp(argv[command], "deform") != 0 || envp == nullptr) return;
  std::size_t n = 0;
  for (; envp[n] != nullptr; ++n) {
    if (starts_with(envp[n], kPolicy) || starts_with(envp[n], kSpinCount) || starts_with(envp[n], kMarker)) return;
    if (std::strcmp(envp[n], kOneThread.data()) == 0) {
      g_not_restarted = "one thread (OMP_NUM_THREADS=1): no thread waits";
      return;
    }
    if (starts_with(envp[n], kPreload) && std::strstr(envp[n], "vgpreload") != nullptr) {
      g_not_restarted = "run under valgrind";
      return;
    }
    if (n + 3 > environment.size()) {
      g_not_restarted = "its environment has too many variables";
      return;
    }
    environment[n] = envp[n];
  }
  if (const char* why = one_thread(argc, argv, command)) {
    g_not_restarted = why;
    return;
  }
  // Started by the kernel through the program's interpreter, the loader's base is known; run
  // as `ld.so hotmesh`, the loader is the program the kernel started, and /proc/self/exe.
  if (getauxval(AT_BASE) == 0) {
    g_not_restarted = "started by the dynamic loader";
    return;
  }
  environment[n] = policy;
  environment[n + 1] = marker;
  environment[n + 2] = nullptr;
  execve("/proc/self/exe", argv, environment.data());
  g_not_restarted = "it could not start itself again (execve of /proc/self/exe failed)";
}

std::string wait_policy() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const char* spin = std::getenv("GOMP_SPINCOUNT");
  const char* marker = std::getenv("HOTMESH_DEFAULT_WAIT_POLICY");
  if (marker != nullptr && policy != nullptr && std::string_view(policy) == "passive" && spin == nullptr) {
    return "passive (hotmesh's default)";
  }
  if (policy == nullptr && spin == nullptr) {
    return fmt::format("libgomp's default, a waiting thread spins a while{}",
                       g_not_restarted ? fmt::format(" (hotmesh did not make it passive: {})", g_not_restarted) : "");
  }
  std::string set = policy ? fmt::format("OMP_WAIT_POLICY={}", policy) : "";
  if (spin) set += fmt::format("{}GOMP_SPINCOUNT={}", policy ? ", " : "", spin);
  return set + " (set by the user)";
}

}  // namespace hotmesh::app
