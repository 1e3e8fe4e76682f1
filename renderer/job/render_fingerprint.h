// What decides a render's pixels, in two forms: the canonical `kiln render` arguments for a set of
// render_options (so a job can be re-run by hand or on a farm), and two cheap hashes that an EXR
// records so a batch can tell whether an existing output is still up to date.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "job/render_options.h"

namespace kiln {

struct render_fingerprint {
  std::string input_hash;     // the asset's bytes, every buffer and image file it names, the environment map
  std::string settings_hash;  // the canonical arguments, region included
  // The same without --crop/--tile: equal for every region of one frame, and the settings hash of
  // the frame they stitch into.
  std::string frame_settings_hash;
  std::string scene_hash;  // the asset file's own bytes (kiln/scene_hash)
};

// Hashes the inputs and settings of options (reads every input file once). The files the asset
// names are checked by the loader's own URI rule before any is read, so a URI the loader refuses
// (absolute, outside the folder, a FIFO or a device) is refused here first, in the loader's words.
render_fingerprint make_fingerprint(const render_options& options, const std::atomic<bool>* cancel = nullptr);

// The fingerprint of options whose inputs `inputs` hashed already (its input and scene hashes):
// the settings hashes only, which read no file. The frames of a sequence share their inputs.
render_fingerprint fingerprint_with_settings(const render_fingerprint& inputs, const render_options& options);

}  // namespace kiln
