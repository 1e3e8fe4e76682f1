// One render as a library call: options in, film and metadata out. run_job loads the asset,
// chooses the view, builds the backend, renders and assembles the EXR metadata; write_job_outputs
// writes the EXR (and the preview) atomically. `kiln render`, `kiln batch`'s jobs, `kiln compare`,
// `kiln bench` and the Python module are thin clients of these calls; printing, signals and
// exit codes stay with them.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accel/accelerator.h"
#include "core/memory_budget.h"
#include "io/exr/exr_writer.h"
#include "job/deep_output.h"
#include "job/render_options.h"
#include "job/working_space.h"
#include "render/film.h"
#include "render/tile_renderer.h"
#include "render/view_camera.h"
#include "scene/scene.h"

namespace kiln {

struct render_fingerprint;

struct render_job {
  render_options options;
  // Raised (by a signal handler, or Python's KeyboardInterrupt): loading stops between chunks and
  // rendering within a pixel or 64 samples; run_job then throws kiln::error (interrupted).
  const std::atomic<bool>* cancel = nullptr;
  // Pixels finished so far, for a progress line or callback watching from another thread.
  render_progress* progress = nullptr;
  // Loader warnings and notes ("the file has no lights; ..."), one line each; empty: dropped.
  std::function<void(const std::string&)> warn;
  // The input and settings hashes when the caller knows them (a batch); null: computed here.
  const render_fingerprint* fingerprint = nullptr;
};

// A loaded scene in render space with the chosen view and, when the file has none, the headlight.
struct prepared_scene {
  scene world;
  view_camera cam;
  std::string camera_description;
  double load_seconds = 0.0;
  // The job's memory budget (--max-memory), holding what the scene's meshes and images were
  // estimated to take; the render stage charges its own allocations to it.
  std::shared_ptr<memory_budget> memory;
  bool headlight_noted = false;  // the lighting's notes were given (once per sequence)
  std::string lighting;          // what lights the render (job/lighting.h's apply_lighting)
  // With the motion AOV: the scene at the neighbouring frames (job/frame_motion.h); else null.
  std::shared_ptr<scene_motion> motion;
  std::shared_ptr<memory_charge> motion_memory;   // what motion holds, charged to memory
  std::shared_ptr<memory_charge> shutter_memory;  // what world.shutter holds (motion blur)
  // A glTF camera moving during the shutter: the view at each step, in render space; else empty.
  std::vector<view_camera> camera_steps;
  // An animated file seen by the default camera: the bounds of its poses across the animation, which
  // that camera frames at every time (job/frame_motion.h); empty otherwise.
  std::optional<bounds3> framing;
  bool framing_checked = false;    // framing was worked out (once for a sequence)
  working_space colour;            // --working-space, resolved before loading; applied by finish_loaded_scene
  bool colours_converted = false;  // what a sequence's poses carry over is in the working space already
};

// The job's memory budget in bytes: --max-memory, or job/memory_limit.h's default.
uint64_t job_memory_limit(const render_options& options);

// The time in seconds the scene is posed at: --time, or (--frame - --frame-start) / --fps with
// the defaults 1 and 24, or 0. Throws kiln::error (input) for --time with --frame, or --fps or
// --frame-start without --frame.
double scene_time(const render_options& options);

// Loads options.input and chooses the view. Throws kiln::error for bad input.
prepared_scene prepare_scene(const render_options& options, const std::atomic<bool>* cancel = nullptr,
                             const std::function<void(const std::string&)>& warn = {});

// The renderer's settings from the options (without the crop, the mattes and the callbacks).
render_settings make_render_settings(const render_options& options);

// The backend the options name, built over world.
std::unique_ptr<accelerator> make_job_accelerator(const scene& world, const render_options& options);

struct render_job_result {
  film image;
  exr_metadata metadata;
  exr_settings storage;  // how the EXR stores the layers (resolved before rendering)
  render_statistics stats;
  int width = 0, height = 0;  // the full frame; the film may hold a crop or band of it
  std::string camera_description;
  double load_seconds = 0.0, build_seconds = 0.0;
  // With --deep: the deep image, written beside the EXR (job/deep_output.h); null otherwise.
  std::shared_ptr<deep_output> deep;
};

// The checks that need no scene: the asset is a file, the outputs are safe to write (never a
// file the render reads, never through a symlink, writable), the storage options agree. Throws
// kiln::error (input or io). run_job calls it; a client may call it earlier to fail fast. shared
// (job/output_guard.h) holds what the frames of a sequence share, found once for all of them.
struct shared_output_checks;
void check_job(const render_options& options, const shared_output_checks* shared = nullptr);

// Options given that do nothing beside the others ("--view without --preview"), one "warning: ..."
// line each, for a client to print or raise; empty when none.
std::vector<std::string> job_option_warnings(const render_options& options);

// Renders the job. Throws kiln::error: input for bad input or a file over the memory budget,
// render for a backend failure or an allocation that failed (naming the stage it failed in),
// interrupted when cancel was raised.
render_job_result run_job(const render_job& job);

// Writes result to options.output (and options.preview and the deep EXR when set; the deep file
// first, so an EXR that exists has its deep file beside it), each through a temporary file
// renamed into place. Throws kiln::error (io) on failure, (render) when memory runs out, (interrupted) when
// cancel is raised before the EXR is renamed; an existing file is then untouched.
void write_job_outputs(const render_job_result& result, const render_options& options,
                       const std::atomic<bool>* cancel = nullptr);

}  // namespace kiln
