// `kiln bench`: renders one view with timing and replays its rays through a bare Embree loop, then
// prints the measurements and writes them as JSON and CSV with the machine, thread count and
// versions recorded. Wires app options to ray_replay/; measures nothing itself.
#pragma once

#include <string>

#include "app/render_command.h"

namespace CLI {
class App;
}

namespace kiln {

struct bench_options {
  render_options view;
  std::string accel = "embree";
  int repeats = 3;
  std::string json;  // optional report files
  std::string csv;
  std::string label;   // a name for this case in the reports (default: the asset's file name)
  std::string frames;  // --frames: time a sequence's per-frame posing and backend update instead
};

void add_bench_options(CLI::App& app, bench_options& options);

// Runs the benchmark. Throws kiln::error for bad input or I/O failures.
void run_bench_command(const bench_options& options);

}  // namespace kiln
