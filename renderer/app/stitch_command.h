// `kiln stitch OUT.exr IN.exr...`: joins region EXRs (the bands of `kiln render --tile i/N`, or
// any crops that tile the frame) into one full-frame EXR. Wires the command line to io/exr.
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace kiln {

struct stitch_options {
  std::string output;
  std::vector<std::string> inputs;
  std::string max_memory;  // --max-memory SIZE; empty: the default budget
};

void add_stitch_options(CLI::App& app, stitch_options& options);

// Throws kiln::error (input) for inputs that do not tile one frame, (io) when OUT cannot be written.
void run_stitch(const stitch_options& options);

}  // namespace kiln
