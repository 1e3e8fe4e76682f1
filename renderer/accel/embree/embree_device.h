// The process's one Embree device, shared by every embree_accelerator (a render, `kiln compare`,
// `kiln bench`'s repeats, each `kiln.render` of a Python session), with the two callbacks Embree
// offers per device: errors and memory. Part of accel/embree: the only module that includes
// <embree3/rtcore.h>.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <mutex>
#include <string>

namespace kiln {

// The device, created on first use with verbose=0 and never released (it holds no scene of its
// own; each accelerator releases its scenes). Throws kiln::error (render) when Embree cannot create
// it; a later call tries again.
RTCDevice process_embree_device();

// Keeps the first error Embree reports; safe from any thread. Embree reports an API error through
// the device's callback on the thread that made the call, so an accelerator catches the errors of
// its own build with an embree_error_scope on the building thread; an error outside every scope
// (a traversal on a render thread) goes to the process log, which every accelerator consults.
class embree_error_log {
 public:
  void record(const std::string& message);
  // Throws a render error naming what kiln was doing when Embree first failed.
  void throw_if_any(const std::string& during) const;

 private:
  mutable std::mutex mutex_;
  std::string first_;
};

// While alive, Embree errors reported on this thread go to log.
class embree_error_scope {
 public:
  explicit embree_error_scope(embree_error_log& log);
  ~embree_error_scope();
  embree_error_scope(const embree_error_scope&) = delete;
  embree_error_scope& operator=(const embree_error_scope&) = delete;

 private:
  embree_error_log* previous_;
};

// Errors reported outside every scope since the process started, and the first of them.
uint64_t unscoped_embree_errors();
const embree_error_log& unscoped_embree_error_log();

// The device's memory monitor: bytes Embree holds now over the whole process, and the most it
// has held since the last reset_embree_peak(). An accelerator measures its own build as the
// difference; builds running at the same time in one process share these figures.
int64_t embree_bytes_now();
int64_t embree_peak_bytes_since_reset();
void reset_embree_peak();

}  // namespace kiln
