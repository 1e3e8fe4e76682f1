// `kiln bench` measurements: load, build, render and peak memory of one scene and view, plus the
// very rays that render traced replayed through a bare Embree loop (rtcIntersect1/rtcOccluded1, no
// shading) and through kiln's accelerator interface, all in one run, so kiln's overhead is a
// measured ratio. Depends on render, shade and the accelerators; knows nothing of files or the CLI.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "accel/embree/embree_options.h"
#include "render/tile_renderer.h"
#include "render/view_camera.h"
#include "scene/scene.h"

namespace kiln {

// One ray kind and query type (closest hit or occlusion) of the recorded render.
struct kind_measurement {
  std::string kind;   // camera, shadow, reflection, refraction, other
  std::string query;  // intersect or occluded
  size_t rays = 0;
  double bare_seconds = 0.0;  // bare Embree loop over these rays
  double kiln_seconds = 0.0;  // the same rays through kiln's accelerator (hit record included)
  size_t bare_hits = 0;
  size_t kiln_hits = 0;
  // Camera rays only: the same rays as streams of 1024 (rtcIntersect1M, coherent flag) bare and
  // through accelerator::intersect_coherent; 0 when not measured, and never for scenes with
  // quadrics, whose user geometry answers single rays only.
  double bare_stream_seconds = 0.0;
  double kiln_stream_seconds = 0.0;
  // Occlusion queries only: the same chunks of rays through accelerator::occluded_batch (Embree's
  // ray packets), timed alternating with the single-ray loops; 0 when not measured.
  double kiln_batch_seconds = 0.0;
  size_t kiln_batch_hits = 0;
  // The render asked these rays closest-hit queries (the shadow walk past see-through surfaces);
  // here they are timed as occlusion queries, and left out of the render's totals.
  bool replayed_as_occlusion = false;
};

struct bench_measurement {
  double build_seconds = 0.0;
  double render_seconds = 0.0;  // best of the repeats
  // CPU time (user + system, all threads) of the render with the least of it: unlike wall time,
  // it does not grow while other processes hold the cores, so A/B runs on a loaded machine compare.
  double render_cpu_seconds = 0.0;
  double first_pixel_seconds = 0.0;  // load + build: how long until tracing starts
  size_t peak_rss_after_build = 0;   // bytes (getrusage maximum resident set size)
  size_t peak_rss_after_render = 0;
  size_t rss_after_build = 0;    // current, not peak: the scene and its acceleration structure
  size_t rss_build_delta = 0;    // current RSS after the build minus before it
  size_t embree_bytes = 0;       // Embree's memory monitor after the build (BVHs, vertex copies)
  size_t embree_peak_bytes = 0;  // and its peak during the build
  size_t unique_triangles = 0;   // stored once per mesh
  size_t placed_triangles = 0;   // summed over instances
  size_t instances = 0;
  ray_counts rays;  // traced by the timed render
  int threads = 0;
  std::vector<kind_measurement> kinds;
};

struct bench_settings {
  std::string accel = "embree";  // backend of the timed render (the bare loop is always Embree)
  int repeats = 3;               // timed renders and replays; the best is reported
  embree_options embree;         // BVH build settings of the timed backend and the bare loop
};

// Builds the backend, renders `repeats` times, records one more render's rays and replays them.
// Throws kiln::error on render failure.
bench_measurement run_bench(const scene& world, const view_camera& cam, const render_settings& render,
                            const bench_settings& settings);

// Peak resident set size of this process so far, in bytes.
size_t peak_resident_bytes();

// Resident set size of this process now, in bytes (/proc/self/statm). Unlike the peak, it shows
// what a small scene adds on top of the libraries' own baseline.
size_t current_resident_bytes();

}  // namespace kiln
