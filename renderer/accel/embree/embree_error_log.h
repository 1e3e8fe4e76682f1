// Records errors that an Embree device reports through its C callback, so they can be turned into a
// kiln::error after the Embree call has returned (an exception must never unwind through Embree).
// Part of accel/embree: the only module that includes <embree3/rtcore.h>.
#pragma once

#include <embree3/rtcore.h>

#include <mutex>
#include <string>

#include "core/error.h"

namespace kiln {

// Keeps the first error message; safe to call from any render thread.
class embree_error_log {
 public:
  // Installs the log as the device's error callback. The log must outlive the device.
  void attach(RTCDevice device) { rtcSetDeviceErrorFunction(device, &embree_error_log::record, this); }

  // Throws a render error naming what kiln was doing when Embree first failed.
  void throw_if_any(const std::string& during) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!first_.empty()) throw error(error_kind::render, "", "", first_ + " (while " + during + ")");
  }

 private:
  static void record(void* user, RTCError code, const char* message) {
    auto* self = static_cast<embree_error_log*>(user);
    std::lock_guard<std::mutex> lock(self->mutex_);
    if (self->first_.empty())
      self->first_ = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
  }

  mutable std::mutex mutex_;
  std::string first_;
};

}  // namespace kiln
