#include "job/render_sequence.h"

#include <chrono>
#include <memory>
#include <new>
#include <optional>

#include "accel/make_accelerator.h"
#include "io/exr/environment_reader.h"
#include "job/exr_storage_options.h"
#include "job/frame_motion.h"
#include "job/frame_range.h"
#include "job/job_stop.h"
#include "job/lighting.h"
#include "job/option_values.h"
#include "job/output_guard.h"
#include "job/render_job_steps.h"
#include "job/turntable.h"

namespace kiln {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The environment map a frame hands back for the next: the last image of its scene.
std::optional<image> take_environment(scene& world) {
  if (world.env.map_image < 0 || size_t(world.env.map_image) >= world.images.size()) return std::nullopt;
  return std::move(world.images[size_t(world.env.map_image)]);
}

// One frame after the asset is loaded: pose, view, backend (updated when it can be), render.
struct sequence_state {
  prepared_scene prepared;
  std::unique_ptr<gltf_sequence> asset;
  std::unique_ptr<accelerator> accel;
  std::optional<image> environment;
  render_fingerprint inputs;  // hashed once for every frame
  bool charged = false;
};

render_job_result render_frame(const render_job& job, const render_options& options, sequence_state& st,
                               const std::atomic<bool>* stop, frame_report& report, const char*& stage) {
  render_job_result result;
  result.storage = resolve_exr_settings(options);
  const auto pose_start = std::chrono::steady_clock::now();
  stage = "posing the scene";
  std::vector<uint32_t> posed;
  scene previous = std::move(st.prepared.world);
  if (!st.environment) st.environment = take_environment(previous);
  pose_job_frame(*st.asset, options, &previous, &posed, st.prepared);
  previous = scene();  // the last frame's deformed meshes go now
  finish_loaded_scene(options, st.prepared, job.warn, st.environment ? &*st.environment : nullptr, &posed);
  st.environment.reset();
  report.pose_seconds += seconds_since(pose_start);

  const prepared_scene& p = st.prepared;
  result.width = p.cam.width;
  result.height = p.cam.height;
  result.camera_description = p.camera_description;
  result.load_seconds = report.pose_seconds;
  render_settings settings = make_render_settings(options);
  settings.crop = job_region(options, p.cam);
  settings.motion = p.motion.get();
  if (!p.camera_steps.empty()) settings.camera_steps = &p.camera_steps;
  // The film, pyramids and backend of one frame; the next frame's replace them.
  if (!st.charged) charge_render_memory(p, settings);
  st.charged = true;

  stage = "building the acceleration structure";
  const auto build_start = std::chrono::steady_clock::now();
  report.backend_updated = st.accel && st.accel->update(posed);
  if (!report.backend_updated) {
    st.accel.reset();
    st.accel = make_job_accelerator(p.world, options);
  }
  report.update_seconds = result.build_seconds = seconds_since(build_start);

  stage = "rendering";
  const cryptomatte_layer objects = cryptomatte_objects(p.world);
  const cryptomatte_layer materials = cryptomatte_materials(p.world);
  settings.mattes = {objects.id_by_key, materials.id_by_key};
  settings.cancel = stop;
  settings.progress = job.progress;
  result.deep = attach_deep_output(options, p, settings);
  result.image = render_image(p.world, *st.accel, p.cam, settings, &result.stats);
  st.accel->throw_if_failed();
  throw_if_cancelled(stop, options.output);
  result.metadata = job_metadata(options, p, settings, result.stats,
                                 fingerprint_with_settings(st.inputs, options), objects, materials);
  return result;
}

}  // namespace

render_options frame_options(const render_options& sequence, long long frame) {
  render_options o = sequence;
  o.frames.clear();
  o.frame = frame;
  o.output = frame_path(sequence.output, frame);
  if (!sequence.preview.empty()) o.preview = frame_path(sequence.preview, frame);
  return o;
}

bool renders_sequence(const render_options& options) {
  return !options.frames.empty() || (options.turntable > 0 && !options.frame);
}

std::vector<long long> sequence_frames(const render_options& options) {
  if (!options.frames.empty()) return frame_numbers(parse_frame_range(options.frames));
  return frame_numbers(turntable_frames(options));
}

std::vector<long long> check_sequence(const render_options& options) {
  const std::vector<long long> frames = sequence_frames(options);
  const char* sequence = options.frames.empty() ? "--turntable" : "--frames";
  if (options.time && !turntable_holds_pose(options))
    throw input_error(
        "", "--time",
        std::string("--time and ") + sequence + " both choose the time; give one of them" +
            (options.turntable > 0 ? " (--turntable-animation hold keeps the pose at --time)" : ""));
  if (options.frame)
    throw input_error("", "--frame", "--frame and --frames both choose the frame; give one of them");
  if (frames.size() > 1 && !options.output.empty()) {  // no output: a benchmark's frames
    if (!has_frame_placeholder(options.output))
      throw input_error("", "-o",
                        "'" + options.output + "' has no frame placeholder: with several frames (" +
                            sequence + "), name the output like shot.####.exr or shot.%04d.exr");
    if (!options.preview.empty() && !has_frame_placeholder(options.preview))
      throw input_error("", "--preview",
                        "'" + options.preview + "' has no frame placeholder (e.g. shot.####.png)");
  }
  // Every frame reads the same files and writes into the same folders: the first frame's check
  // finds both, the others check only their own outputs against them.
  shared_output_checks shared;
  shared.inputs = index_inputs(render_input_files(frame_options(options, frames.front())));
  for (long long frame : frames) {
    check_job(frame_options(options, frame), &shared);
    shared.folders_probed = true;
  }
  return frames;
}

void run_sequence(const render_job& job,
                  const std::function<void(const render_job_result&, const render_options&,
                                           const frame_report&)>& on_frame) {
  const std::vector<long long> frames = check_sequence(job.options);
  sequence_state st;
  frame_report first;
  // Loaded once, under the first frame's options (the stop flag of a load ends with it).
  const render_options first_options = frame_options(job.options, frames.front());
  run_stoppable(job, first_options, [&](const std::atomic<bool>* stop, const char*& stage) {
    stage = "hashing the inputs";
    st.inputs = job.fingerprint ? *job.fingerprint : make_fingerprint(first_options, stop);
    stage = "loading the scene";
    const auto load_start = std::chrono::steady_clock::now();
    st.prepared.memory = std::make_shared<memory_budget>(job_memory_limit(first_options));
    st.prepared.colour = resolve_working_space(first_options);        // before the asset loads
    if (!first_options.preview.empty()) preview_view(first_options);  // and the preview's view
    st.asset = std::make_unique<gltf_sequence>(
        first_options.input, job_load_options(first_options, stop, st.prepared.memory.get()));
    if (const std::string file = job_environment_file(first_options); !file.empty())
      st.environment = read_environment_image(file);
    first.pose_seconds = seconds_since(load_start);
    return 0;
  });
  for (size_t i = 0; i < frames.size(); ++i) {
    const render_options options = frame_options(job.options, frames[i]);
    frame_report report = i == 0 ? first : frame_report{};
    report.frame = frames[i];
    const render_job_result result =
        run_stoppable(job, options, [&](const std::atomic<bool>* stop, const char*& stage) {
          return render_frame(job, options, st, stop, report, stage);
        });
    on_frame(result, options, report);
  }
}

}  // namespace kiln
