// What a job will cost, estimated at plan time (kiln batch --plan-only) for a farm to size its
// tasks: peak memory from job/memory_estimates.h over the loaded scene, and render seconds from two
// probes, the frame rendered small and at few samples: a cost fixed per render plus one per sample.
#pragma once

#include <cstdint>

#include "job/render_job.h"
#include "job/render_options.h"

namespace kiln {

struct plan_estimate {
  double load_seconds = 0.0;    // loading the scene and building its acceleration structure
  double render_seconds = 0.0;  // rendering the full frame on one thread, scaled from the probe
  uint64_t peak_memory_bytes = 0;
  int probe_width = 0, probe_height = 0, probe_spp = 0;
};

// Loads options.input, estimates its memory and renders the probes (one pixel, then about
// probe_pixels pixels; at most 4 samples a pixel, one thread). Throws kiln::error as run_job does.
plan_estimate estimate_job(const render_options& options, int probe_pixels = 19200);

// The same for a scene the caller has loaded with prepare_scene(options): its load time is the
// preparation's plus the backend's build.
plan_estimate estimate_job(const prepared_scene& prepared, const render_options& options,
                           int probe_pixels = 19200);

}  // namespace kiln
