#include "app/exit_status.h"

#include <csignal>
#include <new>

#include "app/interrupt.h"
#include "core/error.h"

namespace kiln {

int exit_status_of(const std::exception& e) {
  const auto* known = dynamic_cast<const error*>(&e);
  if (!known) return 1;
  switch (known->kind()) {
    case error_kind::input:
      return 2;
    case error_kind::time_limit:
      return 124;  // as timeout(1)
    case error_kind::interrupted:
      return 128 + (interrupt_signal() ? interrupt_signal() : SIGINT);
    default:
      return 1;
  }
}

std::string message_of(const std::exception& e) {
  if (dynamic_cast<const std::bad_alloc*>(&e)) return "out of memory";
  return e.what();
}

}  // namespace kiln
