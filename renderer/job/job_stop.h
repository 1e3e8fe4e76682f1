// When a job stops early: the caller's cancel flag (a signal, Ctrl-C) or the job's own time limit
// (--time-limit). One flag goes to the loader, the hashing and the renderer; a watcher thread
// raises it when either cause arrives, so a hostile file that stalls loading or spawns an
// exponential ray tree stops within the renderer's polling interval either way.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace kiln {

class job_stop {
 public:
  // seconds <= 0: no time limit (and, without an outer flag either, no thread).
  job_stop(const std::atomic<bool>* outer, double seconds);
  ~job_stop();
  job_stop(const job_stop&) = delete;
  job_stop& operator=(const job_stop&) = delete;

  // The flag to poll: raised once the outer flag is or the time limit has passed.
  const std::atomic<bool>* flag() const { return watcher_.joinable() ? &stop_ : outer_; }
  // Whether the time limit (not the outer flag) raised it.
  bool timed_out() const { return timed_out_.load(); }

 private:
  void watch(std::chrono::steady_clock::time_point deadline);
  const std::atomic<bool>* outer_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> timed_out_{false};
  bool finished_ = false;
  bool started_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread watcher_;
};

}  // namespace kiln
