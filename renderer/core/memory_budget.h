// One job's memory budget: a running total of what its large allocations are estimated to take
// (JSON and its parse, buffers, geometry, decoded textures, mip pyramids, the film, the BVH),
// charged before each is made, so a file that would exhaust memory is refused with one line
// instead of being killed or crashing. Depends on core's error type and the standard library only.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace kiln {

// "7.0 GiB", "512 MiB", "12 KiB", "100 bytes": binary units, one decimal below 10.
inline std::string memory_text(uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
  double value = double(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 5) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  if (unit == 0)
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(text, sizeof text, value < 10.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

class memory_budget {
 public:
  explicit memory_budget(uint64_t limit) : limit_(limit) {}
  memory_budget(const memory_budget&) = delete;
  memory_budget& operator=(const memory_budget&) = delete;

  uint64_t limit() const { return limit_; }
  uint64_t used() const { return used_.load(); }

  // Adds bytes to the running total, or throws kiln::error (input, exit 2 like the other resource
  // limits) naming file, what needs the memory, the estimate and the budget, and leaves the total
  // as it was. `what` reads as a plural subject: "textures and mip pyramids".
  void charge(uint64_t bytes, const std::string& file, const std::string& what) {
    uint64_t before = used_.load();
    uint64_t after = 0;
    do {
      after = before + bytes;
      if (after < before || after > limit_) throw refusal(bytes, before, file, what);
    } while (!used_.compare_exchange_weak(before, after));
  }

  // Takes back bytes charged earlier, once what they estimated is freed.
  void release(uint64_t bytes) { used_.fetch_sub(bytes); }

 private:
  error refusal(uint64_t bytes, uint64_t before, const std::string& file, const std::string& what) const {
    std::string need = memory_text(bytes);
    if (before > 0) need += " more, " + memory_text(before + bytes) + " in all";
    return input_error(file, "",
                       what + " need about " + need + ", over the memory budget of " + memory_text(limit_) +
                           " (raise it with --max-memory)");
  }

  uint64_t limit_;
  std::atomic<uint64_t> used_{0};
};

// Charges that end with a scope: memory a step needs only while it runs (a JSON parse, a decode
// buffer). Each add charges the budget; the destructor releases the sum. A null budget charges
// nothing.
class memory_charge {
 public:
  explicit memory_charge(memory_budget* budget) : budget_(budget) {}
  memory_charge(const memory_charge&) = delete;
  memory_charge& operator=(const memory_charge&) = delete;
  ~memory_charge() {
    if (budget_) budget_->release(held_);
  }

  void add(uint64_t bytes, const std::string& file, const std::string& what) {
    if (!budget_) return;
    budget_->charge(bytes, file, what);
    held_ += bytes;
  }

 private:
  memory_budget* budget_;
  uint64_t held_ = 0;
};

// Charges budget when there is one.
inline void charge_memory(memory_budget* budget, uint64_t bytes, const std::string& file,
                          const std::string& what) {
  if (budget) budget->charge(bytes, file, what);
}

}  // namespace kiln
