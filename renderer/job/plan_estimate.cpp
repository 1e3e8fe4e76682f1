#include "job/plan_estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "io/exr/cryptomatte.h"
#include "job/memory_estimates.h"
#include "job/render_job.h"
#include "render/light_groups.h"
#include "shade/texture_filter.h"

namespace kiln {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

plan_estimate estimate_job(const render_options& options, int probe_pixels) {
  const auto load_start = std::chrono::steady_clock::now();
  const prepared_scene prepared = prepare_scene(options);
  const double preparing = seconds_since(load_start);
  plan_estimate e = estimate_job(prepared, options, probe_pixels);
  e.load_seconds += preparing - prepared.load_seconds;  // the view and lighting besides the file
  return e;
}

plan_estimate estimate_job(const prepared_scene& prepared, const render_options& options, int probe_pixels) {
  plan_estimate e;
  const auto build_start = std::chrono::steady_clock::now();
  render_settings settings = make_render_settings(options);
  const int width = prepared.cam.width, height = prepared.cam.height;

  // Peak memory: what the loader charged (meshes, images) plus what the render stage charges.
  e.peak_memory_bytes =
      prepared.memory->used() + texture_filter_bytes(prepared.world) + accelerator_bytes(prepared.world) +
      film_and_output_bytes({0, 0, width, height}, settings.aovs, light_group_count(prepared.world));
  const std::unique_ptr<accelerator> accel = make_job_accelerator(prepared.world, options);
  e.load_seconds = prepared.load_seconds + seconds_since(build_start);

  // Two probes, the same view on smaller images (the window does not depend on the pixel count):
  // a render costs a part fixed per call (the textures' mip pyramids, the film, the threads, cold
  // caches), which a one-pixel probe measures, and a part per sample, from the larger probe.
  settings.samples_per_pixel = std::min(samples_per_pixel_of(options), 4);
  settings.threads = 1;
  settings.motion = prepared.motion.get();
  if (!prepared.camera_steps.empty()) settings.camera_steps = &prepared.camera_steps;
  const cryptomatte_layer objects = cryptomatte_objects(prepared.world);
  const cryptomatte_layer materials = cryptomatte_materials(prepared.world);
  settings.mattes = {objects.id_by_key, materials.id_by_key};
  double probe_samples[2], probe_seconds[2];
  view_camera probe = prepared.cam;
  for (int k = 0; k < 2; ++k) {
    const double shrink = k == 0
                              ? std::max(width, height)
                              : std::max(1.0, std::sqrt(double(width) * height / std::max(probe_pixels, 1)));
    probe.width = std::max(1, int(std::lround(width / shrink)));
    probe.height = std::max(1, int(std::lround(height / shrink)));
    render_statistics stats;
    render_image(prepared.world, *accel, probe, settings, &stats);
    accel->throw_if_failed();
    probe_samples[k] = double(probe.width) * probe.height * settings.samples_per_pixel;
    probe_seconds[k] = stats.seconds;
  }
  e.probe_width = probe.width;
  e.probe_height = probe.height;
  e.probe_spp = settings.samples_per_pixel;
  // Timing noise on a busy machine can make the larger probe no slower than the one-pixel one:
  // then at least a twentieth of its time counts as per sample.
  const double samples = double(width) * height * std::max(samples_per_pixel_of(options), 1);
  const double fixed = std::min(probe_seconds[0], 0.95 * probe_seconds[1]);
  const double per_sample = (probe_seconds[1] - fixed) / std::max(probe_samples[1] - probe_samples[0], 1.0);
  e.render_seconds = fixed + per_sample * samples;
  return e;
}

}  // namespace kiln
