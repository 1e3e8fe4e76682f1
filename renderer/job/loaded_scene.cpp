#include "job/loaded_scene.h"

#include <chrono>
#include <optional>
#include <vector>

#include "io/exr/cryptomatte.h"
#include "io/exr/preview_writer.h"
#include "job/asset_file.h"
#include "job/asset_info.h"
#include "job/exr_storage_options.h"
#include "job/frame_motion.h"
#include "job/lighting.h"
#include "job/option_table.h"
#include "job/render_job_steps.h"
#include "job/turntable.h"

namespace kiln {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The option-table values of names, one line each, for comparing two sets of options.
std::string option_values(const render_options& options, const std::vector<const char*>& names) {
  std::string text;
  for (const char* name : names) {
    const std::optional<std::string> value = find_render_option(name)->get(options);
    text += std::string(name) + "=" + value.value_or("<unset>") + "\n";
  }
  return text;
}

// What the parsed file, its materials and its budget depend on.
const std::vector<const char*> load_option_names = {
    "scene",          "variant",    "animation",           "working-space",
    "ocio-config",    "max-memory", "allow-outside-files", "max-json-bytes",
    "max-json-depth", "max-nodes",  "max-instances",       "max-texels"};

// What the backend is built from besides the scene's geometry: the kind and its tuning, and the
// holdouts, which set the instances' ray masks.
const std::vector<const char*> backend_option_names = {
    "accel",       "grid-resolution", "grid-density", "grid-max-items", "grid-max-depth",    "bvh-quality",
    "bvh-compact", "holdout",         "only",         "others",         "holdout-invisible", "deep"};

// Whether an animated file's poses across its animation frame the view (job/frame_motion.h).
std::string framing_key(const render_options& options) {
  return std::to_string(options.look_from || options.look_at) + std::to_string(options.camera.empty()) +
         std::to_string(uses_orbit_view(options)) + std::to_string(turntable_holds_pose(options));
}

// The environment map a render hands back for the next: the last image of its scene.
std::optional<image> take_environment(scene& world) {
  if (world.env.map_image < 0 || size_t(world.env.map_image) >= world.images.size()) return std::nullopt;
  return std::move(world.images[size_t(world.env.map_image)]);
}

}  // namespace

std::string changed_load_option(const render_options& loaded, const render_options& wanted) {
  if (loaded.input != wanted.input || loaded.in_memory != wanted.in_memory) return "input";
  for (const char* name : load_option_names)
    if (find_render_option(name)->get(loaded) != find_render_option(name)->get(wanted)) return name;
  return "";
}

struct loaded_scene::state {
  render_options loaded;  // the options it was loaded with
  render_fingerprint inputs;
  std::string hashed_environment;  // the environment file inputs hashed
  prepared_scene prepared;         // before asset: its budget outlives what the asset holds charged to it
  std::unique_ptr<gltf_sequence> asset;
  double load_seconds = 0.0;           // reported with the first render
  bool posed = false;                  // prepared.world holds a pose
  std::vector<uint32_t> posed_meshes;  // the meshes its pose built (the backend refits them)
  bool sequence = false;
  std::string framing;  // framing_key of the pose prepared.framing was found for
  std::unique_ptr<accelerator> accel;
  std::string backend;  // backend_option_names' values accel was built under
  std::string environment_file;
  // The texture pyramids of the last render, kept while the poses carry its images over, and the
  // environment's tables, kept while its map is the same image.
  std::unique_ptr<texture_filter> textures;
  std::unique_ptr<environment_light> environment_tables;
};

loaded_scene::loaded_scene(const render_job& job) : state_(std::make_unique<state>()) {
  check_asset_file(job.options.input);
  run_stoppable(job, job.options, [&](const std::atomic<bool>* stop, const char*& stage) {
    load(job, job.options, stop, stage);
    return 0;
  });
}

loaded_scene::loaded_scene(const render_job& job, const render_options& options,
                           const std::atomic<bool>* stop, const char*& stage)
    : state_(std::make_unique<state>()) {
  load(job, options, stop, stage);
}

loaded_scene::~loaded_scene() = default;

void loaded_scene::load(const render_job& job, const render_options& options, const std::atomic<bool>* stop,
                        const char*& stage) {
  state& st = *state_;
  st.loaded = options;
  stage = "hashing the inputs";
  st.inputs = job.fingerprint ? *job.fingerprint : make_fingerprint(options, stop);
  st.hashed_environment = job_environment_file(options);
  stage = "loading the scene";
  const auto load_start = std::chrono::steady_clock::now();
  st.prepared.memory = std::make_shared<memory_budget>(job_memory_limit(options));
  st.prepared.colour = resolve_working_space(options);  // a bad config or space fails before the asset loads
  if (!options.preview.empty()) preview_view(options);  // and so does a bad display or view
  st.asset = std::make_unique<gltf_sequence>(options.input,
                                             job_load_options(options, stop, st.prepared.memory.get()));
  st.load_seconds = seconds_since(load_start);
}

const render_options& loaded_scene::options() const { return state_->loaded; }

void loaded_scene::render_as_sequence() { state_->sequence = true; }

render_job_result loaded_scene::render(const render_job& job) {
  check_job(job.options);
  if (!changed_load_option(state_->loaded, job.options).empty()) return run_job(job);
  return run_stoppable(job, job.options, [&](const std::atomic<bool>* stop, const char*& stage) {
    return render(job, job.options, stop, stage, nullptr);
  });
}

bool loaded_scene::pose(const render_job& job, const render_options& options, const std::atomic<bool>* stop,
                        const char*& stage, frame_report& timings) {
  try {
    return pose_scene(job, options, stop, stage, timings);
  } catch (...) {
    // What the failed pose left is no base for the next: that one poses afresh.
    state_->posed = false;
    state_->accel.reset();
    state_->prepared.colours_converted = false;
    throw;
  }
}

bool loaded_scene::pose_scene(const render_job& job, const render_options& options,
                              const std::atomic<bool>* stop, const char*& stage, frame_report& timings) {
  state& st = *state_;
  prepared_scene& p = st.prepared;
  // The environment map is an input too: one other than the load's is hashed now.
  if (const std::string file = job_environment_file(options);
      file != st.hashed_environment && !job.fingerprint) {
    stage = "hashing the inputs";
    st.inputs = make_fingerprint(options, stop);
    st.hashed_environment = file;
  }
  const auto pose_start = std::chrono::steady_clock::now();
  stage = st.posed ? "posing the scene" : "loading the scene";
  if (framing_key(options) != st.framing) {  // found again for a view that frames otherwise
    p.framing.reset();
    p.framing_checked = false;
    st.framing = framing_key(options);
  }
  // A pose takes over the last one's materials, images and still meshes, converted already; in a
  // working space, a render that is not a sequence's frame poses afresh instead, so that an image
  // read as colour and as data can keep its converted copy (render/colour_conversion.h).
  const bool carry = st.sequence || (st.posed && !p.colour.converts());
  scene previous = std::move(p.world);
  std::optional<image> environment = take_environment(previous);
  const std::string environment_file = job_environment_file(options);
  if (environment_file != st.environment_file) environment.reset();
  // Their map is read again (its freed buffer's address can come back), or converted afresh.
  if (!environment || (!carry && p.colour.converts())) st.environment_tables.reset();
  if (!carry) {
    st.accel.reset();     // it points into the meshes that go now
    st.textures.reset();  // and it into the images: decoded again, they may reuse the addresses
    previous = scene();
    p.colours_converted = false;
  }
  std::vector<uint32_t>& posed = st.posed_meshes;
  posed.clear();
  pose_job_frame(*st.asset, options, carry ? &previous : nullptr, carry ? &posed : nullptr, p);
  previous = scene();                           // the last pose's deformed meshes go now
  if (!st.sequence) p.headlight_noted = false;  // each render gives its notes
  finish_loaded_scene(options, p, job.warn, environment ? &*environment : nullptr, carry ? &posed : nullptr);
  st.environment_file = environment_file;
  st.posed = true;
  timings.pose_seconds = st.load_seconds + seconds_since(pose_start);
  st.load_seconds = 0.0;
  return carry;
}

asset_info loaded_scene::describe(const render_job& job) {
  check_job(job.options);
  if (!changed_load_option(state_->loaded, job.options).empty())
    return describe_asset(job.options, job.cancel, job.warn);
  const std::lock_guard<std::mutex> one_at_a_time(rendering_);
  return run_stoppable(job, job.options, [&](const std::atomic<bool>* stop, const char*& stage) {
    frame_report timings;
    state_->accel.reset();  // built for another pose; the next render builds its own
    pose(job, job.options, stop, stage, timings);
    return describe_prepared(job.options, state_->prepared, state_->asset->summary());
  });
}

render_job_result loaded_scene::render(const render_job& job, const render_options& options,
                                       const std::atomic<bool>* stop, const char*& stage,
                                       frame_report* report) {
  const std::lock_guard<std::mutex> one_at_a_time(rendering_);
  state& st = *state_;
  prepared_scene& p = st.prepared;
  frame_report timings;
  render_job_result result;
  result.storage = resolve_exr_settings(options);
  const bool carry = pose(job, options, stop, stage, timings);
  result.width = p.cam.width;
  result.height = p.cam.height;
  result.camera_description = p.camera_description;
  result.load_seconds = timings.pose_seconds;
  render_settings settings = make_render_settings(options);
  settings.crop = job_region(options, p.cam);
  settings.motion = p.motion.get();
  if (!p.camera_steps.empty()) settings.camera_steps = &p.camera_steps;
  memory_charge render_memory(p.memory.get());  // the film, pyramids and backend of this render
  charge_render_memory(p, settings, render_memory);

  stage = "building the acceleration structure";
  const auto build_start = std::chrono::steady_clock::now();
  const std::string backend = option_values(options, backend_option_names);
  timings.backend_updated = carry && st.accel && backend == st.backend && st.accel->update(st.posed_meshes);
  if (!timings.backend_updated) {
    st.accel.reset();
    st.accel = make_job_accelerator(p.world, options);
    st.backend = backend;
  }
  timings.update_seconds = result.build_seconds = seconds_since(build_start);

  // The images a carrying pose moved keep their pyramids: built once for a sequence's frames.
  timings.textures_kept = st.textures && st.textures->rebind(p.world);
  if (!timings.textures_kept) st.textures.reset();
  settings.kept_textures = &st.textures;
  timings.environment_kept = st.environment_tables && environment_light_fits(*st.environment_tables, p.world);
  settings.kept_environment = &st.environment_tables;

  stage = "rendering";
  const cryptomatte_layer objects = cryptomatte_objects(p.world);
  const cryptomatte_layer materials = cryptomatte_materials(p.world);
  settings.mattes = {objects.id_by_key, materials.id_by_key};
  settings.cancel = stop;
  settings.progress = job.progress;
  result.deep = attach_deep_output(options, p, settings);
  result.image = render_image(p.world, *st.accel, p.cam, settings, &result.stats);
  st.accel->throw_if_failed();  // an error Embree reported during traversal fails the render
  // A stop that arrives after the last pixel still ends the job before anything is written.
  throw_if_cancelled(stop, options.output);
  const render_fingerprint fingerprint =
      job.fingerprint && !st.sequence ? *job.fingerprint : fingerprint_with_settings(st.inputs, options);
  result.metadata = job_metadata(options, p, settings, result.stats, fingerprint, objects, materials);
  if (report) {
    timings.frame = report->frame;
    *report = timings;
  }
  return result;
}

}  // namespace kiln
