// Mailboxing (Amanatides and Woo 1987; Kirk and Arvo 1988): an item that spans several cells is
// tested once per ray. Instead of a ray id stored in every item, which threads would race on, each
// query owns a small direct-mapped cache of the ids it has tested. A collision only evicts an
// entry, so the worst case is a repeated test, never a missed one. Lives on the stack: thread-safe.
#pragma once

#include <array>
#include <cstdint>

namespace kiln {

class mailbox {
 public:
  mailbox() { slots_.fill(UINT32_MAX); }

  // True the first time id is seen by this query (test it); false when it was already tested.
  bool first_visit(uint32_t id) {
    uint32_t& slot = slots_[id & (size - 1)];
    if (slot == id) return false;
    slot = id;
    return true;
  }

 private:
  static constexpr uint32_t size = 64;  // a power of two; covers the items of the last few cells
  std::array<uint32_t, size> slots_;
};

}  // namespace kiln
