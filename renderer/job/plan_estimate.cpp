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
  plan_estimate e;
  const auto load_start = std::chrono::steady_clock::now();
  const prepared_scene prepared = prepare_scene(options);
  render_settings settings = make_render_settings(options);
  const int width = prepared.cam.width, height = prepared.cam.height;

  // Peak memory: what the loader charged (meshes, images) plus what the render stage charges.
  e.peak_memory_bytes =
      prepared.memory->used() + texture_filter_bytes(prepared.world) + accelerator_bytes(prepared.world) +
      film_and_output_bytes({0, 0, width, height}, settings.aovs, light_group_count(prepared.world));
  const std::unique_ptr<accelerator> accel = make_job_accelerator(prepared.world, options);
  e.load_seconds = seconds_since(load_start);

  // The probe: the same view on a smaller image (the window does not depend on the pixel count).
  const double shrink = std::max(1.0, std::sqrt(double(width) * height / std::max(probe_pixels, 1)));
  view_camera probe = prepared.cam;
  probe.width = std::max(1, int(std::lround(width / shrink)));
  probe.height = std::max(1, int(std::lround(height / shrink)));
  settings.samples_per_pixel = std::min(options.samples_per_pixel, 4);
  settings.threads = 1;
  settings.motion = prepared.motion.get();
  if (!prepared.camera_steps.empty()) settings.camera_steps = &prepared.camera_steps;
  const cryptomatte_layer objects = cryptomatte_objects(prepared.world);
  const cryptomatte_layer materials = cryptomatte_materials(prepared.world);
  settings.mattes = {objects.id_by_key, materials.id_by_key};
  render_statistics stats;
  render_image(prepared.world, *accel, probe, settings, &stats);
  accel->throw_if_failed();
  e.probe_width = probe.width;
  e.probe_height = probe.height;
  e.probe_spp = settings.samples_per_pixel;
  const double probe_samples = double(probe.width) * probe.height * settings.samples_per_pixel;
  const double samples = double(width) * height * std::max(options.samples_per_pixel, 1);
  e.render_seconds = stats.seconds * samples / probe_samples;
  return e;
}

}  // namespace kiln
