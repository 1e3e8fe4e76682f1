// The tile scheduler: splits the image into tiles, renders them on a TBB task arena with the
// requested thread count, and fills the film. Each pixel is computed by exactly one task in a
// fixed sample order, and filtered samples that reach into other tiles are summed in source
// pixel order (see splat_film.h), so the result does not depend on scheduling or tile size.
// Depends on shade (through the accelerator interface) and render; never on a backend.
#pragma once

#include <atomic>
#include <functional>
#include <memory>

#include "core/memory_budget.h"
#include "render/adaptive_sampling.h"
#include "render/deep_pixel.h"
#include "render/film.h"
#include "render/id_coverage.h"
#include "render/motion_vectors.h"
#include "render/reconstruction_filter.h"
#include "render/view_camera.h"
#include "shade/environment_light.h"
#include "shade/texture_filter.h"
#include "shade/whitted.h"

namespace kiln {

// Work done so far, for progress reports and ETAs: pixels finished, counted row by row inside the
// tiles as they go, so the fraction is the work done (not the tiles done: with T threads, T tiles
// are nearly done when the first one ends). render_image sets the total before the first pixel.
struct render_progress {
  std::atomic<uint64_t> pixels_done{0};
  std::atomic<uint64_t> pixels_total{0};
};

struct render_settings {
  int samples_per_pixel = 1;
  bool random_samples = false;   // independent uniform samples instead of jittered strata
  int threads = 0;               // 0: all cores
  int tile_size = 32;            // pixels per tile side
  reconstruction_filter filter;  // how stratified samples become pixels (box 0.5: the pixel's mean)
  adaptive_options adaptive;     // threshold > 0: Whitted's adaptive corner sampling instead of spp
  bool show_background = false;  // camera rays that miss see the environment (alpha 1) instead of alpha 0
  shading_options shading;
  // Each pixel's camera rays traced together (accelerator::intersect_coherent) before shading; the
  // image is the same either way but where two surfaces coincide (render/camera_rays.h). Adaptive
  // sampling traces its samples one at a time.
  bool packets = true;
  // Shade each sample from its camera ray to its last bounce before the next (the reference the
  // wave is held to) instead of making a run's camera hits ready together first.
  bool reference_shading = false;
  aov_set aovs;  // which outputs the film keeps beside the colour
  // Motion blur: each camera sample gets its time in the shutter (render/sample_pattern.h), which
  // every ray of its path keeps. Off: every ray is at time 0 (the frame, or the shutter's opening).
  bool motion_blur = false;
  // With motion blur, a camera that moves during the shutter: its views at the shutter's evenly
  // spaced steps (render/view_camera.h: view_at_time); null: the camera holds still.
  const std::vector<view_camera>* camera_steps = nullptr;
  // The scene at the neighbouring frames (with the motion AOV; null: no motion, all 0).
  const scene_motion* motion = nullptr;
  // The Cryptomatte id of each glTF node and material (with the crypto_* AOVs).
  matte_ids mattes;
  // Renders and keeps only this region of the frame (empty: the whole frame). Its pixels are
  // bit-identical to the same pixels of a full render.
  pixel_rect crop;
  // When set and it becomes true (e.g. from a signal handler), rendering stops at the next pixel
  // (or sample batch) and render_image throws kiln::error of kind interrupted. A camera sample's
  // ray tree also looks at it every ray_budget::poll_interval rays and then spawns no more.
  const std::atomic<bool>* cancel = nullptr;
  // When set, render_image counts the pixels it finishes here (read from any thread).
  render_progress* progress = nullptr;
  // When set, render_image also fills it with every pixel's deep samples (render/deep_pixel.h),
  // charging each finished tile's to deep_memory when that is set. Deep output takes the simple
  // path only (check_deep_path); render_image throws kiln::error (input) otherwise.
  deep_image* deep = nullptr;
  memory_charge* deep_memory = nullptr;
  // When set, the texture pyramids a caller keeps across renders of one scene (a sequence's frames,
  // a scene rendered again): render_image uses the filter it holds (the caller has pointed it at
  // the scene, texture_filter::rebind) or builds one into it.
  std::unique_ptr<texture_filter>* kept_textures = nullptr;
  // The same for the environment's sampling tables: render_image uses them when they fit the scene
  // (environment_light_fits), else makes them into it.
  std::unique_ptr<environment_light>* kept_environment = nullptr;
};

struct render_statistics {
  ray_counts rays;
  uint64_t discarded_samples = 0;  // samples whose radiance was NaN or infinite, left out of their pixel
  double seconds = 0.0;
  int threads_used = 0;
};

// Called after each finished tile with (tiles done, tiles total); may be called from any thread,
// never concurrently.
using progress_callback = std::function<void(size_t done, size_t total)>;

// The cone each camera ray carries: the pixel's, narrowed for supersampling by 1/√spp (each sample
// stands for a sub-pixel), no narrower than 1/8 pixel (as pbrt-v4 scales its camera differentials).
ray_cone sample_cone(const view_camera& cam, int spp);
// The factor sample_cone narrows the pixel's cone by.
double sample_cone_scale(int spp);

// Throws kiln::error (input, location "--deep") unless settings take the path deep output supports:
// the whole frame (whole_frame: no crop or band), stratified samples, a filter that stays inside
// the pixel, no visible background. Anything else would write samples that do not add up to the
// flat pixels.
void check_deep_path(const render_settings& settings, bool whole_frame);

film render_image(const scene& world, const accelerator& accel, const view_camera& cam,
                  const render_settings& settings, render_statistics* stats = nullptr,
                  const progress_callback& progress = {});

}  // namespace kiln
