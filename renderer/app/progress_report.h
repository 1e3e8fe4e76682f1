// Prints a render's progress while it runs, from the pixels it has finished (render_progress):
// on a terminal one line that rewrites itself, otherwise (a farm log, a pipe to kiln batch) one
// line every interval seconds, so a log shows the render is alive and when it will end. App layer.
#pragma once

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "render/tile_renderer.h"

namespace kiln {

// "rendering  42%  ETA 3.1 s" (ETA unknown before the first finished row).
std::string progress_text(uint64_t done, uint64_t total, double eta_seconds);

// The remaining time at the rate of the work done so far: seconds since the first pixel times
// what is left over what is done; negative when nothing is done yet.
double estimate_eta(uint64_t done, uint64_t total, double seconds_rendering);

class progress_report {
 public:
  // Watches progress on its own thread until destroyed; prints nothing when not enabled.
  progress_report(const render_progress& progress, bool enabled, double interval_seconds);
  // Stops watching; on a terminal it ends the line.
  ~progress_report();
  progress_report(const progress_report&) = delete;
  progress_report& operator=(const progress_report&) = delete;

 private:
  void watch();
  const render_progress& progress_;
  const bool terminal_;
  const double interval_;
  bool stop_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace kiln
