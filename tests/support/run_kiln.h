// Runs the kiln binary from tests and captures its exit code and stderr.
#pragma once

#include <string>
#include <vector>

namespace kiln::testing {

struct command_result {
  int exit_code = -1;
  std::string stderr_text;
  std::string stdout_text;
};

// Runs KILN_BINARY with the given arguments (each quoted for the shell), capturing stderr and stdout. A
// `render` that names neither --spp nor --adaptive-threshold runs at --spp 1 (the pixel centre), not the
// default 16: most tests check pixel-centre closed forms on tiny images; the default itself is tested by
// environment_lighting_cli_test, which names --spp 16 or runs the binary through another helper.
command_result run_kiln(const std::vector<std::string>& arguments);

// Lines of text, without the trailing empty line.
std::vector<std::string> lines(const std::string& text);

// Path to a fresh scratch folder for one test.
std::string scratch_folder(const std::string& name);

// Copies the demo scene (its .gltf, buffer and texture) into folder (created when missing), the
// .gltf as name; returns the .gltf's path.
std::string copy_scene(const std::string& folder, const std::string& name = "cornell_box.gltf");

}  // namespace kiln::testing
