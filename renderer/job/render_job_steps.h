// The steps run_job is made of, shared with run_sequence (job/render_sequence.h), which runs
// them once per frame over one loaded asset. Internal to the job layer.
#pragma once

#include <atomic>
#include <functional>
#include <new>
#include <string>

#include "core/error.h"
#include "core/format_number.h"
#include "io/exr/cryptomatte.h"
#include "io/gltf/gltf_loader.h"
#include "job/job_stop.h"
#include "job/option_values.h"
#include "job/render_fingerprint.h"
#include "job/render_job.h"

namespace kiln {

// The loader's options for the job: scene, file rules, limits, threads, the budget and the pose.
gltf_load_options job_load_options(const render_options& options, const std::atomic<bool>* cancel,
                                   memory_budget* memory);

// Everything prepare_scene does after loading p.world: the background and environment map (the
// one given, else read from --environment), the loader's warnings, holdouts, the view and its
// range check, the headlight, the working space and the move to render space. A sequence passes
// posed_meshes, the meshes this frame's pose built (the rest, like its materials and images,
// carry over from the last frame, already in the working space).
void finish_loaded_scene(const render_options& options, prepared_scene& p,
                         const std::function<void(const std::string&)>& warn,
                         image* environment_map = nullptr,
                         const std::vector<uint32_t>* posed_meshes = nullptr);

// The view the job renders world through: --look-from/--look-at, an orbit view (--camera-view, a
// --turntable frame; job/turntable.h), the --camera (default: the first glTF camera), or the
// default camera; the orbit and default cameras frame `framing` when given (an animated file's every
// pose) and else world's bounds; description names it. Throws kiln::error (input).
view_camera job_view(const render_options& options, const scene& world, std::string& description,
                     const bounds3* framing = nullptr);

// The region of the frame the job renders: its --crop or --band, checked against the image.
pixel_rect job_region(const render_options& options, const view_camera& cam);

// The film, the mip pyramids and the backend, charged to the job's budget (through held, which
// gives them back when the render is over) before any is made.
void charge_render_memory(const prepared_scene& prepared, const render_settings& settings,
                          memory_charge& held);

// With --deep: a deep image for settings to fill, its samples charged to the prepared scene's budget
// as tiles finish; null (and settings untouched) without.
std::shared_ptr<deep_output> attach_deep_output(const render_options& options, const prepared_scene& prepared,
                                                render_settings& settings);

// The EXR header of a finished render.
exr_metadata job_metadata(const render_options& options, const prepared_scene& prepared,
                          const render_settings& settings, const render_statistics& stats,
                          const render_fingerprint& fingerprint, const cryptomatte_layer& objects,
                          const cryptomatte_layer& materials);

// The error of an allocation that failed at `stage` although the estimates fit the budget.
error out_of_memory(const render_options& options, const std::string& stage);

// Throws kiln::error (interrupted) naming output when cancel is raised.
void throw_if_cancelled(const std::atomic<bool>* cancel, const std::string& output);

// Runs fn(stop, stage) under the job's stop flag (its cancel flag and --time-limit) and turns
// what stops it into one message: a failed allocation names the stage fn last set; wherever the
// time limit found the job (hashing, loading, rendering) it ends as time_limit; an interrupt
// names the file it was reading, or the output when it stopped the render.
template <typename F>
auto run_stoppable(const render_job& job, const render_options& options, F&& fn) {
  const job_stop stop(job.cancel, options.time_limit_seconds);
  const char* stage = "checking the inputs";
  try {
    return fn(stop.flag(), stage);
  } catch (const std::bad_alloc&) {
    throw out_of_memory(options, stage);
  } catch (const error& e) {
    if (e.kind() != error_kind::interrupted) throw;
    if (stop.timed_out())
      throw error(
          error_kind::time_limit, options.output, "",
          "time limit of " + format_number(options.time_limit_seconds) + " s reached, nothing written");
    if (!e.file().empty()) throw;
    throw error(error_kind::interrupted, options.output, "", "render interrupted, nothing written");
  }
}

}  // namespace kiln
