#include "app/render_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "accel/make_accelerator.h"
#include "app/asset_file.h"
#include "app/cli_checks.h"
#include "app/exr_options.h"
#include "app/interrupt.h"
#include "app/output_lock.h"
#include "app/progress_report.h"
#include "app/output_guard.h"
#include "app/render_fingerprint.h"
#include "core/error.h"
#include "io/exr/cryptomatte.h"
#include "io/exr/environment_reader.h"
#include "io/exr/exr_writer.h"
#include "io/exr/preview_writer.h"
#include "io/gltf/gltf_loader.h"
#include "render/frame_bands.h"
#include "render/render_space.h"
#include "render/tile_renderer.h"
#include "render/view_camera.h"
#include "render/view_range.h"

namespace kiln {

namespace {

constexpr int default_width = 640;
constexpr int default_height = 480;
constexpr int max_image_side = 65536;
// Bounds of the --grid-* options: beyond them a grid's memory explodes (256³ cells per grid, 8^depth
// children per crowded cell) long before traversal gets faster.
constexpr int max_grid_resolution = 256;
constexpr int max_grid_depth = 6;

// Parses "X,Y,Z" into three finite numbers; CLI11 reports a ValidationError as a usage error.
dvec3 parse_triple(const std::string& text, const std::string& option) {
  dvec3 value;
  std::istringstream in(text);
  char comma1 = 0, comma2 = 0;
  if (!(in >> value.x >> comma1 >> value.y >> comma2 >> value.z) || comma1 != ',' || comma2 != ',' ||
      !(in >> std::ws).eof() || !is_finite(value))
    throw CLI::ValidationError(option, "expects three finite numbers X,Y,Z, got '" + text + "'");
  return value;
}

// Parses "N" (N cells on every axis) or "X,Y,Z" for --grid-resolution.
glm::ivec3 parse_grid_resolution(const std::string& text) {
  std::istringstream in(text);
  glm::ivec3 r;
  char comma1 = 0, comma2 = 0;
  bool ok = bool(in >> r.x);
  if (ok && (in >> std::ws).eof()) {
    r = glm::ivec3(r.x);
  } else {
    in.clear();
    ok = ok && (in >> comma1 >> r.y >> comma2 >> r.z) && comma1 == ',' && comma2 == ',' &&
         (in >> std::ws).eof();
  }
  if (!ok || glm::any(glm::lessThan(r, glm::ivec3(1))) ||
      glm::any(glm::greaterThan(r, glm::ivec3(max_grid_resolution))))
    throw CLI::ValidationError("--grid-resolution", "expects N or X,Y,Z cells per axis, each 1 to " +
                                                        std::to_string(max_grid_resolution) + ", got '" +
                                                        text + "'");
  return r;
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
    names += (names.empty() ? "" : ", ") + ("'" + c.name + "'");
  }
  throw input_error(world.source, "--camera", "no camera named '" + which + "' (cameras: " + names + ")");
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

view_camera choose_view(const render_options& options, const scene& world, std::string& description) {
  if (options.look_from || options.look_at) {
    if (!options.look_from || !options.look_at)
      throw input_error("", "--look-from/--look-at", "give both --look-from and --look-at");
    int width = 0, height = 0;
    resolve_image_size(options, 0.0f, width, height);
    description = "look-at";
    return make_look_at_camera(*options.look_from, *options.look_at, options.up, options.fov_degrees, width,
                               height);
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
  return make_default_camera(world_bounds(world), width, height);
}

// When a file has no light, a point light at the camera (a headlight) keeps assets visible: its
// intensity is chosen so a white surface facing it at the scene centre reflects radiance ≈ 1.
void add_default_light(scene& world, const view_camera& cam) {
  bounds3 b = world_bounds(world);
  double distance = b.empty() ? 1.0 : std::max(glm::length(b.center() - cam.eye), 1e-6);
  light headlight;
  headlight.name = "kiln default headlight";
  headlight.kind = light_kind::point;
  headlight.position = cam.eye;
  headlight.intensity = float(pi * distance * distance);
  headlight.casts_shadows = false;
  world.lights.push_back(headlight);
}

std::string format_vec(const vec3& v) {
  std::ostringstream out;
  out << v.x << ',' << v.y << ',' << v.z;
  return out.str();
}

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

void add_view_options(CLI::App& app, render_options& o) {
  app.add_option("asset", o.input, "glTF 2.0 asset to render (.gltf or .glb)")->required();
  add_view_settings(app, o);
}

void add_view_settings(CLI::App& app, render_options& o) {
  app.add_option("--width", o.width,
                 "Image width in pixels (default 640, or from --height and the camera's aspect)")
      ->check(CLI::Range(1, max_image_side));
  app.add_option("--height", o.height,
                 "Image height in pixels (default 480, or from the camera's aspect ratio)")
      ->check(CLI::Range(1, max_image_side));
  app.add_option("--spp", o.samples_per_pixel,
                 "Samples per pixel, stratified and jittered (1 = pixel centre)")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  app.add_option("--sampler", o.sampler,
                 "Sample positions inside a pixel: jittered strata, or independent uniform samples (the "
                 "baseline stratification is measured against)")
      ->check(CLI::IsMember({"stratified", "random"}))
      ->capture_default_str();
  app.add_option(
         "--filter", o.filter,
         "Reconstruction filter for the stratified samples (default radius: box 0.5, tent 1, gaussian "
         "1.5 with sigma radius/3, blackman-harris 2)")
      ->check(CLI::IsMember({"box", "tent", "gaussian", "blackman-harris"}))
      ->capture_default_str();
  app.add_option_function<float>(
      "--filter-radius",
      [&o](float r) {
        if (!(r > 0.0f && r <= 16.0f))
          throw CLI::ValidationError("--filter-radius", "must be in (0, 16] pixels");
        o.filter_radius = r;
      },
      "Filter radius in pixels, in (0, 16] (default: the filter's own)");
  app.add_option(
         "--adaptive-threshold", o.adaptive_threshold,
         "Whitted's adaptive supersampling: split a pixel square while its corners differ by more than T "
         "in R, G, B or A, or hit different instances (0 = off; replaces --spp and --filter)")
      ->check(CLI::Range(0.0f, 1e9f))
      ->capture_default_str();
  app.add_option("--adaptive-depth", o.adaptive_depth, "Adaptive supersampling: most splits per pixel")
      ->check(CLI::Range(0, max_adaptive_depth))
      ->capture_default_str();
  app.add_option("--threads", o.threads, "Render threads (0 = all cores)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  app.add_option("--tile-size", o.tile_size, "Tile side in pixels")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  app.add_option("--camera", o.camera,
                 "glTF camera by name or index (default: the first camera in the file)");
  app.add_option_function<std::string>(
      "--look-from", [&o](const std::string& s) { o.look_from = parse_triple(s, "--look-from"); },
      "Look-at camera position X,Y,Z (overrides --camera; needs --look-at)");
  app.add_option_function<std::string>(
      "--look-at", [&o](const std::string& s) { o.look_at = parse_triple(s, "--look-at"); },
      "Look-at camera target X,Y,Z");
  app.add_option_function<std::string>(
      "--up", [&o](const std::string& s) { o.up = parse_triple(s, "--up"); },
      "Look-at camera up vector X,Y,Z (default 0,1,0)");
  app.add_option("--fov", o.fov_degrees, "Look-at camera vertical field of view in degrees")
      ->check(finite_number())
      ->check(CLI::Range(1e-3, 179.999))
      ->capture_default_str();
  app.add_option("--scene", o.scene_index, "glTF scene index (default: the file's default scene)")
      ->check(CLI::NonNegativeNumber);
  app.add_option_function<std::string>(
      "--background",
      [&o](const std::string& s) {
        dvec3 c = parse_triple(s, "--background");
        if (c.x < 0 || c.y < 0 || c.z < 0)
          throw CLI::ValidationError("--background", "colour must be non-negative");
        o.background = vec3(c);
      },
      "Environment colour R,G,B (linear), seen by reflections (default 0,0,0)");
  app.add_option(
         "--environment", o.environment,
         "Equirectangular environment map (EXR, HDR, ...; linear radiance) seen by rays that leave the scene")
      ->check(CLI::ExistingFile);
  app.add_option("--environment-rotation", o.environment_rotation_degrees,
                 "Turn the environment map about +Y by DEG degrees (counter-clockwise seen from above)")
      ->check(finite_number())
      ->check(CLI::Range(-36000.0, 36000.0))
      ->capture_default_str();
  app.add_option("--environment-intensity", o.environment_intensity,
                 "Scale of the environment map's radiance")
      ->check(finite_number())
      ->check(CLI::Range(0.0f, 1e9f))
      ->capture_default_str();
  app.add_flag(
      "--show-background", o.show_background,
      "Camera rays that miss see the environment colour with alpha 1 (default: transparent, alpha 0)");
  app.add_option("--transmission-alpha", o.transmission_alpha,
                 "What glass contributes to alpha: opaque (it holds out, what it shows is baked in) or "
                 "transparent (refraction reaching a background the camera does not show is transparent)")
      ->check(CLI::IsMember({"opaque", "transparent"}))
      ->capture_default_str();
  app.add_option("--max-depth", o.max_depth, "Maximum reflection depth")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  app.add_option("--min-throughput", o.min_throughput, "Reflections weighted below this are not traced")
      ->check(finite_number())
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--texture-cache-mb", o.texture_cache_mb, "No effect (texture pyramids are kept in memory); accepted so existing command lines keep working")
      ->check(CLI::Range(1.0f, 1e6f))
      ->capture_default_str();
  app.add_flag(
      "--allow-outside-files", o.allow_outside_files,
      "Let buffer and image URIs name files outside the asset's folder ('..' escapes, symlinks that lead "
      "out); absolute paths and URLs stay refused");
  app.add_option("--max-json-bytes", o.max_json_bytes, "Refuse glTF JSON larger than this (bytes)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-json-depth", o.max_json_depth, "Refuse glTF JSON nested deeper than this")
      ->check(CLI::Range(size_t(1), size_t(100000)))
      ->capture_default_str();
  app.add_option("--max-nodes", o.max_nodes, "Refuse glTF files with more nodes than this")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option(
         "--max-instances", o.max_instances,
         "Refuse glTF files whose EXT_mesh_gpu_instancing takes the scene past this many mesh instances")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  // A function, not CLI::Range: Range lets NaN through (every comparison with it is false).
  app.add_option_function<double>(
      "--grid-density",
      [&o](double density) {
        if (!(density >= 1e-3 && density <= 1e3))
          throw CLI::ValidationError("--grid-density", "expects a number from 0.001 to 1000");
        o.grid.density = density;
      },
      "Grid backends: aim for density x N cells for N items (the resolution heuristic; default 2)");
  app.add_option_function<std::string>(
      "--grid-resolution", [&o](const std::string& s) { o.grid.resolution = parse_grid_resolution(s); },
      "Grid backends: N or X,Y,Z cells per axis for every grid, instead of the heuristic");
  app.add_option("--grid-max-items", o.grid.max_items_per_cell,
                 "Adaptive grid: a cell holding more items than this is subdivided")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  app.add_option("--grid-max-depth", o.grid.max_depth,
                 "Adaptive grid: levels of subdivision below the top grid")
      ->check(CLI::Range(0, max_grid_depth))
      ->capture_default_str();
  app.add_option("--max-texels", o.max_texels,
                 "Refuse glTF images declaring more texels than this (width x height), before decoding")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-pixels", o.max_pixels, "Refuse images with more pixels than this (width x height)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option_function<std::string>(
         "--bvh-quality",
         [&o](const std::string& name) { o.embree.quality = *parse_bvh_quality(name); },
         "Embree BVH build quality: low, medium or high (default medium)")
      ->check(CLI::IsMember({"low", "medium", "high"}));
  app.add_flag("--bvh-compact", o.embree.compact, "Embree: compact BVH layout (less memory, slower rays)");
  app.add_option_function<std::string>(
         "--packets", [&o](const std::string& v) { o.packets = v == "on"; },
         "Trace each tile's camera rays together as Embree packets: on or off (default off)")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_flag("-q,--quiet", o.quiet, "No progress line or summary");
}

void add_render_options(CLI::App& app, render_options& o) {
  add_view_options(app, o);
  app.add_option("-o,--output", o.output, "Output OpenEXR file")->required();
  add_image_options(app, o);
  add_progress_interval_option(app, o);
  // Internal: kiln batch runs each job as `kiln render ... --batch-command-line LINE` in a child
  // process; LINE is the job's own command line for the EXR header. Hidden from --help.
  app.add_option_function<std::string>(
         "--batch-command-line",
         [&o](const std::string& line) {
           o.command_line = line;
           o.batch_job = true;
           o.summary_line = false;  // the batch prints its own line per job
         },
         "")
      ->group("");
}

void add_progress_interval_option(CLI::App& app, render_options& o) {
  app.add_option("--progress-interval", o.progress_interval,
                 "Seconds between progress lines when stderr is not a terminal (a log or a pipe)")
      ->check(CLI::Range(0.01, 86400.0))
      ->capture_default_str();
}

void add_image_options(CLI::App& app, render_options& o) {
  add_exr_options(app, o);
  app.add_option_function<std::string>(
      "--aovs",
      [&o](const std::string& text) {
        std::string bad;
        std::optional<aov_set> aovs = parse_aov_list(text, &bad);
        if (!aovs)
          throw CLI::ValidationError("--aovs",
                                     "unknown or repeated output " + bad +
                                         " (choose from beauty, Z, N, P, albedo, uv, id, crypto_object, "
                                         "crypto_material, cryptomatte, direct, reflection, refraction)");
        // The other options fill in fields of the same set, whichever order they come in.
        aovs->crypto_depth = o.aovs.crypto_depth;
        aovs->depth_kind = o.aovs.depth_kind;
        o.aovs = *aovs;
      },
      "Comma-separated outputs to write: beauty (R G B A), Z, N, P (world position), albedo, uv, id "
      "(id.object, id.material, id.instance), crypto_object and crypto_material (Cryptomatte of the node "
      "and material names; cryptomatte for both), direct, reflection and refraction (the beauty split by "
      "first event) (default beauty,Z,N)");
  app.add_option_function<int>(
         "--cryptomatte-depth", [&o](int depth) { o.aovs.crypto_depth = depth; },
         "Cryptomatte ranks (id and coverage pairs) per pixel, two per RGBA channel set (default 6)")
      ->check(CLI::Range(1, max_cryptomatte_depth));
  app.add_option_function<std::string>(
         "--depth-mode", [&o](const std::string& mode) { o.aovs.depth_kind = *parse_depth_mode(mode); },
         "What Z holds: distance (along the ray from the camera, the default) or planar (along the view "
         "axis)")
      ->check(CLI::IsMember({"distance", "planar"}));
  CLI::Option* crop = app.add_option_function<std::string>(
      "--crop",
      [&o](const std::string& text) {
        std::istringstream in(text);
        pixel_rect r;
        char c1 = 0, c2 = 0, c3 = 0;
        if (!(in >> r.x0 >> c1 >> r.y0 >> c2 >> r.x1 >> c3 >> r.y1) || c1 != ',' || c2 != ',' || c3 != ',' ||
            !(in >> std::ws).eof() || r.x0 < 0 || r.y0 < 0 || r.x1 <= r.x0 || r.y1 <= r.y0)
          throw CLI::ValidationError(
              "--crop", "expects pixels x0,y0,x1,y1 with 0 <= x0 < x1 and 0 <= y0 < y1, got '" + text + "'");
        o.crop = r;
      },
      "Render and store only pixels [x0, x1) x [y0, y1) (EXR data window; the display window stays the "
      "full frame)");
  app.add_option_function<std::string>(
         "--tile",
         [&o](const std::string& text) {
           std::istringstream in(text);
           char slash = 0;
           int index = -1, count = 0;
           if (!(in >> index >> slash >> count) || slash != '/' || !(in >> std::ws).eof() || count < 1 ||
               index < 0 || index >= count)
             throw CLI::ValidationError("--tile",
                                        "expects i/N with N >= 1 and 0 <= i < N, got '" + text + "'");
           o.tile_index = index;
           o.tile_count = count;
         },
         "Render band i (0-based) of N horizontal bands of whole rows, as a crop (band i holds rows "
         "[floor(i*H/N), floor((i+1)*H/N)); join the files with kiln stitch)")
      ->excludes(crop);
  app.add_option("--accel", o.accel, "Traversal backend")
      ->check(CLI::IsMember({"embree", "grid", "adaptive-grid"}))
      ->capture_default_str();
}

prepared_scene prepare_scene(const render_options& options) {
  check_asset_file(options.input);
  prepared_scene p;
  auto load_start = std::chrono::steady_clock::now();
  gltf_load_options load_options;
  load_options.scene_index = options.scene_index;
  load_options.allow_files_outside_folder = options.allow_outside_files;
  load_options.limits.max_json_bytes = options.max_json_bytes;
  load_options.limits.max_json_depth = options.max_json_depth;
  load_options.limits.max_nodes = options.max_nodes;
  load_options.limits.max_instances = options.max_instances;
  load_options.limits.max_texels = options.max_texels;
  load_options.cancel = &interrupt_requested();  // SIGINT/SIGTERM stop the reading of large files
  load_options.threads = options.threads;        // images decode on the render's threads
  p.world = load_gltf(options.input, load_options);
  p.world.env.color = options.background;
  if (!options.environment.empty()) {
    p.world.images.push_back(read_environment_image(options.environment));
    p.world.env.map_image = int32_t(p.world.images.size() - 1);
    p.world.env.rotation = float(glm::radians(options.environment_rotation_degrees));
    p.world.env.intensity = options.environment_intensity;
  }
  p.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  if (!options.quiet) {
    for (const std::string& warning : p.world.stats.warnings)
      std::cerr << "kiln: warning: " << warning << '\n';
    if (size_t dropped = p.world.stats.degenerate_triangles_dropped)
      std::cerr << "kiln: warning: dropped " << dropped << " degenerate triangle" << (dropped == 1 ? "" : "s")
                << " (repeated vertices or zero area)\n";
  }

  p.cam = choose_view(options, p.world, p.camera_description);
  // Before any accelerator is built, for every backend and every client (render, batch, compare,
  // bench): no coordinate a ray can reach may pass Embree's limit.
  if (options.look_from)
    check_view_range(p.world, p.cam, "", "--look-from");
  else
    check_view_range(p.world, p.cam, p.world.source, "camera '" + p.camera_description + "'");
  if (p.world.lights.empty()) {
    add_default_light(p.world, p.cam);
    if (!options.quiet) std::cerr << "kiln: the file has no lights; using a headlight at the camera\n";
  }
  // Every client traces in camera-relative render space (render/render_space.h).
  move_to_render_space(p.world, p.cam);
  return p;
}

render_settings make_render_settings(const render_options& options) {
  render_settings settings;
  settings.samples_per_pixel = options.samples_per_pixel;
  settings.random_samples = options.sampler == "random";
  settings.filter.kind = parse_filter_kind(options.filter).value_or(filter_kind::box);
  settings.filter.radius = options.filter_radius.value_or(default_filter_radius(settings.filter.kind));
  settings.adaptive.threshold = options.adaptive_threshold;
  settings.adaptive.max_depth = options.adaptive_depth;
  // Adaptive sampling places its own samples and averages them over the pixel's square.
  if (options.adaptive_threshold > 0.0f && options.samples_per_pixel != 1)
    throw input_error("", "--adaptive-threshold", "adaptive supersampling replaces --spp; give one of them");
  if (options.adaptive_threshold > 0.0f && (options.filter != "box" || options.filter_radius))
    throw input_error("", "--adaptive-threshold",
                      "adaptive supersampling averages over the pixel; drop --filter");
  settings.threads = options.threads;
  settings.tile_size = options.tile_size;
  settings.show_background = options.show_background;
  settings.shading.transmission_transparent = options.transmission_alpha == "transparent";
  settings.shading.max_depth = options.max_depth;
  settings.shading.min_throughput = options.min_throughput;
  settings.packets = options.packets;
  settings.aovs = options.aovs;
  settings.cancel = &interrupt_requested();
  return settings;
}

void run_render(const render_options& options, const render_fingerprint* known) {
  check_asset_file(options.input);  // before the fingerprint reads it
  // A running batch owns its output folder; its own jobs (children) write there.
  if (!options.batch_job) {
    check_not_in_locked_folder(options.output);
    if (!options.preview.empty()) check_not_in_locked_folder(options.preview);
  }
  // Both sides given: the size is known before the scene loads, so a huge one fails at once.
  if (options.width && options.height) check_pixel_count(*options.width, *options.height, options.max_pixels);
  check_render_outputs(options);  // never a file the render reads, never through a symlink
  check_output_writable(options.output);
  const exr_settings storage = resolve_exr_settings(options);
  if (!options.preview.empty()) check_output_writable(options.preview);

  // Hashed before loading: an asset edited during the render then reads as stale next time.
  const render_fingerprint fingerprint = known ? *known : make_fingerprint(options);
  prepared_scene prepared = prepare_scene(options);
  const scene& world = prepared.world;
  const view_camera& cam = prepared.cam;
  const std::string& camera_description = prepared.camera_description;
  const double load_seconds = prepared.load_seconds;

  auto build_start = std::chrono::steady_clock::now();
  std::unique_ptr<accelerator> accel =
      make_accelerator(world, *parse_accel_kind(options.accel), options.grid, options.embree);
  double build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();

  render_settings settings = make_render_settings(options);
  const cryptomatte_layer objects = cryptomatte_objects(world);
  const cryptomatte_layer materials = cryptomatte_materials(world);
  settings.mattes = {objects.id_by_key, materials.id_by_key};
  if (options.crop) {
    const pixel_rect& c = *options.crop;
    if (c.x1 > cam.width || c.y1 > cam.height)
      throw input_error("", "--crop",
                        "the region must lie inside the " + std::to_string(cam.width) + "x" +
                            std::to_string(cam.height) + " image");
    settings.crop = c;
  }
  if (options.tile_count > 0) {
    if (options.tile_count > cam.height)
      throw input_error("", "--tile",
                        "cannot split " + std::to_string(cam.height) + " rows into " +
                            std::to_string(options.tile_count) + " bands");
    settings.crop = frame_band(options.tile_index, options.tile_count, cam.width, cam.height);
  }
  render_statistics stats;
  film image;
  render_progress progress;
  settings.progress = &progress;
  try {
    const progress_report report(progress, !options.quiet, options.progress_interval);
    image = render_image(world, *accel, cam, settings, &stats);
    accel->throw_if_failed();  // an error Embree reported during traversal fails the render
  } catch (const error& e) {
    if (e.kind() != error_kind::interrupted) throw;
    throw error(error_kind::interrupted, options.output, "", "render interrupted, nothing written");
  }

  exr_metadata metadata;
  metadata.world_to_camera = world_to_camera(world_space_view(cam, world));
  metadata.world_to_ndc = world_to_ndc(world_space_view(cam, world));
  metadata.attributes = {
      {"kiln/scene_file", options.input},
      {"kiln/camera", camera_description},
      {"kiln/accelerator", options.accel},
      {"kiln/bvh_quality", bvh_quality_name(options.embree.quality)},
      {"kiln/bvh_compact", options.embree.compact ? "on" : "off"},
      {"kiln/packets", options.packets ? "on" : "off"},
      {"kiln/samples_per_pixel", std::to_string(options.samples_per_pixel)},
      {"kiln/sampler", options.sampler},
      {"kiln/filter", sampling_description(settings, false)},
      {"kiln/adaptive", settings.adaptive.threshold > 0.0f ? sampling_description(settings, true) : "off"},
      {"kiln/max_depth", std::to_string(options.max_depth)},
      {"kiln/background", format_vec(options.background)},
      {"kiln/transmission_alpha", options.transmission_alpha},
      {"kiln/depth", options.aovs.depth_kind == depth_mode::planar ? "planar depth" : "ray distance"},
      {"kiln/render_seconds", std::to_string(stats.seconds)},
      {"kiln/discarded_samples", std::to_string(stats.discarded_samples)},
      {"kiln/command_line", options.command_line},
      {"kiln/aovs", aov_list_name(options.aovs)},
      {"kiln/scene_hash", file_hash_hex(options.input)},
      {"kiln/input_hash", fingerprint.input_hash},
      {"kiln/settings_hash", fingerprint.settings_hash},
      {"kiln/frame_settings_hash", fingerprint.frame_settings_hash},
  };
  for (const auto* layer :
       {options.aovs.crypto_object ? &objects : nullptr, options.aovs.crypto_material ? &materials : nullptr})
    if (layer)
      for (auto& attribute : cryptomatte_attributes(*layer))
        metadata.attributes.push_back(std::move(attribute));
  metadata.float_attributes = {{"renderTimeSeconds", float(stats.seconds)}};
  metadata.int_attributes = {{"samplesPerPixel", options.samples_per_pixel}};
  // A signal that arrives after the last pixel still stops the run before anything is written.
  if (interrupt_requested())
    throw error(error_kind::interrupted, options.output, "", "render interrupted, nothing written");
  write_exr(options.output, image, storage, metadata);
  // From the file as written, so the preview shows exactly what the EXR holds.
  if (!options.preview.empty()) write_preview(options.output, options.preview, options.preview_exposure);

  if (!options.quiet && options.summary_line) {
    const std::string sampling = settings.adaptive.threshold > 0.0f
                                     ? "adaptive " + sampling_description(settings, true)
                                     : std::to_string(options.samples_per_pixel) + " spp, " +
                                           sampling_description(settings, false) + " filter";
    std::fprintf(stderr,
                 "kiln: %dx%d, %s, %d threads: load %.3f s, build %.3f s, render %.3f s "
                 "(%llu camera, %llu shadow, %llu reflection, %llu refraction rays; %llu non-finite samples "
                 "discarded) -> %s\n",
                 cam.width, cam.height, sampling.c_str(), stats.threads_used, load_seconds, build_seconds,
                 stats.seconds, (unsigned long long)stats.rays.camera, (unsigned long long)stats.rays.shadow,
                 (unsigned long long)stats.rays.reflection, (unsigned long long)stats.rays.refraction,
                 (unsigned long long)stats.discarded_samples, options.output.c_str());
  }
}

}  // namespace kiln
