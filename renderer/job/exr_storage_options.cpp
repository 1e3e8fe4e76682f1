#include "job/exr_storage_options.h"

#include <sstream>

#include "core/error.h"
#include "io/exr/exr_writer.h"

namespace kiln {

namespace {

constexpr int default_exr_tile = 64;

// The format slot of a --channel-format AOV name; nullptr for names that have none. Throws for
// data AOVs asked to be half and for unknown names.
sample_format* format_slot(layer_formats& formats, const std::string& name, const std::string& format) {
  for (const aov_row& row : aov_table) {
    if (name != row.name) continue;
    if (!row.data) return &formats[row.id];
    if (format == "float") return nullptr;  // what it is anyway
    throw input_error("", "--channel-format",
                      name +
                          " is always 32-bit float (depth, positions, motion, ids and Cryptomatte need the "
                          "precision); only " +
                          selectable_format_aovs() + " can be half");
  }
  throw input_error("", "--channel-format",
                    "unknown AOV '" + name + "' (choose from " + selectable_format_aovs() + ")");
}

// "a, b, c": the names of the AOV table's rows that keep.
template <typename predicate>
std::string aov_names_where(predicate keep) {
  std::string out;
  for (const aov_row& row : aov_table)
    if (keep(row)) out += (out.empty() ? "" : ", ") + std::string(row.name);
  return out;
}

}  // namespace

const std::string& selectable_format_aovs() {
  static const std::string list = aov_names_where([](const aov_row& row) { return !row.data; });
  return list;
}

const std::string& half_by_default_aovs() {
  static const std::string list = aov_names_where([](const aov_row& row) { return row.half_by_default; });
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
  settings.formats = layer_formats{};  // uv float, the other colour layers half
  if (options.full_float)
    for (sample_format& format : settings.formats.of) format = sample_format::float32;
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
  if (!options.preview.empty() && !options.aovs.has(aov::beauty))
    throw input_error("", "--preview", "the preview shows the beauty; add beauty to --aovs");
  return settings;
}

}  // namespace kiln
