#include "job/render_job.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <new>
#include <sstream>

#include "accel/make_accelerator.h"
#include "core/error.h"
#include "core/message_text.h"
#include "io/exr/cryptomatte.h"
#include "io/exr/deep_writer.h"
#include "io/exr/environment_reader.h"
#include "io/exr/preview_writer.h"
#include "io/gltf/gltf_loader.h"
#include "job/asset_file.h"
#include "job/exr_storage_options.h"
#include "job/frame_motion.h"
#include "job/holdouts.h"
#include "job/job_stop.h"
#include "job/lighting.h"
#include "job/loaded_scene.h"
#include "job/memory_estimates.h"
#include "job/memory_limit.h"
#include "job/option_table.h"
#include "job/option_values.h"
#include "job/output_guard.h"
#include "job/render_fingerprint.h"
#include "job/render_job_steps.h"
#include "job/turntable.h"
#include "render/frame_bands.h"
#include "render/light_groups.h"
#include "render/render_space.h"
#include "render/view_range.h"
#include "shade/environment_light.h"
#include "shade/texture_filter.h"

namespace kiln {

namespace {

constexpr int default_width = 640;
constexpr int default_height = 480;
constexpr int max_image_side = 65536;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Finds the camera named or numbered by the --camera argument.
const camera& select_camera(const scene& world, const std::string& which) {
  if (world.cameras.empty()) throw input_error(world.source, "--camera", "the file has no cameras");
  char* end = nullptr;
  long index = std::strtol(which.c_str(), &end, 10);
  if (!which.empty() && end && *end == '\0') {
    if (index < 0 || size_t(index) >= world.cameras.size())
      throw input_error(world.source, "--camera",
                        "camera index " + which + " out of range (file has " +
                            std::to_string(world.cameras.size()) + " cameras)");
    return world.cameras[size_t(index)];
  }
  std::string names;
  for (const camera& c : world.cameras) {
    if (c.name == which) return c;
    names += (names.empty() ? "" : ", ") + quoted(c.name);
  }
  throw input_error(world.source, "--camera",
                    "no camera named " + quoted(which) + " (cameras: " + names + ")");
}

// The film holds 32 bytes a pixel (RGBA, Z, N) and the EXR writer a copy; past max_pixels the
// allocation would fail (or swap) only after the scene has loaded, so refuse it as a usage error.
void check_pixel_count(int width, int height, size_t max_pixels) {
  const size_t pixels = size_t(width) * size_t(height);
  if (pixels > max_pixels)
    throw input_error("", "image size",
                      std::to_string(width) + "x" + std::to_string(height) + " is " + std::to_string(pixels) +
                          " pixels, over the limit of " + std::to_string(max_pixels) + " (--max-pixels)");
}

// Image size: explicit values win; a missing side follows the glTF camera's aspect ratio when it
// has one, 4:3 otherwise; with neither given the image is 640 wide.
void resolve_image_size(const render_options& options, float camera_aspect, int& width, int& height) {
  double aspect = camera_aspect > 0.0f ? camera_aspect : double(default_width) / default_height;
  if (options.width && options.height) {
    width = *options.width;
    height = *options.height;
  } else if (options.width) {
    width = *options.width;
    height = std::max(1, int(std::lround(width / aspect)));
  } else if (options.height) {
    height = *options.height;
    width = std::max(1, int(std::lround(height * aspect)));
  } else {
    width = default_width;
    height = camera_aspect > 0.0f ? std::max(1, int(std::lround(width / aspect))) : default_height;
  }
  if (width > max_image_side || height > max_image_side)
    throw input_error("", "image size", "at most " + std::to_string(max_image_side) + " pixels a side");
  check_pixel_count(width, height, options.max_pixels);
}

// A look-at camera needs both its ends; checked before the scene loads and again where it is made.
void check_look_at_pair(const render_options& options) {
  if (bool(options.look_from) != bool(options.look_at))
    throw input_error("", "--look-from/--look-at", "give both --look-from and --look-at");
}

}  // namespace

view_camera job_view(const render_options& options, const scene& world, std::string& description,
                     const bounds3* framing) {
  const std::optional<orbit_angles> orbit = job_orbit(options);  // refuses it beside --look-from, --camera
  if (options.look_from || options.look_at) {
    check_look_at_pair(options);
    int width = 0, height = 0;
    resolve_image_size(options, 0.0f, width, height);
    description = "look-at";
    return make_look_at_camera(*options.look_from, *options.look_at, options.up, options.fov_degrees, width,
                               height);
  }
  if (orbit) {
    int width = 0, height = 0;
    resolve_image_size(options, 0.0f, width, height);
    description = orbit->description;
    try {
      return make_orbit_camera(framing ? *framing : world_bounds(world), orbit->azimuth, orbit->elevation,
                               options.fov_degrees, width, height);
    } catch (const error& e) {
      throw input_error(world.source, e.location(), e.reason());
    }
  }
  if (!options.camera.empty() || !world.cameras.empty()) {
    const camera& c = options.camera.empty() ? world.cameras.front() : select_camera(world, options.camera);
    // An orthographic camera's view is xmag by ymag, so that is the aspect of a size left open.
    float aspect = c.aspect_ratio;
    if (c.kind == projection::orthographic && c.xmag != 0.0f && c.ymag != 0.0f)
      aspect = std::abs(c.xmag / c.ymag);
    int width = 0, height = 0;
    resolve_image_size(options, aspect, width, height);
    description = c.name.empty() ? "glTF camera" : c.name;
    try {
      return make_gltf_camera(c, width, height);
    } catch (const error& e) {
      throw input_error(world.source, e.location(), e.reason());
    }
  }
  int width = 0, height = 0;
  resolve_image_size(options, 0.0f, width, height);
  description = "default";
  try {
    return make_default_camera(framing ? *framing : world_bounds(world), width, height);
  } catch (const error& e) {
    throw input_error(world.source, e.location(), e.reason());
  }
}

namespace {

// "gaussian 1.5" (the filter and its radius), or "threshold 0.1, depth 2" for adaptive sampling.
std::string sampling_description(const render_settings& s, bool adaptive) {
  std::ostringstream out;
  if (adaptive)
    out << "threshold " << s.adaptive.threshold << ", depth " << s.adaptive.max_depth;
  else
    out << filter_name(s.filter.kind) << ' ' << s.filter.radius;
  return out.str();
}

}  // namespace

pixel_rect job_region(const render_options& options, const view_camera& cam) {
  if (options.crop) {
    const pixel_rect& c = *options.crop;
    if (c.x1 > cam.width || c.y1 > cam.height)
      throw input_error("", "--crop",
                        "the region must lie inside the " + std::to_string(cam.width) + "x" +
                            std::to_string(cam.height) + " image");
    return c;
  }
  if (options.band_count > 0) {
    if (options.band_count > cam.height)
      throw input_error("", "--band",
                        "cannot split " + std::to_string(cam.height) + " rows into " +
                            std::to_string(options.band_count) + " bands");
    return frame_band(options.band_index, options.band_count, cam.width, cam.height);
  }
  return {};
}

exr_metadata job_metadata(const render_options& options, const prepared_scene& prepared,
                          const render_settings& settings, const render_statistics& stats,
                          const render_fingerprint& fingerprint, const cryptomatte_layer& objects,
                          const cryptomatte_layer& materials) {
  exr_metadata metadata;
  const view_camera world_view = world_space_view(prepared.cam, prepared.world);
  metadata.world_to_camera = world_to_camera(world_view);
  metadata.world_to_ndc = world_to_ndc(world_view);
  metadata.attributes = recorded_option_attributes(options);
  // The shot's rate and first frame even when not given (their defaults): what a frame number means.
  if (!options.fps) metadata.attributes.emplace_back("kiln/fps", 24.0);
  if (!options.frame_start) metadata.attributes.emplace_back("kiln/frame_start", 1);
  const bool adaptive = settings.adaptive.threshold > 0.0f;
  const std::vector<std::pair<std::string, exr_value>> resolved = {
      {"kiln/scene_file", options.input},
      {"kiln/camera", prepared.camera_description},
      {"kiln/lighting", prepared.lighting},
      {"kiln/filter", sampling_description(settings, false)},
      {"kiln/adaptive", adaptive ? sampling_description(settings, true) : "off"},
      {"kiln/depth", options.aovs.depth_kind == depth_mode::planar ? "planar depth" : "ray distance"},
      {"kiln/render_seconds", float(stats.seconds)},
      // A double: a count can pass an int's 2^31, and a double holds every count to 2^53 exactly.
      {"kiln/discarded_samples", double(stats.discarded_samples)},
      {"kiln/command_line", options.command_line},
      {"kiln/scene_hash", fingerprint.scene_hash},
      {"kiln/input_hash", fingerprint.input_hash},
      {"kiln/settings_hash", fingerprint.settings_hash},
      {"kiln/frame_settings_hash", fingerprint.frame_settings_hash},
  };
  metadata.attributes.insert(metadata.attributes.end(), resolved.begin(), resolved.end());
  if (options.time || options.frame)
    metadata.attributes.emplace_back("kiln/time_seconds", scene_time(options));
  if (options.frame)
    metadata.shot =
        exr_shot_frame{options.fps.value_or(24.0), *options.frame - options.frame_start.value_or(1)};
  for (const auto* layer : {options.aovs.has(aov::crypto_object) ? &objects : nullptr,
                            options.aovs.has(aov::crypto_material) ? &materials : nullptr})
    if (layer)
      for (auto& [name, value] : cryptomatte_attributes(*layer))
        metadata.attributes.emplace_back(name, value);
  if (prepared.colour.converts()) {
    // OpenImageIO reads oiio:ColorSpace from an EXR as the image's colour space; colorspace is the
    // name other tools (and the issue) ask for. Both hold the config's name for the space.
    metadata.attributes.emplace_back("colorspace", prepared.colour.name);
    metadata.attributes.emplace_back("oiio:ColorSpace", prepared.colour.name);
    metadata.attributes.emplace_back("kiln/ocio_config_file", prepared.colour.config);  // whichever named it
    for (size_t i = 0; i < 8; ++i) metadata.chromaticities[i] = float(prepared.colour.primaries.xy[i]);
  }
  metadata.attributes.emplace_back("renderTimeSeconds", float(stats.seconds));
  if (options.shutter) {
    // ImfStandardAttributes' expTime: how long the shutter is open, in seconds.
    const double open_frames = options.shutter->second - options.shutter->first;
    metadata.attributes.emplace_back("expTime", float(open_frames * motion_frame_seconds(options)));
    const size_t steps = std::max<size_t>(prepared.world.shutter.steps, prepared.camera_steps.size());
    metadata.attributes.emplace_back("kiln/shutter_steps", int(steps));
  }
  metadata.attributes.emplace_back("samplesPerPixel", samples_per_pixel_of(options));
  return metadata;
}

// An allocation that failed although the estimates fit the budget: the budget is more than the
// process may really use (a ulimit, other processes), or an estimate fell short.
error out_of_memory(const render_options& options, const std::string& stage) {
  return error(error_kind::render, options.input, "",
               "out of memory while " + stage + " (an allocation failed within the memory budget of " +
                   memory_text(job_memory_limit(options)) +
                   "; give --max-memory what the job may really use, and such files are refused instead)");
}

void throw_if_cancelled(const std::atomic<bool>* cancel, const std::string& output) {
  if (cancel && cancel->load())
    throw error(error_kind::interrupted, output, "", "render interrupted, nothing written");
}

double scene_time(const render_options& options) {
  // A held turntable's frame turns the camera only; the asset keeps the pose at --time.
  if (turntable_holds_pose(options)) return options.time.value_or(0.0);
  if (options.time && options.frame)
    throw input_error("", "--time", "--time and --frame both choose the time; give one of them");
  if (!options.frame && (options.fps || options.frame_start))
    throw input_error("", options.fps ? "--fps" : "--frame-start", "only applies to --frame; give --frame N");
  if (options.time) return *options.time;
  if (!options.frame) return 0.0;
  return double(*options.frame - options.frame_start.value_or(1)) / options.fps.value_or(24.0);
}

gltf_load_options job_load_options(const render_options& options, const std::atomic<bool>* cancel,
                                   memory_budget* memory) {
  gltf_load_options load_options;
  load_options.in_memory = options.in_memory;
  load_options.scene_index = options.scene_index;
  load_options.allow_files_outside_folder = options.allow_outside_files;
  load_options.limits = options.limits;
  load_options.cancel = cancel;            // a signal stops the reading of large files
  load_options.threads = options.threads;  // images decode on the render's threads
  load_options.memory = memory;
  load_options.time = scene_time(options);
  load_options.animation = options.animation.value_or("");
  load_options.variant = options.variant.value_or("");
  return load_options;
}

void finish_loaded_scene(const render_options& options, prepared_scene& p,
                         const std::function<void(const std::string&)>& warn, image* environment_map,
                         const std::vector<uint32_t>* posed_meshes) {
  p.world.env.color = options.background.value_or(vec3(0.0f));
  const std::string environment_file = job_environment_file(options);
  if (!environment_file.empty()) {
    p.world.images.push_back(environment_map ? std::move(*environment_map)
                                             : read_environment_image(environment_file));
    p.world.env.map_image = int32_t(p.world.images.size() - 1);
    p.world.env.rotation = float(glm::radians(options.environment_rotation_degrees));
    p.world.env.intensity = options.environment_intensity;
  }
  // Once the environment map is in: every colour the file and options give is linear Rec.709.
  colour_conversion_scope scope;
  scope.carried_over = p.colours_converted;
  scope.posed_meshes = posed_meshes;
  scope.allow_image_copies = posed_meshes == nullptr;  // not in a sequence
  apply_working_space(p.world, p.colour, p.memory.get(), scope);
  p.colours_converted = true;
  if (warn) {
    for (const std::string& warning : p.world.stats.warnings) warn("warning: " + warning);
    if (size_t dropped = p.world.stats.degenerate_triangles_dropped)
      warn("warning: dropped " + std::to_string(dropped) + " degenerate triangle" +
           (dropped == 1 ? "" : "s") + " (repeated vertices or zero area)");
  }
  p.world.stats.warnings.clear();  // given: the next frame's pose would carry them on

  apply_holdouts(p.world, options.holdout, options.only,
                 others_kind(options.others, options.holdout_invisible, options.deep));
  p.cam = job_view(options, p.world, p.camera_description, p.framing ? &*p.framing : nullptr);
  // Before any accelerator is built, for every backend and every client (render, batch, compare,
  // bench): no coordinate a ray can reach may pass Embree's limit.
  if (options.look_from)
    check_view_range(p.world, p.cam, "", "--look-from");
  else
    check_view_range(p.world, p.cam, p.world.source, "camera " + quoted(p.camera_description));
  // Notes about the lighting are given once per sequence.
  p.lighting = apply_lighting(options, p.world, p.cam, p.headlight_noted ? nullptr : warn);
  p.headlight_noted = true;
  // The frame's own pose for motion vectors, in world space like its neighbours'.
  if (p.motion) {
    p.motion->current = current_pose(p.world, p.cam);
    if (p.motion->previous.present.empty()) p.motion->previous = p.motion->next = p.motion->current;
  }
  // Every client traces in camera-relative render space (render/render_space.h).
  move_to_render_space(p.world, p.cam);
  for (view_camera& step : p.camera_steps) step.eye -= p.world.render_origin;
}

prepared_scene prepare_scene(const render_options& options, const std::atomic<bool>* cancel,
                             const std::function<void(const std::string&)>& warn) {
  check_asset_file(options.input);
  prepared_scene p;
  p.memory = std::make_shared<memory_budget>(job_memory_limit(options));
  p.colour = resolve_working_space(options);            // a bad config or space fails before the asset loads
  if (!options.preview.empty()) preview_view(options);  // and so does a bad display or view
  const auto load_start = std::chrono::steady_clock::now();
  gltf_sequence asset(options.input, job_load_options(options, cancel, p.memory.get()));
  pose_job_frame(asset, options, nullptr, nullptr, p);
  p.load_seconds = seconds_since(load_start);
  finish_loaded_scene(options, p, warn);
  return p;
}

render_settings make_render_settings(const render_options& options) {
  render_settings settings;
  settings.samples_per_pixel = samples_per_pixel_of(options);
  settings.random_samples = options.sampler == "random";
  settings.filter.kind = parse_filter_kind(options.filter).value_or(filter_kind::box);
  settings.filter.radius = options.filter_radius.value_or(default_filter_radius(settings.filter.kind));
  settings.adaptive.threshold = options.adaptive_threshold;
  settings.adaptive.max_depth = options.adaptive_depth;
  // Adaptive sampling places its own samples and averages them over the pixel's square.
  if (options.adaptive_threshold > 0.0f && options.spp_given > 1)
    throw input_error("", "--adaptive-threshold", "adaptive supersampling replaces --spp; give one of them");
  if (options.adaptive_threshold > 0.0f && (options.filter != "box" || options.filter_radius))
    throw input_error("", "--adaptive-threshold",
                      "adaptive supersampling averages over the pixel; drop --filter");
  if (options.shutter && options.adaptive_threshold > 0.0f)
    throw input_error(
        "", "--shutter",
        "motion blur needs --spp sampling: adaptive supersampling traces its corners at one time");
  settings.motion_blur = options.shutter.has_value();
  settings.threads = options.threads;
  settings.tile_size = options.tile_size;
  settings.show_background = options.show_background;
  settings.shading.transmission_transparent = options.transmission_alpha == "transparent";
  settings.shading.max_depth = options.max_depth;
  settings.shading.min_throughput = options.min_throughput;
  settings.shading.max_rays_per_sample = options.max_rays_per_sample;
  settings.shading.environment_samples = options.environment_samples;
  settings.packets = options.packets;
  settings.reference_shading = options.shading == "reference";
  settings.aovs = options.aovs;
  return settings;
}

std::unique_ptr<accelerator> make_job_accelerator(const scene& world, const render_options& options) {
  return make_accelerator(world, *parse_accel_kind(options.accel), options.grid, options.embree);
}

void check_job(const render_options& options, const shared_output_checks* shared) {
  if (!options.frames.empty() || (options.turntable > 0 && !options.frame))
    throw input_error(
        "", options.frames.empty() ? "--turntable" : "--frames",
        "a job renders one frame; a sequence runs through run_sequence (kiln render --frames or "
        "--turntable, kiln.render_sequence)");
  check_asset_file(options.input);  // before the fingerprint reads it
  scene_time(options);
  check_turntable_frame(options);  // and --camera-view's options
  check_look_at_pair(options);
  if (options.crop && options.band_count > 0)
    throw input_error("", "--crop", "--crop and --band both choose the region; give one of them");
  // Both sides given: the size is known before the scene loads, so a huge one fails at once.
  if (options.width && options.height) check_pixel_count(*options.width, *options.height, options.max_pixels);
  check_no_nul(options.output, "-o");
  check_no_nul(options.preview, "--preview");
  if (!options.output.empty()) {
    check_render_outputs(options, shared);  // never a file the render reads, never through a symlink
    check_output_writable(options.output, !shared || !shared->folders_probed);
  }
  resolve_exr_settings(options);
  if (!options.preview.empty()) check_output_writable(options.preview, !shared || !shared->folders_probed);
  check_deep_job(options, shared);
}

std::vector<std::string> job_option_warnings(const render_options& options) {
  std::vector<std::string> lines;
  // The preview is written beside the EXR (a Python call without output= writes neither).
  if (!options.preview.empty() && options.output.empty())
    lines.push_back("warning: --preview does nothing without an output (output=; Result.write writes both)");
  // The display and view choose the preview's transform only; the EXR stays scene-linear.
  if (!options.preview.empty()) return lines;
  if (!options.display.empty()) lines.push_back("warning: --display does nothing without --preview");
  if (!options.view.empty()) lines.push_back("warning: --view does nothing without --preview");
  return lines;
}

uint64_t job_memory_limit(const render_options& options) {
  return options.max_memory ? options.max_memory : default_memory_budget();
}

void charge_render_memory(const prepared_scene& prepared, const render_settings& settings,
                          memory_charge& held) {
  const std::string& file = prepared.world.source;
  pixel_rect region = settings.crop;
  if (region.width() <= 0) region = {0, 0, prepared.cam.width, prepared.cam.height};
  held.add(texture_filter_bytes(prepared.world), file, "the textures' mip pyramids");
  held.add(environment_light_bytes(prepared.world), file, "the environment's sampling tables");
  held.add(accelerator_bytes(prepared.world), file, "the acceleration structures");
  held.add(film_and_output_bytes(region, settings.aovs, light_group_count(prepared.world)), file,
           "the film and AOV buffers");
}

std::shared_ptr<deep_output> attach_deep_output(const render_options& options, const prepared_scene& prepared,
                                                render_settings& settings) {
  if (!options.deep) return nullptr;
  auto deep = std::make_shared<deep_output>(prepared.memory);
  settings.deep = &deep->image;
  settings.deep_memory = &deep->charge;
  return deep;
}

render_job_result run_job(const render_job& job) {
  check_job(job.options);
  // Loaded and rendered once, as a kept scene renders: one time limit for both.
  return run_stoppable(job, job.options, [&job](const std::atomic<bool>* stop, const char*& stage) {
    loaded_scene loaded(job, job.options, stop, stage);
    return loaded.render(job, job.options, stop, stage, nullptr);
  });
}

void write_job_outputs(const render_job_result& result, const render_options& options,
                       const std::atomic<bool>* cancel) {
  try {
    if (result.deep)
      write_deep_exr(deep_output_path(options.output), result.deep->image, result.metadata, cancel);
  } catch (const std::bad_alloc&) {
    throw out_of_memory(options, "writing the deep EXR");
  }
  try {
    write_exr(options.output, result.image, result.storage, result.metadata, cancel);
  } catch (const std::bad_alloc&) {
    throw out_of_memory(options, "writing the EXR");
  }
  // The beauty exactly as the EXR holds it: from memory under a lossless codec, else read back.
  try {
    if (!options.preview.empty()) {
      const std::optional<display_transform> view = preview_view(options);
      const display_transform* transform = view ? &*view : nullptr;
      if (const std::optional<rgba_image> beauty = stored_beauty(result.image, result.storage))
        write_preview(*beauty, options.preview, options.preview_exposure, transform, cancel);
      else
        write_preview(options.output, options.preview, options.preview_exposure, transform, cancel);
    }
  } catch (const std::bad_alloc&) {
    throw out_of_memory(options, "writing the preview");
  }
}

}  // namespace kiln
