// The option table's EXR part: channel formats, compression, tiles, outputs beside the EXR, colour
// management, deep output, crop, band and the backend; and the progress interval.
#include <string>
#include <vector>

#include "core/error.h"
#include "io/exr/preview_codes.h"
#include "job/asset_file.h"
#include "job/exr_storage_options.h"
#include "job/frame_range.h"
#include "job/option_entries.h"

namespace kiln::option_entries {

void add_image_options(std::vector<option_spec>& t) {
  scoped_adder add{t, option_scope::image};
  add.group = option_group::output;
  add(flag_option(
      "float", [](render_options & o) -> auto& { return o.full_float; },
      "Write " + half_by_default_aovs() +
          " as 32-bit float instead of half (uv is float unless --channel-format uv=half; Z, P, id and "
          "Cryptomatte are always float)"));
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
  add.group = option_group::animation;
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
  // A turntable (job/turntable.h) is a sequence too; each frame's --frame turns its camera.
  add(custom_option(
          "turntable",
          [](render_options& o, const std::string& text) {
            o.turntable = parse_integer(text, "--turntable", 1, max_sequence_frames);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.turntable > 0 ? std::optional<std::string>(std::to_string(o.turntable)) : std::nullopt;
          },
          "24",
          "Render N frames orbiting the asset about +Y through its bounds' centre, framed like the default "
          "camera at every angle, each to -o with its #### replaced (as --frames); an animation plays along"))
      .recorded_as = "kiln/turntable";
  t.back().type = option_type::integer;
  add(custom_option(
          "turntable-elevation",
          [](render_options& o, const std::string& text) {
            o.turntable_elevation = parse_number(text, "--turntable-elevation", -90.0, 90.0);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.turntable_elevation ? std::optional<std::string>(exact_text(*o.turntable_elevation))
                                         : std::nullopt;
          },
          "35",
          "Turntable: the camera's elevation above the asset's centre in degrees, -90 to 90 (default 20)"))
      .recorded_as = "kiln/turntable_elevation";
  t.back().type = option_type::number;
  add(custom_option(
          "turntable-start",
          [](render_options& o, const std::string& text) {
            o.turntable_start = parse_number(text, "--turntable-start", -1e6, 1e6);
          },
          [](const render_options& o) -> std::optional<std::string> {
            return o.turntable_start ? std::optional<std::string>(exact_text(*o.turntable_start))
                                     : std::nullopt;
          },
          "90",
          "Turntable: the first frame's azimuth in degrees, from the front (+Z) towards +X (default 0); "
          "frame i is at start + 360 i / N"))
      .recorded_as = "kiln/turntable_start";
  t.back().type = option_type::number;
  add(custom_option(
          "turntable-animation",
          [](render_options& o, const std::string& text) {
            check_choice(text, "--turntable-animation", {"play", "hold"});
            o.turntable_animation = text;
          },
          [](const render_options& o) -> std::optional<std::string> { return o.turntable_animation; }, "hold",
          "Turntable of an animated asset: play (default: frame N poses the animation at frame N) or hold "
          "(the pose at --time, default 0, while the camera turns)"))
      .recorded_as = "kiln/turntable_animation";
  t.back().choices = {"play", "hold"};
  add.group = option_group::output;
  option_spec& preview = add(custom_option(
      "preview",
      [](render_options& o, const std::string& text) {
        check_no_nul(text, "--preview");
        if (preview_format(text).empty())
          throw input_error("", "--preview", "a preview must end in .png, .jpg or .jpeg, got '" + text + "'");
        o.preview = text;
      },
      [](const render_options& o) -> std::optional<std::string> {
        return o.preview.empty() ? std::nullopt : std::optional<std::string>(o.preview);
      },
      "x.png", "Also write an 8-bit sRGB preview FILE.png (with alpha) or FILE.jpg of the beauty"));
  preview.effect = option_effect::none;  // an output, not a setting of the EXR's pixels
  preview.names_file = true;
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
  add.group = option_group::colour;
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
  add.group = option_group::output;
  add(flag_option(
          "deep", [](render_options & o) -> auto& { return o.deep; },
          "Also write a deep EXR beside -o (NAME.deep.exr for NAME.exr): per pixel its camera paths' "
          "surfaces "
          "front to back, premultiplied R G B A, Z, ZBack and the ids; whole frame, stratified samples and a "
          "filter inside the pixel only"))
      .recorded_as = "kiln/deep";
  add.group = option_group::aovs;
  add(custom_option(
          "aovs", parse_aovs,
          [](const render_options& o) -> std::optional<std::string> { return aov_list_name(o.aovs); },
          "beauty,Z", aov_help()))
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
  add.group = option_group::output;
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
  add.group = option_group::performance;
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
  s.group = option_group::progress;
  s.effect = option_effect::none;
  t.push_back(std::move(s));
}

}  // namespace kiln::option_entries
