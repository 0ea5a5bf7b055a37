// hotmesh parallel: the processes of a job and what they exchange (MPI through PETSc's mpi.h).
#include "hotmesh/parallel/processes.hpp"

#include <petscsys.h>
#if defined(__GLIBC__)
#include <malloc.h>  // mallopt
#endif

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::parallel {
namespace {

Processes g_job;                      ///< {0, 1} until start_processes() finds several
std::filesystem::path g_session_dir;  ///< Open MPI's session directory of a singleton run
bool g_initialised_here = false;

/// The number of processes an MPI launcher started, from its environment; 0 without one.
int launched_processes() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
    if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
  }
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

void finalize_petsc() {
  if (g_initialised_here) PetscFinalize();
  if (!g_session_dir.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(g_session_dir, ec);
  }
}

/// A process not started by mpirun is an MPI singleton. Open MPI then starts a daemon and
/// probes every network transport, 0.3-0.4 s here; a run that needs no other process needs
/// neither (0.04 s). Concurrent singletons of one user also share, and race to create and
/// remove, one session directory under /tmp: each gets its own. Values the user set win.
void configure_singleton() {
  if (launched_processes() > 0) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  if (!std::getenv("OMPI_MCA_orte_tmpdir_base")) {
    std::error_code ec;
    std::string pattern = (std::filesystem::temp_directory_path(ec) / "hotmesh-mpi-XXXXXX").string();
    if (!ec && mkdtemp(pattern.data())) {
      g_session_dir = pattern;
      setenv("OMPI_MCA_orte_tmpdir_base", pattern.c_str(), 1);
    }
  }
}

void check_mpi(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI failed in ") + what + " (error code " + std::to_string(code) + ")");
}

/// The exchange of a job of several processes, over MPI on PETSc's world communicator.
class MpiExchange final : public RankExchange {
 public:
  int rank() const override { return g_job.rank; }
  int ranks() const override { return g_job.count; }

  void sum(std::span<double> values) const override {
    // In pieces: an MPI count is an int.
    constexpr std::size_t kPiece = 1 << 26;
    for (std::size_t at = 0; at < values.size(); at += kPiece) {
      const auto n = static_cast<int>(std::min(kPiece, values.size() - at));
      check_mpi(MPI_Allreduce(MPI_IN_PLACE, values.data() + at, n, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD), "MPI_Allreduce");
    }
  }

  double max(double value) const override {
    check_mpi(MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD), "MPI_Allreduce");
    return value;
  }

 protected:
  void gather_share_bytes(std::span<std::byte> items, std::size_t item_size) const override {
    const std::size_t count = items.size() / item_size;
    if (items.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      throw std::runtime_error("MPI_Allgatherv: " + std::to_string(items.size()) + " bytes to gather, more than an MPI count holds");
    }
    std::vector<int> counts(static_cast<std::size_t>(g_job.count)), offsets(counts.size());
    for (int r = 0; r < g_job.count; ++r) {
      const Share s = share_of(count, r, g_job.count);
      counts[static_cast<std::size_t>(r)] = static_cast<int>((s.end - s.begin) * item_size);
      offsets[static_cast<std::size_t>(r)] = static_cast<int>(s.begin * item_size);
    }
    check_mpi(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, items.data(), counts.data(), offsets.data(), MPI_BYTE,
                             PETSC_COMM_WORLD),
              "MPI_Allgatherv");
  }
};

/// The exchange of a job of one process.
class OneProcess final : public RankExchange {
 public:
  int rank() const override { return 0; }
  int ranks() const override { return 1; }
  void sum(std::span<double>) const override {}
  double max(double value) const override { return value; }

 protected:
  void gather_share_bytes(std::span<std::byte>, std::size_t) const override {}
};

}  // namespace

const RankExchange& one_process() {
  static const OneProcess one;
  return one;
}

Processes start_processes() {
  const int launched = launched_processes();
  if (launched == 0) return g_job;
  start_petsc();
  int rank = 0, count = 1;
  check_mpi(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), "MPI_Comm_rank");
  check_mpi(MPI_Comm_size(PETSC_COMM_WORLD, &count), "MPI_Comm_size");
  if (launched > 1 && count == 1) {
    throw InputError("an MPI launcher started hotmesh as one of " + std::to_string(launched) +
                     " processes, but the MPI hotmesh was built with (Open MPI) sees one process: start it with "
                     "Open MPI's mpirun (Debian package openmpi-bin), e.g. mpirun -n " + std::to_string(launched) +
                     " hotmesh deform case.yaml");
  }
  g_job = {rank, count};  // each rank's threads: its share of the cores (choose_threads, threads.hpp)
  return g_job;
}

Processes processes() { return g_job; }

const RankExchange& job_exchange() {
  static const MpiExchange mpi;
  if (g_job.count > 1) return mpi;
  return one_process();
}

void abort_processes(int exit_code) {
  std::fflush(stdout);
  std::fflush(stderr);
  if (g_job.count > 1) MPI_Abort(PETSC_COMM_WORLD, exit_code);
  std::exit(exit_code);
}

void restore_malloc_defaults() {
#if defined(__GLIBC__)
  // Blocks from 4 MiB on (node vectors from 170 000 nodes on, the matrix, PETSc's work arrays)
  // mapped apart and unmapped when freed; glibc's own threshold would rise from 128 KiB to at
  // most 32 MiB, but CombBLAS's calls have fixed it. The trim threshold is glibc's default.
  mallopt(M_MMAP_MAX, 65536);
  mallopt(M_MMAP_THRESHOLD, 4 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 10);
#endif
}

void start_petsc() {
  static std::once_flag once;
  std::call_once(once, [] {
    PetscBool initialised = PETSC_FALSE;
    if (PetscInitialized(&initialised) != 0) throw std::runtime_error("PETSc failed in PetscInitialized");
    if (initialised) return;  // an embedding program runs PETSc already
    configure_singleton();
    // No PETSc signal handlers: crashes stay the program's (and the sanitizers') business.
    static char name[] = "hotmesh", no_handler[] = "-no_signal_handler";
    static char* arguments[] = {name, no_handler, nullptr};
    int argc = 2;
    char** argv = arguments;
    if (const PetscErrorCode code = PetscInitialize(&argc, &argv, nullptr, nullptr); code != 0) {
      throw std::runtime_error("MPI and PETSc could not start (PetscInitialize error " + std::to_string(code) +
                               "): is Open MPI installed (Debian packages openmpi-bin, libopenmpi3)?");
    }
    g_initialised_here = true;
    std::atexit(finalize_petsc);
  });
}

Share share_of(std::size_t count, int rank, int ranks) {
  const auto r = static_cast<std::size_t>(rank), n = static_cast<std::size_t>(ranks);
  const std::size_t base = count / n, extra = count % n;
  const std::size_t begin = r * base + std::min(r, extra);
  return {begin, begin + base + (r < extra ? 1 : 0)};
}

}  // namespace hotmesh::parallel
