// hotmesh serve: heavy slots, their queue, and 503 beyond it (see heavy_work.hpp).
#include "serve/heavy_work.hpp"

#include <malloc.h>

#include <algorithm>

#include <fmt/format.h>

#include "service/api_error.hpp"

namespace hotmesh::app::serve {

HeavyWork::HeavyWork(std::size_t limit, std::size_t queue) : limit_(std::max<std::size_t>(limit, 1)), queue_(queue) {}

HeavyWork::Slot::Slot(HeavyWork& work) : work_(work) {
  std::unique_lock lock(work.mutex_);
  if (work.running_ < work.limit_ && work.waiting_ == 0) {
    ++work.running_;
    return;
  }
  if (work.waiting_ >= work.queue_) {
    throw ApiError::busy(fmt::format("the service is busy: {} heavy request(s) are being computed (--heavy-requests) "
                                     "and {} wait (--heavy-queue); try again in a few seconds",
                                     work.running_, work.waiting_),
                         kRetryAfterSeconds);
  }
  const std::uint64_t ticket = work.next_ticket_++;
  ++work.waiting_;
  work.freed_.wait(lock, [&] { return work.running_ < work.limit_ && ticket == work.serving_; });
  ++work.serving_;
  --work.waiting_;
  ++work.running_;
  work.freed_.notify_all();  // the next in line may fit too
}

HeavyWork::Slot::~Slot() {
  {
    std::lock_guard lock(work_.mutex_);
    --work_.running_;
  }
  work_.freed_.notify_all();
  ::malloc_trim(0);  // what the heavy work freed, back to the system
}

Json HeavyWork::status() const {
  std::lock_guard lock(mutex_);
  return {{"limit", limit_}, {"queue", queue_}, {"running", running_}, {"waiting", waiting_}};
}

}  // namespace hotmesh::app::serve
