#include "app/exr_options.h"

#include <CLI/CLI.hpp>
#include <sstream>

#include "app/cli_checks.h"
#include "core/error.h"
#include "io/exr/exr_writer.h"
#include "io/exr/preview_writer.h"

namespace kiln {

namespace {

constexpr int default_exr_tile = 64;

// The AOVs --channel-format (and --float) set, those of layer_formats.
const std::string selectable_aovs = "beauty, N, albedo, uv, direct, reflection, refraction";

// "rgba, depth, N, ...": every part --multipart can write, from the writer's table.
std::string part_list() {
  std::string list;
  for (const std::string& name : exr_part_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

// The format slot of a --channel-format AOV name; nullptr for names that have none. Throws a
// usage error for data AOVs asked to be half and for unknown names.
sample_format* format_slot(layer_formats& formats, const std::string& aov, const std::string& format) {
  if (aov == "beauty") return &formats.beauty;
  if (aov == "N") return &formats.normal;
  if (aov == "albedo") return &formats.albedo;
  if (aov == "uv") return &formats.uv;
  if (aov == "direct") return &formats.direct;
  if (aov == "reflection") return &formats.reflection;
  if (aov == "refraction") return &formats.refraction;
  if (aov == "Z" || aov == "P" || aov == "id") {
    if (format == "float") return nullptr;  // what it is anyway
    throw CLI::ValidationError("--channel-format", aov +
                                                       " is always 32-bit float (depth, positions and ids "
                                                       "need the precision); only " +
                                                       selectable_aovs + " can be half");
  }
  throw CLI::ValidationError("--channel-format",
                             "unknown AOV '" + aov + "' (choose from " + selectable_aovs + ")");
}

// Parses "AOV=half|float,..." onto formats.
void apply_channel_formats(const std::string& text, layer_formats& formats) {
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const size_t equals = item.find('=');
    const std::string aov = item.substr(0, equals);
    const std::string format = equals == std::string::npos ? std::string() : item.substr(equals + 1);
    if (format != "half" && format != "float")
      throw CLI::ValidationError("--channel-format", "expects AOV=half or AOV=float, got '" + item + "'");
    if (sample_format* slot = format_slot(formats, aov, format))
      *slot = format == "float" ? sample_format::float32 : sample_format::half;
  }
}

}  // namespace

void add_exr_options(CLI::App& app, render_options& o) {
  app.add_flag("--float", o.full_float,
               "Write RGBA, N, albedo and the light split (direct, reflection, refraction) as 32-bit float "
               "instead of half (uv is float unless --channel-format uv=half; Z, P, id and Cryptomatte are "
               "always float)");
  app.add_option_function<std::string>(
      "--channel-format",
      [&o](const std::string& text) {
        layer_formats check;
        apply_channel_formats(text, check);  // a usage error now, not after the render
        o.channel_formats = text;
      },
      "Per-AOV sample format after --float, e.g. beauty=float,N=half,uv=half (" + selectable_aovs +
          "; Z, P and id are always float)");
  app.add_option("--compression", o.exr.compression,
                 "EXR codec; pxr24, b44, b44a, dwaa and dwab are lossy and need --multipart when the file "
                 "holds Z, P or id (which then keep zip)")
      ->check(CLI::IsMember(exr_compression_names()))
      ->capture_default_str();
  app.add_option("--compression-level", o.exr.compression_level,
                 "zip/zips: zlib level 1-9 (default 4); dwaa/dwab: dwaCompressionLevel (default 45)")
      ->check(CLI::Range(1, 100000));
  app.add_flag("--tiled", o.exr_tiled, "Tiled EXR (64x64 tiles unless --exr-tile-size) instead of scanlines");
  app.add_option("--exr-tile-size", o.exr_tile_size, "Tiled EXR with NxN tiles (implies --tiled)")
      ->check(CLI::Range(1, 4096));
  app.add_flag("--multipart", o.exr.multipart,
               "One EXR part per layer (" + part_list() + "), each with the full header");
  app.add_option("--preview", o.preview,
                 "Also write an 8-bit sRGB preview FILE.png (with alpha) or FILE.jpg of the beauty")
      ->check(CLI::Validator(
          [](std::string& path) {
            return preview_format(path).empty() ? "a preview must end in .png, .jpg or .jpeg" : std::string();
          },
          "FILE.png|FILE.jpg"));
  app.add_option("--preview-exposure", o.preview_exposure, "Preview: scale linear colour by 2^EV")
      ->check(finite_number())
      ->check(CLI::Range(-64.0, 64.0))
      ->capture_default_str();
}

exr_settings resolve_exr_settings(const render_options& options) {
  exr_settings settings = options.exr;
  if (options.exr_tiled || options.exr_tile_size > 0)
    settings.tile_size = options.exr_tile_size > 0 ? options.exr_tile_size : default_exr_tile;
  const sample_format all = options.full_float ? sample_format::float32 : sample_format::half;
  settings.formats = {all, all, all, sample_format::float32, all, all, all};  // uv: float either way
  apply_channel_formats(options.channel_formats, settings.formats);
  const std::string& codec = settings.compression;
  if (settings.compression_level > 0) {
    if (!compression_takes_level(codec))
      throw input_error("", "--compression-level",
                        codec + " takes no level (only zip, zips, dwaa and dwab do)");
    if ((codec == "zip" || codec == "zips") && settings.compression_level > 9)
      throw input_error("", "--compression-level", codec + " takes a level from 1 to 9");
  }
  check_exr_settings(options.aovs, settings);
  if (!options.preview.empty() && !options.aovs.beauty)
    throw input_error("", "--preview", "the preview shows the beauty; add beauty to --aovs");
  return settings;
}

}  // namespace kiln
