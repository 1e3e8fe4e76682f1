#include "accel/embree/embree_device.h"

#include <atomic>

#include "core/error.h"

namespace kiln {

namespace {

thread_local embree_error_log* current_log = nullptr;
embree_error_log unscoped_log;
std::atomic<uint64_t> unscoped_count{0};

std::atomic<int64_t> bytes_now{0};
std::atomic<int64_t> peak_bytes{0};

void report_error(void* /*user*/, RTCError code, const char* message) {
  const std::string text = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
  if (current_log) return current_log->record(text);
  unscoped_log.record(text);
  ++unscoped_count;
}

bool count_memory(void* /*user*/, ssize_t bytes, bool /*post*/) {
  const int64_t now = bytes_now += int64_t(bytes);
  int64_t peak = peak_bytes.load();
  while (now > peak && !peak_bytes.compare_exchange_weak(peak, now)) {
  }
  return true;  // never refuse an allocation
}

RTCDevice create_device() {
  RTCDevice device = rtcNewDevice("verbose=0");
  if (!device)
    throw error(
        error_kind::render, "", "",
        "cannot create Embree device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(device, &report_error, nullptr);
  rtcSetDeviceMemoryMonitorFunction(device, &count_memory, nullptr);
  return device;
}

}  // namespace

RTCDevice process_embree_device() {
  static std::mutex mutex;
  static RTCDevice device = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (!device) device = create_device();
  return device;
}

void embree_error_log::record(const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (first_.empty()) first_ = message;
}

void embree_error_log::throw_if_any(const std::string& during) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!first_.empty()) throw error(error_kind::render, "", "", first_ + " (while " + during + ")");
}

embree_error_scope::embree_error_scope(embree_error_log& log) : previous_(current_log) { current_log = &log; }
embree_error_scope::~embree_error_scope() { current_log = previous_; }

uint64_t unscoped_embree_errors() { return unscoped_count.load(); }
const embree_error_log& unscoped_embree_error_log() { return unscoped_log; }

int64_t embree_bytes_now() { return bytes_now.load(); }
int64_t embree_peak_bytes_since_reset() { return peak_bytes.load(); }
void reset_embree_peak() { peak_bytes.store(bytes_now.load()); }

}  // namespace kiln
