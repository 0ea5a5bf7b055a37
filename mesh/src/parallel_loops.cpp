// hotmesh mesh: starting the OpenMP threads while a failure can still be reported.
#include "hotmesh/mesh/parallel_loops.hpp"

#include <omp.h>
#include <pthread.h>
#include <semaphore.h>

#include <new>
#include <vector>

namespace hotmesh::mesh {
namespace {

void* wait_for(void* release) {
  sem_wait(static_cast<sem_t*>(release));
  return nullptr;
}

}  // namespace

void start_threads(int count) {
  if (count > 0) omp_set_num_threads(count);
  // First as many threads as OpenMP adds to this one, and one more for what OpenMP allocates
  // beside them, all alive at once, with the default stack size as OpenMP's (unless
  // OMP_STACKSIZE sets another). Plain POSIX threads that allocate nothing (a std::thread
  // frees its start state in the new thread, which gives that thread a malloc arena of 64 MB
  // of address space), so that they take what OpenMP's take.
  const int threads = omp_get_max_threads();
  std::vector<pthread_t> probes;
  probes.reserve(static_cast<std::size_t>(threads));
  sem_t release;
  sem_init(&release, 0, 0);
  int error = 0;
  for (int i = 0; i < threads && error == 0; ++i) {
    pthread_t thread;
    error = pthread_create(&thread, nullptr, wait_for, &release);
    if (error == 0) probes.push_back(thread);
  }
  for (std::size_t i = 0; i < probes.size(); ++i) sem_post(&release);
  for (const pthread_t thread : probes) pthread_join(thread, nullptr);
  sem_destroy(&release);
  if (error != 0) throw std::bad_alloc();
  // Then OpenMP's own, at once, in the memory the probes gave back; OpenMP keeps them.
#pragma omp parallel
  {
  }
}

}  // namespace hotmesh::mesh
