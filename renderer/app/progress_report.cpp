#include "app/progress_report.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>

namespace kiln {

namespace {

using clock_type = std::chrono::steady_clock;

// How often the watcher looks: often enough to see when the first pixel starts (the ETA counts
// from there, not from scene setup such as texture pyramids) and to keep a terminal line fresh.
constexpr auto look_every = std::chrono::milliseconds(50);
constexpr double terminal_interval = 0.25;

}  // namespace

std::string progress_text(uint64_t done, uint64_t total, double eta_seconds) {
  char text[96];
  const int percent = total ? int(100.0 * double(done) / double(total)) : 0;
  if (eta_seconds < 0.0)
    std::snprintf(text, sizeof text, "rendering %3d%%  ETA unknown", percent);
  else
    std::snprintf(text, sizeof text, "rendering %3d%%  ETA %.1f s", percent, eta_seconds);
  return text;
}

double estimate_eta(uint64_t done, uint64_t total, double seconds_rendering) {
  if (done == 0 || total == 0) return -1.0;
  return seconds_rendering * double(total - std::min(done, total)) / double(done);
}

progress_report::progress_report(const render_progress& progress, bool enabled, double interval_seconds)
    : progress_(progress),
      terminal_(::isatty(STDERR_FILENO)),
      interval_(terminal_ ? terminal_interval : interval_seconds) {
  if (enabled) thread_ = std::thread([this] { watch(); });
}

progress_report::~progress_report() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void progress_report::watch() {
  const auto start = clock_type::now();
  clock_type::time_point first_pixel{};
  bool started = false;
  double next_line = interval_;
  std::unique_lock<std::mutex> lock(mutex_);
  auto print = [&](bool final_line) {
    const uint64_t total = progress_.pixels_total.load(), done = progress_.pixels_done.load();
    const double rendering = std::chrono::duration<double>(clock_type::now() - first_pixel).count();
    const std::string text =
        progress_text(done, total, started ? estimate_eta(done, total, rendering) : -1.0);
    if (terminal_)
      std::fprintf(stderr, "\rkiln: %s %s", text.c_str(), final_line ? "\n" : "");
    else
      std::fprintf(stderr, "kiln: %s\n", text.c_str());
    std::fflush(stderr);
  };
  while (!wake_.wait_for(lock, look_every, [this] { return stop_; })) {
    if (!started && progress_.pixels_total.load() > 0) {
      started = true;
      first_pixel = clock_type::now();
    }
    const double elapsed = std::chrono::duration<double>(clock_type::now() - start).count();
    if (elapsed < next_line) continue;
    next_line = elapsed + interval_;
    // Every pixel done: the job is resolving the film and writing its files, and its own line
    // follows; a log gets no "rendering 100%  ETA 0.0 s" lines meanwhile.
    const uint64_t total = progress_.pixels_total.load();
    if (!terminal_ && total > 0 && progress_.pixels_done.load() >= total) continue;
    print(false);
  }
  // On a terminal the last state (100% when the render completed) ends the line, even when the
  // render was over before the first refresh.
  if (terminal_ && progress_.pixels_total.load() > 0) {
    if (!started) first_pixel = clock_type::now();
    started = true;
    print(true);
  }
}

}  // namespace kiln
