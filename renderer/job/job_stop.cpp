#include "job/job_stop.h"

#include <chrono>

namespace kiln {

job_stop::job_stop(const std::atomic<bool>* outer, double seconds) : outer_(outer) {
  if (seconds > 0.0) watcher_ = std::thread([this, seconds] { watch(seconds); });
}

job_stop::~job_stop() {
  if (!watcher_.joinable()) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    finished_ = true;
  }
  wake_.notify_one();
  watcher_.join();
}

void job_stop::watch(double seconds) {
  using clock = std::chrono::steady_clock;
  const clock::time_point deadline =
      clock::now() + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(seconds));
  std::unique_lock<std::mutex> lock(mutex_);
  while (!finished_) {
    if (outer_ && outer_->load()) {
      stop_ = true;
      return;
    }
    if (clock::now() >= deadline) {
      timed_out_ = true;
      stop_ = true;
      return;
    }
    // The outer flag is raised from a signal handler, which cannot notify: look every 10 ms.
    wake_.wait_until(lock, std::min(deadline, clock::now() + std::chrono::milliseconds(10)));
  }
}

}  // namespace kiln
