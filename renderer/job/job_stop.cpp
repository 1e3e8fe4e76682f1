#include "job/job_stop.h"

#include <chrono>

namespace kiln {

job_stop::job_stop(const std::atomic<bool>* outer, double seconds) : outer_(outer) {
  if (seconds <= 0.0) return;
  using clock = std::chrono::steady_clock;
  const clock::time_point deadline =
      clock::now() + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(seconds));
  watcher_ = std::thread([this, deadline] { watch(deadline); });
  // Wait until the watcher has looked at the clock once: a limit shorter than a thread's start
  // (or a busy machine that starts it late) still stops the job before any of its work is done.
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait(lock, [this] { return started_; });
}

job_stop::~job_stop() {
  if (!watcher_.joinable()) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    finished_ = true;
  }
  wake_.notify_all();
  watcher_.join();
}

void job_stop::watch(std::chrono::steady_clock::time_point deadline) {
  using clock = std::chrono::steady_clock;
  std::unique_lock<std::mutex> lock(mutex_);
  const auto announce_start = [this] {
    if (started_) return;
    started_ = true;
    wake_.notify_all();
  };
  while (!finished_) {
    if (outer_ && outer_->load()) {
      stop_ = true;
      announce_start();
      return;
    }
    if (clock::now() >= deadline) {
      timed_out_ = true;
      stop_ = true;
      announce_start();
      return;
    }
    announce_start();
    // The outer flag is raised from a signal handler, which cannot notify: look every 10 ms.
    wake_.wait_until(lock, std::min(deadline, clock::now() + std::chrono::milliseconds(10)));
  }
}

}  // namespace kiln
