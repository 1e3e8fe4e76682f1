// What a job will cost, estimated at plan time (kiln batch --plan-only) for a farm to size its
// tasks: peak memory from job/memory_estimates.h over the loaded scene, and render seconds from a
// probe, the frame rendered small and at few samples, scaled by pixels × samples.
#pragma once

#include <cstdint>

#include "job/render_options.h"

namespace kiln {

struct plan_estimate {
  double load_seconds = 0.0;    // loading the scene and building its acceleration structure
  double render_seconds = 0.0;  // rendering the full frame on one thread, scaled from the probe
  uint64_t peak_memory_bytes = 0;
  int probe_width = 0, probe_height = 0, probe_spp = 0;
};

// Loads options.input, estimates its memory and renders the probe (about probe_pixels pixels, at
// most 4 samples a pixel, one thread). Throws kiln::error as run_job does for bad input.
plan_estimate estimate_job(const render_options& options, int probe_pixels = 4800);

}  // namespace kiln
