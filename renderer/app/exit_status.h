// The exit status and the one-line message of a command that stopped on an exception: 2 for bad
// input, 124 past --time-limit, 128 + signal when interrupted, 1 otherwise (an I/O or render
// failure, out of memory). main and kiln batch's summary both use it, so they never disagree.
#pragma once

#include <exception>
#include <string>

namespace kiln {

int exit_status_of(const std::exception& e);

// What kiln prints after "kiln: " for e ("out of memory" for std::bad_alloc).
std::string message_of(const std::exception& e);

}  // namespace kiln
