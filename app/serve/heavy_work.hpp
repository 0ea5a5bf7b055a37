// hotmesh serve: the bound on heavy work. Requests that build something (CAD models, curves,
// surfaces, projections, STEP/IGES downloads: every POST and download) take one of
// `limit` heavy slots while they compute; one that finds them all taken waits in a queue of
// at most `queue` requests (first come, first served), and beyond that is answered 503 with
// Retry-After at once. Waiting holds no worker, so light requests (health, lists, what is
// kept, deletes, the page) are served while heavy ones wait. When a heavy request ends, the
// memory it freed is handed back to the system (glibc keeps freed memory otherwise, in the
// arena of each connection's thread).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "service/json_fields.hpp"

namespace hotmesh::app::serve {

class HeavyWork {
 public:
  static constexpr int kRetryAfterSeconds = 5;

  HeavyWork(std::size_t limit, std::size_t queue);

  /// A heavy slot held for as long as the object lives.
  class Slot {
   public:
    explicit Slot(HeavyWork& work);
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot();

   private:
    HeavyWork& work_;
  };

  /// {"limit", "queue", "running", "waiting"}.
  Json status() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable freed_;
  std::size_t limit_;
  std::size_t queue_;
  std::size_t running_ = 0;
  std::size_t waiting_ = 0;
  std::uint64_t next_ticket_ = 0;  ///< the queue's order
  std::uint64_t serving_ = 0;      ///< tickets below this one have been let in
};

}  // namespace hotmesh::app::serve
