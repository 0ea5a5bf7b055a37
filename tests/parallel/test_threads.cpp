// Tests of the choice of a run's threads (hotmesh/parallel/threads.hpp): the user's count as
// given, one thread on one core or for a small mesh, a share of the cores for each process of
// a job, and the cores other processes leave free; the load looked at only when it decides.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>

#include "hotmesh/parallel/threads.hpp"

namespace hotmesh::parallel {
namespace {

using ::testing::HasSubstr;

/// A process on `cores` cores, a mesh of `nodes` nodes, threads paying from 20 000.
ThreadInputs machine(int cores, std::size_t nodes, int processes = 1) {
  ThreadInputs in;
  in.cores = cores;
  in.processes = processes;
  in.nodes = nodes;
  in.pay_from = 20000;
  return in;
}

/// A load that must not be looked at.
double unused_load() {
  ADD_FAILURE() << "the load was looked at";
  return 0.0;
}

TEST(ThreadChoice, TheUsersCountIsObeyedAsGiven) {
  ThreadInputs in = machine(2, 100);  // small, and the machine busy: still as asked
  in.request = {4, "--threads 4"};
  const ThreadChoice choice = choose_threads(in, unused_load);
  EXPECT_EQ(choice.threads, 4);
  EXPECT_EQ(choice.reason, "--threads 4");
  EXPECT_FALSE(choice.others_busy);
}

TEST(ThreadChoice, OneCoreGivesOneThread) {
  const ThreadChoice choice = choose_threads(machine(1, 1'000'000), unused_load);
  EXPECT_EQ(choice.threads, 1);
  EXPECT_EQ(choice.reason, "the process may use 1 core");
}

TEST(ThreadChoice, ASmallMeshRunsOnOneThreadAndSaysWhereThreadsPay) {
  const ThreadChoice choice = choose_threads(machine(2, 5600), unused_load);
  EXPECT_EQ(choice.threads, 1);
  EXPECT_EQ(choice.reason, "a mesh of 5600 nodes: threads pay from 20000");
  EXPECT_EQ(choose_threads(machine(2, 20000), [] { return 0.0; }).threads, 2);  // from the threshold on
}

TEST(ThreadChoice, ProcessesOfAJobShareTheCores) {
  EXPECT_EQ(choose_threads(machine(2, 1'000'000, 2), unused_load).threads, 1);
  const ThreadChoice choice = choose_threads(machine(8, 1'000'000, 2), unused_load);
  EXPECT_EQ(choice.threads, 4);
  EXPECT_EQ(choice.reason, "2 processes share 8 cores");
  EXPECT_EQ(choose_threads(machine(2, 1'000'000, 3), unused_load).threads, 1);  // never none
}

TEST(ThreadChoice, OnlyTheCoresOtherProcessesLeaveFreeGetAThread) {
  struct Case {
    int cores;
    double busy;
    int threads;
  };
  for (const Case c : {Case{2, 0.0, 2}, Case{2, 0.2, 2}, Case{2, 0.3, 1}, Case{2, 1.0, 1}, Case{2, 1.9, 1},
                       Case{2, 5.5, 1}, Case{8, 1.0, 7}, Case{8, 2.8, 5}, Case{4, 0.0, 4}}) {
    const ThreadChoice choice = choose_threads(machine(c.cores, 1'000'000), [&] { return c.busy; });
    EXPECT_EQ(choice.threads, c.threads) << c.cores << " cores, " << c.busy << " busy";
    ASSERT_TRUE(choice.others_busy);
    EXPECT_EQ(*choice.others_busy, c.busy);
  }
  EXPECT_EQ(choose_threads(machine(2, 1'000'000), [] { return 0.97; }).reason,
            "2 cores, other processes keep 1.0 of them busy");
}

TEST(ThreadChoice, TheMachineHasAtLeastOneCoreAndTheLoadIsNeverNegative) {
  EXPECT_GE(machine_cores(), 1);
  const LoadProbe probe;
  const double others = probe.others(0.02);
  EXPECT_GE(others, 0.0);
  EXPECT_LE(others, 1024.0);
  EXPECT_EQ(local_processes(1), 1);
  setenv("OMPI_COMM_WORLD_LOCAL_SIZE", "2", 1);
  EXPECT_EQ(local_processes(4), 2);  // 4 ranks, 2 of them on this machine
  unsetenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  EXPECT_EQ(local_processes(4), 4);
}

}  // namespace
}  // namespace hotmesh::parallel
