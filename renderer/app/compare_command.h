// `kiln compare`: renders one view through a decorator that asks two backends every question the
// render asks (camera rays and all their shadow and reflection rays), renders the image again
// with the second backend, and reports per ray kind and per pixel where they differ.
// Wires app options to accel/compare; no traversal or shading logic of its own.
#pragma once

#include <string>

#include "app/render_command.h"

namespace CLI {
class App;
}

namespace kiln {

struct compare_options {
  render_options view;
  std::string accel = "grid";      // the backend under test (answers the render's queries)
  std::string against = "embree";  // the reference it is checked against
  std::string mask;                // mismatch-mask EXR, optional
  std::string json;                // JSON report, optional
  double pixel_tolerance = 1e-3;   // a pixel differs when a channel differs by more (relative above 1)
  uint64_t max_mismatches = 0;     // ray mismatches beyond error bounds allowed before exit code 3
};

// Exit code when the backends disagree beyond tolerance.
constexpr int exit_backends_disagree = 3;

void add_compare_options(CLI::App& app, compare_options& options);

// Runs the comparison; returns 0 when the backends agree, exit_backends_disagree otherwise.
// Throws kiln::error for bad input or I/O failures.
int run_compare(const compare_options& options);

}  // namespace kiln
