// The option table's first part: the camera, the image size and region, the scene file and its pose.
#include <string>
#include <vector>

#include "core/error.h"
#include "job/option_entries.h"
#include "job/turntable.h"
#include "render/adaptive_sampling.h"

namespace kiln::option_entries {

void add_view_options(std::vector<option_spec>& t) {
  scoped_adder add{t, option_scope::view};
  add.group = option_group::output;
  add(optional_side(
      "width", [](render_options & o) -> auto& { return o.width; }, "64",
      "Image width in pixels (default 640, or from --height and the camera's aspect)"));
  add(optional_side(
      "height", [](render_options & o) -> auto& { return o.height; }, "48",
      "Image height in pixels (default 480, or from the camera's aspect ratio)"));
  add.group = option_group::sampling;
  add(custom_option(
          "spp",
          [](render_options& o, const std::string& text) {
            o.spp_given = int(parse_integer(text, "--spp", 1, 1 << 16));
          },
          [](const render_options& o) -> std::optional<std::string> {
            return std::to_string(samples_per_pixel_of(o));
          },
          "4", "Samples per pixel, stratified and jittered (default 16; 1 = pixel centre)"))
      .recorded_as = "kiln/samples_per_pixel";
  t.back().type = option_type::integer;
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
  add.group = option_group::performance;
  add(integer_option<int>(
          "threads", [](render_options & o) -> auto& { return o.threads; }, 0, 4096, "3",
          "Render threads (0 = all cores)"))
      .effect = option_effect::none;
  add(integer_option<int>(
      "tile-size", [](render_options & o) -> auto& { return o.tile_size; }, 1, 4096, "16",
      "Tile side in pixels"));
  add.group = option_group::camera;
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
      "Vertical field of view in degrees of a look-at camera, --camera-view and --turntable"));
  add(custom_option(
          "camera-view",
          [](render_options& o, const std::string& text) {
            parse_camera_view(text);
            o.camera_view = text;
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.camera_view.empty() ? std::nullopt : std::optional<std::string>(o.camera_view);
          },
          "three-quarter",
          "Frame the asset like the default camera but from another direction: front, three-quarter (azimuth "
          "45, elevation 25), top, or AZIMUTH,ELEVATION in degrees (azimuth from +Z towards +X); --fov sets "
          "its lens (default 45)"))
      .recorded_as = "kiln/camera_view";
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
  add.group = option_group::animation;
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
  t.back().recorded_type = record_type::float64;
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
  t.back().recorded_type = record_type::float64;
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
  add.group = option_group::camera;
  add(custom_option(
          "variant", [](render_options& o, const std::string& text) { o.variant = text; },
          [](const render_options& o) -> std::optional<std::string> { return o.variant; }, "beach",
          "KHR_materials_variants: render the variant NAME (or its index) of a file with material variants"))
      .recorded_as = "kiln/variant";
  add.group = option_group::animation;
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
  t.back().recorded_type = record_type::float2;
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
  add.group = option_group::lighting;
  add(custom_option(
          "background",
          [](render_options& o, const std::string& text) {
            dvec3 c = parse_triple(text, "--background");
            if (c.x < 0 || c.y < 0 || c.z < 0)
              throw input_error("", "--background", "colour must be non-negative, got '" + text + "'");
            o.background = vec3(c);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.background ? std::optional<std::string>(triple_text(*o.background)) : std::nullopt;
          },
          "0.5,0.5,0.5",
          "A constant environment R,G,B (linear radiance): lights every surface and is seen by rays that "
          "leave the scene (default: none; see --lighting)"))
      .recorded_as = "kiln/background";
  t.back().recorded_type = record_type::float3;
}

}  // namespace kiln::option_entries
