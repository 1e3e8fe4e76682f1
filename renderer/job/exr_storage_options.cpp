#include "job/exr_storage_options.h"

#include <sstream>

#include "core/error.h"
#include "io/exr/exr_writer.h"

namespace kiln {

namespace {

constexpr int default_exr_tile = 64;

// The format slot of a --channel-format AOV name; nullptr for names that have none. Throws for
// data AOVs asked to be half and for unknown names.
sample_format* format_slot(layer_formats& formats, const std::string& aov, const std::string& format) {
  if (aov == "beauty") return &formats.beauty;
  if (aov == "N") return &formats.normal;
  if (aov == "albedo") return &formats.albedo;
  if (aov == "uv") return &formats.uv;
  if (aov == "direct") return &formats.direct;
  if (aov == "reflection") return &formats.reflection;
  if (aov == "refraction") return &formats.refraction;
  if (aov == "lightgroups") return &formats.light_groups;
  if (aov == "albedo_filtered") return &formats.albedo_filtered;
  if (aov == "N_filtered") return &formats.normal_filtered;
  if (aov == "diffuse") return &formats.diffuse;
  if (aov == "specular") return &formats.specular;
  if (aov == "shadow") return &formats.shadow;
  if (aov == "Z" || aov == "P" || aov == "id" || aov == "motion") {
    if (format == "float") return nullptr;  // what it is anyway
    throw input_error(
        "", "--channel-format",
        aov + " is always 32-bit float (depth, positions, motion and ids need the precision); only " +
            selectable_format_aovs() + " can be half");
  }
  throw input_error("", "--channel-format",
                    "unknown AOV '" + aov + "' (choose from " + selectable_format_aovs() + ")");
}

}  // namespace

const std::string& selectable_format_aovs() {
  static const std::string list =
      "beauty, N, albedo, uv, direct, reflection, refraction, lightgroups, albedo_filtered, N_filtered, "
      "diffuse, "
      "specular, shadow";
  return list;
}

std::string exr_part_list() {
  std::string list;
  for (const std::string& name : exr_part_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

void apply_channel_formats(const std::string& text, layer_formats& formats) {
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const size_t equals = item.find('=');
    const std::string aov = item.substr(0, equals);
    const std::string format = equals == std::string::npos ? std::string() : item.substr(equals + 1);
    if (format != "half" && format != "float")
      throw input_error("", "--channel-format", "expects AOV=half or AOV=float, got '" + item + "'");
    if (sample_format* slot = format_slot(formats, aov, format))
      *slot = format == "float" ? sample_format::float32 : sample_format::half;
  }
}

exr_settings resolve_exr_settings(const render_options& options) {
  exr_settings settings = options.exr;
  if (options.exr_tiled || options.exr_tile_size > 0)
    settings.tile_size = options.exr_tile_size > 0 ? options.exr_tile_size : default_exr_tile;
  const sample_format all = options.full_float ? sample_format::float32 : sample_format::half;
  settings.formats = {all, all, all, sample_format::float32,
                      all, all, all, all,  // uv: float either way
                      all, all, all, all,
                      all};
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
