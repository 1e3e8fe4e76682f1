#include "job/option_table.h"

#include <sys/stat.h>

#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "io/exr/preview_codes.h"
#include "job/exr_storage_options.h"
#include "job/frame_range.h"
#include "job/option_values.h"
#include "render/adaptive_sampling.h"

namespace kiln {

namespace {

namespace fs = std::filesystem;

template <typename T>
using field = std::function<T&(render_options&)>;

// Reads a field through its accessor without a second, const accessor for every entry.
template <typename T>
const T& read(const render_options& o, const field<T>& at) {
  return at(const_cast<render_options&>(o));
}

std::string dashed(const std::string& name) { return "--" + name; }

constexpr int max_image_side = 65536;
// Bounds of the --grid-* options: beyond them a grid's memory explodes (256³ cells per grid, 8^depth
// children per crowded cell) long before traversal gets faster.
constexpr int max_grid_resolution = 256;
constexpr int max_grid_depth = 6;

template <typename T>
option_spec integer_option(const std::string& name, field<T> at, long long min, long long max,
                           const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::integer;
  s.help = help;
  s.example = example;
  s.set = [at, name, min, max](render_options& o, const std::string& text) {
    at(o) = T(parse_integer(text, dashed(name), min, max));
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return std::to_string(read(o, at)); };
  return s;
}

template <typename T>
option_spec unsigned_option(const std::string& name, field<T> at, unsigned long long min,
                            unsigned long long max, const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::unsigned_integer;
  s.help = help;
  s.example = example;
  s.set = [at, name, min, max](render_options& o, const std::string& text) {
    at(o) = T(parse_unsigned(text, dashed(name), min, max));
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return std::to_string(read(o, at)); };
  return s;
}

template <typename T>
option_spec number_option(const std::string& name, field<T> at, double min, double max,
                          const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::number;
  s.help = help;
  s.example = example;
  s.set = [at, name, min, max](render_options& o, const std::string& text) {
    at(o) = T(parse_number(text, dashed(name), min, max));
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return exact_text(read(o, at)); };
  return s;
}

option_spec choice_option(const std::string& name, field<std::string> at, std::vector<std::string> choices,
                          const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.help = help;
  s.example = example;
  s.choices = choices;
  s.set = [at, name, choices](render_options& o, const std::string& text) {
    check_choice(text, dashed(name), choices);
    at(o) = text;
  };
  s.get = [at](const render_options& o) -> std::optional<std::string> { return read(o, at); };
  return s;
}

option_spec flag_option(const std::string& name, field<bool> at, const std::string& help) {
  option_spec s;
  s.name = name;
  s.type = option_type::flag;
  s.help = help;
  s.example = "true";
  s.set = [at, name](render_options& o, const std::string& text) { at(o) = parse_flag(text, dashed(name)); };
  s.get = [at](const render_options& o) -> std::optional<std::string> {
    return std::string(read(o, at) ? "true" : "false");
  };
  return s;
}

// A text option with its own parser and printer.
option_spec custom_option(const std::string& name,
                          std::function<void(render_options&, const std::string&)> set,
                          std::function<std::optional<std::string>(const render_options&)> get,
                          const std::string& example, const std::string& help) {
  option_spec s;
  s.name = name;
  s.help = help;
  s.example = example;
  s.set = std::move(set);
  s.get = std::move(get);
  return s;
}

void check_existing_file(const std::string& path, const std::string& option) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0) throw input_error("", option, "no such file '" + path + "'");
  if (S_ISDIR(s.st_mode)) throw input_error("", option, "'" + path + "' is a folder, not a file");
}

// An option naming a file that must exist, given back by absolute path: the same file named from
// another folder is the same setting. Its example is filled in by the table's tests.
option_spec file_option(const std::string& name, std::string render_options::*at, const std::string& help) {
  return custom_option(
      name,
      [name, at](render_options& o, const std::string& text) {
        check_existing_file(text, dashed(name));
        o.*at = text;
      },
      [at](const render_options& o) -> std::optional<std::string> {
        if ((o.*at).empty()) return std::nullopt;
        return fs::absolute(o.*at).lexically_normal().string();
      },
      "", help);
}

option_spec optional_side(const std::string& name, field<std::optional<int>> at, const std::string& example,
                          const std::string& help) {
  option_spec s = custom_option(
      name,
      [at, name](render_options& o, const std::string& text) {
        at(o) = int(parse_integer(text, dashed(name), 1, max_image_side));
      },
      [at](const render_options& o) -> std::optional<std::string> {
        const std::optional<int>& v = read(o, at);
        return v ? std::optional<std::string>(std::to_string(*v)) : std::nullopt;
      },
      example, help);
  s.type = option_type::integer;
  return s;
}

option_spec optional_triple(const std::string& name, field<std::optional<dvec3>> at,
                            const std::string& example, const std::string& help) {
  return custom_option(
      name,
      [at, name](render_options& o, const std::string& text) { at(o) = parse_triple(text, dashed(name)); },
      [at](const render_options& o) -> std::optional<std::string> {
        const std::optional<dvec3>& v = read(o, at);
        return v ? std::optional<std::string>(triple_text(*v)) : std::nullopt;
      },
      example, help);
}

// "N" (N cells on every axis) or "X,Y,Z" for --grid-resolution.
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
    throw input_error("", "--grid-resolution",
                      "expects N or X,Y,Z cells per axis, each 1 to " + std::to_string(max_grid_resolution) +
                          ", got '" + text + "'");
  return r;
}

pixel_rect parse_crop(const std::string& text) {
  std::istringstream in(text);
  pixel_rect r;
  char c1 = 0, c2 = 0, c3 = 0;
  if (!(in >> r.x0 >> c1 >> r.y0 >> c2 >> r.x1 >> c3 >> r.y1) || c1 != ',' || c2 != ',' || c3 != ',' ||
      !(in >> std::ws).eof() || r.x0 < 0 || r.y0 < 0 || r.x1 <= r.x0 || r.y1 <= r.y0)
    throw input_error("", "--crop",
                      "expects pixels x0,y0,x1,y1 with 0 <= x0 < x1 and 0 <= y0 < y1, got '" + text + "'");
  return r;
}

void parse_band(render_options& o, const std::string& text) {
  std::istringstream in(text);
  char slash = 0;
  int index = -1, count = 0;
  if (!(in >> index >> slash >> count) || slash != '/' || !(in >> std::ws).eof() || count < 1 || index < 0 ||
      index >= count)
    throw input_error("", "--band", "expects I/N with N >= 1 and 0 <= I < N, got '" + text + "'");
  o.band_index = index;
  o.band_count = count;
}

void parse_aovs(render_options& o, const std::string& text) {
  std::string bad;
  std::optional<aov_set> aovs = parse_aov_list(text, &bad);
  if (!aovs)
    throw input_error(
        "", "--aovs",
        "unknown or repeated output " + bad +
            " (choose from beauty, Z, N, P, albedo, uv, id, motion, crypto_object, crypto_material, "
            "cryptomatte, direct, reflection, refraction, lightgroups, albedo_filtered, "
            "N_filtered, diffuse, specular, shadow)");
  // --cryptomatte-depth and --depth-mode fill in fields of the same set, whichever comes first.
  aovs->crypto_depth = o.aovs.crypto_depth;
  aovs->depth_kind = o.aovs.depth_kind;
  o.aovs = *aovs;
}

std::vector<std::string> quality_names() {
  return {bvh_quality_name(bvh_quality::low), bvh_quality_name(bvh_quality::medium),
          bvh_quality_name(bvh_quality::high)};
}

void add_view_options(std::vector<option_spec>& t) {
  auto add = [&t](option_spec s) -> option_spec& {
    s.scope = option_scope::view;
    t.push_back(std::move(s));
    return t.back();
  };
  add(optional_side(
      "width", [](render_options & o) -> auto& { return o.width; }, "64",
      "Image width in pixels (default 640, or from --height and the camera's aspect)"));
  add(optional_side(
      "height", [](render_options & o) -> auto& { return o.height; }, "48",
      "Image height in pixels (default 480, or from the camera's aspect ratio)"));
  add(integer_option<int>(
          "spp", [](render_options & o) -> auto& { return o.samples_per_pixel; }, 1, 1 << 16, "4",
          "Samples per pixel, stratified and jittered (1 = pixel centre)"))
      .recorded_as = "kiln/samples_per_pixel";
  add(choice_option(
          "sampler", [](render_options & o) -> auto& { return o.sampler; }, {"stratified", "random"},
          "random",
          "Sample positions inside a pixel: jittered strata, or independent uniform samples (the "
          "baseline stratification is measured against)"))
      .recorded_as = "kiln/sampler";
  add(choice_option(
      "filter", [](render_options & o) -> auto& { return o.filter; },
      {"box", "tent", "gaussian", "blackman-harris"}, "tent",
      "Reconstruction filter for the stratified samples (default radius: box 0.5, tent 1, gaussian "
      "1.5 with sigma radius/3, blackman-harris 2)"));
  add(custom_option(
          "filter-radius",
          [](render_options& o, const std::string& text) {
            o.filter_radius = float(parse_number(text, "--filter-radius", 0.0, 16.0, true));
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.filter_radius ? std::optional<std::string>(exact_text(*o.filter_radius)) : std::nullopt;
          },
          "0.75", "Filter radius in pixels, in (0, 16] (default: the filter's own)"))
      .type = option_type::number;
  add(number_option<float>(
      "adaptive-threshold", [](render_options & o) -> auto& { return o.adaptive_threshold; }, 0.0, 1e9, "0.1",
      "Whitted's adaptive supersampling: split a pixel square while its corners differ by more "
      "than T in R, G, B or A, or hit different instances (0 = off; replaces --spp and "
      "--filter)"));
  add(integer_option<int>(
      "adaptive-depth", [](render_options & o) -> auto& { return o.adaptive_depth; }, 0, max_adaptive_depth,
      "2", "Adaptive supersampling: most splits per pixel"));
  add(integer_option<int>(
          "threads", [](render_options & o) -> auto& { return o.threads; }, 0, 4096, "3",
          "Render threads (0 = all cores)"))
      .effect = option_effect::none;
  add(integer_option<int>(
      "tile-size", [](render_options & o) -> auto& { return o.tile_size; }, 1, 4096, "16",
      "Tile side in pixels"));
  add(custom_option(
      "camera", [](render_options& o, const std::string& text) { o.camera = text; },
      [](const render_options& o) -> std::optional<std::string> {
        return o.camera.empty() ? std::nullopt : std::optional<std::string>(o.camera);
      },
      "1", "glTF camera by name or index (default: the first camera in the file)"));
  add(optional_triple(
      "look-from", [](render_options & o) -> auto& { return o.look_from; }, "1,2,3",
      "Look-at camera position X,Y,Z (overrides --camera; needs --look-at)"));
  add(optional_triple(
      "look-at", [](render_options & o) -> auto& { return o.look_at; }, "0,0,-1",
      "Look-at camera target X,Y,Z"));
  add(custom_option(
      "up", [](render_options& o, const std::string& text) { o.up = parse_triple(text, "--up"); },
      [](const render_options& o) -> std::optional<std::string> { return triple_text(o.up); }, "0,0,1",
      "Look-at camera up vector X,Y,Z (default 0,1,0)"));
  add(number_option<double>(
      "fov", [](render_options & o) -> auto& { return o.fov_degrees; }, 1e-3, 179.999, "30",
      "Look-at camera vertical field of view in degrees"));
  option_spec& scene = add(custom_option(
      "scene",
      [](render_options& o, const std::string& text) {
        o.scene_index = int(parse_unsigned(text, "--scene", 0, 1u << 30));
      },
      [](const render_options& o) -> std::optional<std::string> {
        return o.scene_index < 0 ? std::nullopt : std::optional<std::string>(std::to_string(o.scene_index));
      },
      "1", "glTF scene index (default: the file's default scene)"));
  scene.type = option_type::unsigned_integer;
  // The pose: which animations play and at what time. All optional, so a still's arguments (and
  // its settings hash) stay what they were; job/render_job.h's scene_time resolves them.
  add(custom_option(
          "time",
          [](render_options& o, const std::string& text) {
            o.time = parse_number(text, "--time", -max_scene_seconds, max_scene_seconds);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.time ? std::optional<std::string>(exact_text(*o.time)) : std::nullopt;
          },
          "0.5", "Pose the scene at this time in seconds of its animations (default 0; or --frame)"))
      .recorded_as = "kiln/time";
  t.back().type = option_type::number;
  add(custom_option(
          "frame",
          [](render_options& o, const std::string& text) {
            o.frame = parse_integer(text, "--frame", -max_frame_number, max_frame_number);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.frame ? std::optional<std::string>(std::to_string(*o.frame)) : std::nullopt;
          },
          "12", "Pose the scene at frame N: time (N - frame-start) / fps seconds (instead of --time)"))
      .recorded_as = "kiln/frame";
  t.back().type = option_type::integer;
  add(custom_option(
          "fps",
          [](render_options& o, const std::string& text) {
            o.fps = parse_number(text, "--fps", 0.0, 1e6, true);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.fps ? std::optional<std::string>(exact_text(*o.fps)) : std::nullopt;
          },
          "30", "Frames per second of --frame (default 24)"))
      .recorded_as = "kiln/fps";
  t.back().type = option_type::number;
  add(custom_option(
          "frame-start",
          [](render_options& o, const std::string& text) {
            o.frame_start = parse_integer(text, "--frame-start", -max_frame_number, max_frame_number);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.frame_start ? std::optional<std::string>(std::to_string(*o.frame_start)) : std::nullopt;
          },
          "0", "The frame number at time 0 for --frame (default 1)"))
      .recorded_as = "kiln/frame_start";
  t.back().type = option_type::integer;
  add(custom_option(
          "animation", [](render_options& o, const std::string& text) { o.animation = text; },
          [](const render_options& o) -> std::optional<std::string> { return o.animation; }, "1",
          "glTF animations to play: all, or one by name or index (default all)"))
      .recorded_as = "kiln/animation";
  add(custom_option(
          "variant", [](render_options& o, const std::string& text) { o.variant = text; },
          [](const render_options& o) -> std::optional<std::string> { return o.variant; }, "beach",
          "KHR_materials_variants: render the variant NAME (or its index) of a file with material variants"))
      .recorded_as = "kiln/variant";
  add(custom_option(
          "shutter", [](render_options& o, const std::string& text) { o.shutter = parse_shutter(text); },
          [](const render_options& o) -> std::optional<std::string> {
            if (!o.shutter) return std::nullopt;
            return exact_text(o.shutter->first) + "," + exact_text(o.shutter->second);
          },
          "-0.25,0.25",
          "Motion blur: the shutter is open from OPEN to CLOSE, in frames relative to the frame (default: no "
          "blur)"))
      .recorded_as = "kiln/shutter";
  add(custom_option(
          "motion-steps",
          [](render_options& o, const std::string& text) {
            o.motion_steps = int(parse_integer(text, "--motion-steps", 2, max_motion_steps));
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.motion_steps ? std::optional<std::string>(std::to_string(o.motion_steps)) : std::nullopt;
          },
          "5", "Time steps of --shutter's motion blur (default: as many as the motion needs, up to 33)"))
      .recorded_as = "kiln/motion_steps";
  t.back().type = option_type::integer;
  add(custom_option(
          "background",
          [](render_options& o, const std::string& text) {
            dvec3 c = parse_triple(text, "--background");
            if (c.x < 0 || c.y < 0 || c.z < 0)
              throw input_error("", "--background", "colour must be non-negative, got '" + text + "'");
            o.background = vec3(c);
          },
          [](const render_options& o) -> std::optional<std::string> { return triple_text(o.background); },
          "0.5,0.5,0.5", "Environment colour R,G,B (linear), seen by reflections (default 0,0,0)"))
      .recorded_as = "kiln/background";
  add(file_option("environment", &render_options::environment,
                  "Equirectangular environment map (EXR, HDR, ...; linear radiance) seen by rays that leave "
                  "the scene"));
  add(number_option<double>(
      "environment-rotation", [](render_options & o) -> auto& { return o.environment_rotation_degrees; },
      -36000.0, 36000.0, "90",
      "Turn the environment map about +Y by DEG degrees (counter-clockwise seen from above)"));
  add(number_option<float>(
      "environment-intensity", [](render_options & o) -> auto& { return o.environment_intensity; }, 0.0, 1e9,
      "2", "Scale of the environment map's radiance"));
  add(flag_option(
      "show-background", [](render_options & o) -> auto& { return o.show_background; },
      "Camera rays that miss see the environment colour with alpha 1 (default: transparent, alpha 0)"));
  add(choice_option(
          "transmission-alpha", [](render_options & o) -> auto& { return o.transmission_alpha; },
          {"opaque", "transparent"}, "transparent",
          "What glass contributes to alpha: opaque (it holds out, what it shows is baked in) or "
          "transparent (refraction reaching a background the camera does not show is transparent)"))
      .recorded_as = "kiln/transmission_alpha";
  // Holdouts: the patterns are checked for their form here and against the file's nodes at load.
  auto node_patterns = [](const std::string& name, std::string render_options::*at, const std::string& help) {
    return custom_option(
        name,
        [name, at](render_options& o, const std::string& text) {
          if (text.empty() || text.front() == ',' || text.back() == ',' ||
              text.find(",,") != std::string::npos)
            throw input_error("", "--" + name, "expects node names or globs separated by commas");
          o.*at = text;
        },
        [at](const render_options& o) -> std::optional<std::string> {
          return (o.*at).empty() ? std::nullopt : std::optional<std::string>(o.*at);
        },
        "wheel_*,body", help);
  };
  add(node_patterns(
          "holdout", &render_options::holdout,
          "Render these nodes (names or globs, comma-separated) as holdout mattes: they cut alpha to "
          "zero and hide what is behind them, but still cast shadows and show in reflections"))
      .recorded_as = "kiln/holdout";
  add(node_patterns("only", &render_options::only,
                    "Render only these nodes (names or globs); every other node is a holdout (a render "
                    "layer)"))
      .recorded_as = "kiln/only";
  add(flag_option(
          "holdout-invisible", [](render_options & o) -> auto& { return o.holdout_invisible; },
          "Holdouts matte the camera only: they cast no shadows and do not show in reflections or "
          "through glass"))
      .recorded_as = "kiln/holdout_invisible";
  add(integer_option<int>(
          "max-depth", [](render_options & o) -> auto& { return o.max_depth; }, 0, 64, "2",
          "Maximum reflection depth"))
      .recorded_as = "kiln/max_depth";
  add(number_option<float>(
      "min-throughput", [](render_options & o) -> auto& { return o.min_throughput; }, 0.0, 1.0, "0.01",
      "Reflections weighted below this are not traced"));
  add(unsigned_option<uint64_t>(
      "max-rays-per-sample", [](render_options & o) -> auto& { return o.max_rays_per_sample; }, 1, ~0ull,
      "64",
      "Reflected, refracted and continued rays one camera sample may spawn; past it the sample "
      "keeps the light gathered so far"));
  add(number_option<float>(
          "texture-cache-mb", [](render_options & o) -> auto& { return o.texture_cache_mb; }, 1.0, 1e6, "64",
          "No effect (texture pyramids are kept in memory); accepted so existing command lines "
          "keep working"))
      .effect = option_effect::none;
  add(flag_option(
      "allow-outside-files", [](render_options & o) -> auto& { return o.allow_outside_files; },
      "Let buffer and image URIs name files outside the asset's folder ('..' escapes, symlinks that "
      "lead out); absolute paths and URLs stay refused"));
  // The loader's limits: their defaults are gltf_limits' own.
  add(unsigned_option<size_t>(
      "max-json-bytes", [](render_options & o) -> auto& { return o.limits.max_json_bytes; }, 1, ~0ull, "1000",
      "Refuse glTF JSON larger than this (bytes)"));
  add(unsigned_option<size_t>(
      "max-json-depth", [](render_options & o) -> auto& { return o.limits.max_json_depth; }, 1, 100000, "10",
      "Refuse glTF JSON nested deeper than this"));
  add(unsigned_option<size_t>(
      "max-nodes", [](render_options & o) -> auto& { return o.limits.max_nodes; }, 1, ~0ull, "10",
      "Refuse glTF files with more nodes than this"));
  add(unsigned_option<size_t>(
      "max-instances", [](render_options & o) -> auto& { return o.limits.max_instances; }, 1, ~0ull, "10",
      "Refuse glTF files whose EXT_mesh_gpu_instancing takes the scene past this many mesh instances"));
  add(unsigned_option<uint64_t>(
      "max-texels", [](render_options & o) -> auto& { return o.limits.max_texels; }, 1, ~0ull, "10",
      "Refuse glTF images declaring more texels than this (width x height), before decoding"));
  add(unsigned_option<size_t>(
      "max-pixels", [](render_options & o) -> auto& { return o.max_pixels; }, 1, ~0ull, "10",
      "Refuse images with more pixels than this (width x height)"));
  // The job's memory budget does not change a pixel: a render it allows is the same image.
  add(custom_option(
          "max-memory",
          [](render_options& o, const std::string& text) {
            o.max_memory = parse_memory_size(text, "--max-memory");
          },
          [](const render_options& o) -> std::optional<std::string> {
            if (o.max_memory == 0) return std::nullopt;
            return std::to_string(o.max_memory);
          },
          "8G",
          "Memory budget of a job, in bytes or with K, M, G, T (binary): a file whose estimated "
          "memory exceeds it is refused (default: 90% of the machine's or the cgroup's memory)"))
      .effect = option_effect::none;
  add(number_option<double>(
      "grid-density", [](render_options & o) -> auto& { return o.grid.density; }, 1e-3, 1e3, "4",
      "Grid backends: aim for density x N cells for N items (the resolution heuristic; "
      "default 2)"));
  add(custom_option(
      "grid-resolution",
      [](render_options& o, const std::string& text) { o.grid.resolution = parse_grid_resolution(text); },
      [](const render_options& o) -> std::optional<std::string> {
        if (!o.grid.resolution) return std::nullopt;
        const glm::ivec3& r = *o.grid.resolution;
        return std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.z);
      },
      "8", "Grid backends: N or X,Y,Z cells per axis for every grid, instead of the heuristic"));
  add(integer_option<int>(
      "grid-max-items", [](render_options & o) -> auto& { return o.grid.max_items_per_cell; }, 1, 1000000,
      "3", "Adaptive grid: a cell holding more items than this is subdivided"));
  add(integer_option<int>(
      "grid-max-depth", [](render_options & o) -> auto& { return o.grid.max_depth; }, 0, max_grid_depth, "1",
      "Adaptive grid: levels of subdivision below the top grid"));
  add(custom_option(
      "bvh-quality",
      [](render_options& o, const std::string& text) {
        check_choice(text, "--bvh-quality", quality_names());
        o.embree.quality = *parse_bvh_quality(text);
      },
      [](const render_options& o) -> std::optional<std::string> {
        return std::string(bvh_quality_name(o.embree.quality));
      },
      "high", "Embree BVH build quality: low, medium or high (default medium)"));
  t.back().recorded_as = "kiln/bvh_quality";
  t.back().choices = quality_names();
  // Pixels do not depend on the BVH build, but a plan must reproduce the run.
  add(flag_option(
          "bvh-compact", [](render_options & o) -> auto& { return o.embree.compact; },
          "Embree: compact BVH layout (less memory, slower rays)"))
      .recorded_as = "kiln/bvh_compact";
  // --packets can pick the other of two coincident surfaces, so it counts as a pixel setting.
  add(custom_option(
      "packets",
      [](render_options& o, const std::string& text) {
        check_choice(text, "--packets", {"on", "off"});
        o.packets = text == "on";
      },
      [](const render_options& o) -> std::optional<std::string> {
        return std::string(o.packets ? "on" : "off");
      },
      "on", "Trace each tile's camera rays together as Embree packets: on or off (default off)"));
  t.back().recorded_as = "kiln/packets";
  t.back().choices = {"on", "off"};
  add(number_option<double>(
          "time-limit", [](render_options & o) -> auto& { return o.time_limit_seconds; }, 0.0, 1e9, "60",
          "Stop a job still loading or rendering after this many seconds: nothing is written, "
          "exit 124 (0 = no limit)"))
      .effect = option_effect::none;
  option_spec& quiet = add(flag_option(
      "quiet", [](render_options & o) -> auto& { return o.quiet; }, "No progress line or summary"));
  quiet.short_name = "q";
  quiet.effect = option_effect::none;
}

void add_image_options(std::vector<option_spec>& t) {
  auto add = [&t](option_spec s) -> option_spec& {
    s.scope = option_scope::image;
    t.push_back(std::move(s));
    return t.back();
  };
  add(flag_option(
      "float", [](render_options & o) -> auto& { return o.full_float; },
      "Write RGBA, N, albedo, the light split (direct, reflection, refraction), the light groups and the "
      "passes (albedo_filtered, N_filtered, diffuse, specular, shadow) as 32-bit float "
      "instead of half (uv is float unless --channel-format uv=half; Z, P, id and Cryptomatte are "
      "always float)"));
  add(custom_option(
      "channel-format",
      [](render_options& o, const std::string& text) {
        layer_formats check;
        apply_channel_formats(text, check);  // an error now, not after the render
        o.channel_formats = text;
      },
      [](const render_options& o) -> std::optional<std::string> {
        return o.channel_formats.empty() ? std::nullopt : std::optional<std::string>(o.channel_formats);
      },
      "N=float",
      "Per-AOV sample format after --float, e.g. beauty=float,N=half,uv=half (" + selectable_format_aovs() +
          "; Z, P and id are always float)"));
  add(choice_option(
      "compression", [](render_options & o) -> auto& { return o.exr.compression; }, exr_compression_names(),
      "piz",
      "EXR codec; pxr24, b44, b44a, dwaa and dwab are lossy and need --multipart when the file "
      "holds Z, P or id (which then keep zip)"));
  option_spec& level = add(custom_option(
      "compression-level",
      [](render_options& o, const std::string& text) {
        o.exr.compression_level = int(parse_integer(text, "--compression-level", 1, 100000));
      },
      [](const render_options& o) -> std::optional<std::string> {
        if (o.exr.compression_level <= 0) return std::nullopt;
        return std::to_string(o.exr.compression_level);
      },
      "9", "zip/zips: zlib level 1-9 (default 4); dwaa/dwab: dwaCompressionLevel (default 45)"));
  level.type = option_type::integer;
  add(flag_option(
      "tiled", [](render_options & o) -> auto& { return o.exr_tiled; },
      "Tiled EXR (64x64 tiles unless --exr-tile-size) instead of scanlines"));
  option_spec& exr_tile = add(custom_option(
      "exr-tile-size",
      [](render_options& o, const std::string& text) {
        o.exr_tile_size = int(parse_integer(text, "--exr-tile-size", 1, 4096));
      },
      [](const render_options& o) -> std::optional<std::string> {
        if (o.exr_tile_size <= 0) return std::nullopt;
        return std::to_string(o.exr_tile_size);
      },
      "16", "Tiled EXR with NxN tiles (implies --tiled)"));
  exr_tile.type = option_type::integer;
  add(flag_option(
      "multipart", [](render_options & o) -> auto& { return o.exr.multipart; },
      "One EXR part per layer (" + exr_part_list() + "), each with the full header"));
  // A sequence is many renders; each frame's own --frame reaches its settings hash.
  add(custom_option(
          "frames",
          [](render_options& o, const std::string& text) {
            parse_frame_range(text);
            o.frames = text;
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.frames.empty() ? std::nullopt : std::optional<std::string>(o.frames);
          },
          "1-48:2",
          "Render frames FIRST-LAST[:STEP] in one process, each to -o with its #### (or %04d) replaced "
          "by the frame number; the asset loads once and only what moves is updated"))
      .effect = option_effect::none;
  option_spec& preview = add(custom_option(
      "preview",
      [](render_options& o, const std::string& text) {
        if (preview_format(text).empty())
          throw input_error("", "--preview", "a preview must end in .png, .jpg or .jpeg, got '" + text + "'");
        o.preview = text;
      },
      [](const render_options& o) -> std::optional<std::string> {
        return o.preview.empty() ? std::nullopt : std::optional<std::string>(o.preview);
      },
      "x.png", "Also write an 8-bit sRGB preview FILE.png (with alpha) or FILE.jpg of the beauty"));
  preview.effect = option_effect::none;  // an output, not a setting of the EXR's pixels
  // Colour management: the working space changes pixels (and so the settings hash); the config
  // is hashed by its path, as --environment is. The display and view change only the preview.
  auto text_option = [](const std::string& name, std::string render_options::*at, const std::string& example,
                        const std::string& help) {
    return custom_option(
        name,
        [name, at](render_options& o, const std::string& text) {
          if (text.empty()) throw input_error("", "--" + name, "expects a name, got nothing");
          o.*at = text;
        },
        [at](const render_options& o) -> std::optional<std::string> {
          return (o.*at).empty() ? std::nullopt : std::optional<std::string>(o.*at);
        },
        example, help);
  };
  add(file_option("ocio-config", &render_options::ocio_config,
                  "OpenColorIO config for --working-space and the preview (default: $OCIO, else kiln's "
                  "share/ocio/kiln.ocio)"))
      .recorded_as = "kiln/ocio_config";
  add(text_option("working-space", &render_options::working_space, "ACEScg",
                  "Render in this colour space of the config (e.g. ACEScg): glTF's linear Rec.709 colours, "
                  "textures and lights are converted into it, and the EXR is tagged with it (default: "
                  "linear Rec.709, unconverted)"))
      .recorded_as = "kiln/working_space";
  add(text_option("display", &render_options::display, "sRGB",
                  "Preview through this display of the OpenColorIO config (default: the config's default)"))
      .effect = option_effect::none;
  add(text_option("view", &render_options::view, "Raw",
                  "Preview through this view of the display (default: the display's default view)"))
      .effect = option_effect::none;
  add(number_option<double>(
          "preview-exposure", [](render_options & o) -> auto& { return o.preview_exposure; }, -64.0, 64.0,
          "1", "Preview: scale linear colour by 2^EV"))
      .effect = option_effect::none;
  // Hashed like a pixel setting: a stored EXR rendered without it has no deep file beside it.
  add(flag_option(
          "deep", [](render_options & o) -> auto& { return o.deep; },
          "Also write a deep EXR beside -o (NAME.deep.exr for NAME.exr): per pixel its camera paths' "
          "surfaces "
          "front to back, premultiplied R G B A, Z, ZBack and the ids; whole frame, stratified samples and a "
          "filter inside the pixel only"))
      .recorded_as = "kiln/deep";
  add(custom_option(
          "aovs", parse_aovs,
          [](const render_options& o) -> std::optional<std::string> { return aov_list_name(o.aovs); },
          "beauty,Z",
          "Comma-separated outputs to write: beauty (R G B A), Z, N, P (world position), albedo, uv, id "
          "(id.object, id.material, id.instance), crypto_object and crypto_material (Cryptomatte of the node "
          "and material names; cryptomatte for both), direct, reflection and refraction (the beauty split by "
          "first event), lightgroups (the beauty split by light: one layer per light, emission and "
          "environment), albedo_filtered and N_filtered (albedo and normal filtered like the beauty, for a "
          "denoiser), diffuse and specular (the direct light by BRDF lobe), shadow (one shadow matte per "
          "light) (default beauty,Z,N)"))
      .recorded_as = "kiln/aovs";
  add(integer_option<int>(
      "cryptomatte-depth", [](render_options & o) -> auto& { return o.aovs.crypto_depth; }, 1,
      max_cryptomatte_depth, "4",
      "Cryptomatte ranks (id and coverage pairs) per pixel, two per RGBA channel set"));
  add(custom_option(
      "depth-mode",
      [](render_options& o, const std::string& text) {
        check_choice(text, "--depth-mode", {"distance", "planar"});
        o.aovs.depth_kind = *parse_depth_mode(text);
      },
      [](const render_options& o) -> std::optional<std::string> {
        return std::string(o.aovs.depth_kind == depth_mode::planar ? "planar" : "distance");
      },
      "planar",
      "What Z holds: distance (along the ray from the camera, the default) or planar (along the view axis)"));
  t.back().choices = {"distance", "planar"};
  add(custom_option(
          "crop", [](render_options& o, const std::string& text) { o.crop = parse_crop(text); },
          [](const render_options& o) -> std::optional<std::string> {
            if (!o.crop) return std::nullopt;
            const pixel_rect& c = *o.crop;
            return std::to_string(c.x0) + "," + std::to_string(c.y0) + "," + std::to_string(c.x1) + "," +
                   std::to_string(c.y1);
          },
          "0,0,8,8",
          "Render and store only pixels [x0, x1) x [y0, y1) (EXR data window; the display window stays the "
          "full frame)"))
      .effect = option_effect::region;
  option_spec& band = add(custom_option(
      "band", parse_band,
      [](const render_options& o) -> std::optional<std::string> {
        if (o.band_count <= 0) return std::nullopt;
        return std::to_string(o.band_index) + "/" + std::to_string(o.band_count);
      },
      "1/4",
      "Render band I (0-based) of N horizontal bands of whole rows, as a crop (band I holds rows "
      "[floor(I*H/N), floor((I+1)*H/N)); join the files with kiln stitch)"));
  band.effect = option_effect::region;
  band.alias = "tile";  // the name before render tiles, EXR tiles and farm bands were told apart
  // compare and bench name their backends with their own --accel.
  add(choice_option(
          "accel", [](render_options & o) -> auto& { return o.accel; }, {"embree", "grid", "adaptive-grid"},
          "grid", "Traversal backend"))
      .recorded_as = "kiln/accelerator";
}

void add_progress_options(std::vector<option_spec>& t) {
  option_spec s = number_option<double>(
      "progress-interval", [](render_options & o) -> auto& { return o.progress_interval; }, 0.01, 86400.0,
      "1", "Seconds between progress lines when stderr is not a terminal (a log or a pipe)");
  s.scope = option_scope::progress;
  s.effect = option_effect::none;
  t.push_back(std::move(s));
}

std::vector<option_spec> make_table() {
  std::vector<option_spec> t;
  add_view_options(t);
  add_image_options(t);
  add_progress_options(t);
  return t;
}

std::string bare_name(const std::string& name) {
  size_t dashes = 0;
  while (dashes < name.size() && dashes < 2 && name[dashes] == '-') ++dashes;
  return name.substr(dashes);
}

}  // namespace

const std::vector<option_spec>& render_option_table() {
  static const std::vector<option_spec> table = make_table();
  return table;
}

const option_spec* find_render_option(const std::string& name) {
  const std::string bare = bare_name(name);
  for (const option_spec& spec : render_option_table())
    if (spec.name == bare || (!spec.alias.empty() && spec.alias == bare) ||
        (!spec.short_name.empty() && spec.short_name == bare))
      return &spec;
  return nullptr;
}

void set_render_option(render_options& options, const std::string& name, const std::string& text) {
  const option_spec* spec = find_render_option(name);
  if (!spec) throw input_error("", dashed(bare_name(name)), "is not a render option");
  spec->set(options, text);
}

std::vector<std::string> canonical_render_arguments(const render_options& options, region_arguments region) {
  std::vector<std::string> arguments;
  for (const option_spec& spec : render_option_table()) {
    if (spec.effect == option_effect::none) continue;
    if (spec.effect == option_effect::region && region == region_arguments::omit) continue;
    const std::optional<std::string> value = spec.get(options);
    if (!value) continue;
    if (spec.type == option_type::flag) {
      if (*value == "true") arguments.push_back(dashed(spec.name));
      continue;
    }
    arguments.push_back(dashed(spec.name));
    arguments.push_back(*value);
  }
  return arguments;
}

std::vector<std::pair<std::string, std::string>> recorded_option_attributes(const render_options& options) {
  std::vector<std::pair<std::string, std::string>> attributes;
  for (const option_spec& spec : render_option_table()) {
    if (spec.recorded_as.empty()) continue;
    std::optional<std::string> value = spec.get(options);
    if (!value) continue;
    if (spec.type == option_type::flag) value = *value == "true" ? "on" : "off";
    attributes.emplace_back(spec.recorded_as, *value);
  }
  return attributes;
}

}  // namespace kiln
