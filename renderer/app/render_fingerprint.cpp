#include "app/render_fingerprint.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "app/interrupt.h"
#include "io/file/input_file.h"
#include "io/exr/environment_reader.h"
#include "io/gltf/gltf_references.h"

namespace kiln {

namespace {

namespace fs = std::filesystem;

// FNV-1a, 64 bit: cheap and stable across platforms; a fingerprint, not a defence.
struct fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(const char* data, size_t size) {
    for (size_t k = 0; k < size; ++k) h = (h ^ uint8_t(data[k])) * 0x100000001b3ull;
  }
  void add(const std::string& text) { add(text.data(), text.size() + 1); }  // the NUL separates fields
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", (unsigned long long)h);
    return text;
  }
};

// Hashes the file's bytes through the input-file reader: a FIFO or a device is refused before a
// byte is read (input error, exit 2), and SIGINT/SIGTERM stop the hash within a chunk. A missing
// file hashes as nothing; the loader names it in its own words.
void add_file(fnv1a& hash, const std::string& path, uint64_t max_bytes, const std::string& where = "") {
  if (input_file_missing(path)) return;
  read_input_file(path, {max_bytes, &interrupt_requested(), "", where},
                  [&hash](const char* bytes, size_t count) { hash.add(bytes, count); });
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// Nine significant digits read back to the same float.
std::string number(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(value));
  return text;
}

template <typename V>
std::string triple(const V& v) {
  return number(v.x) + "," + number(v.y) + "," + number(v.z);
}

}  // namespace

std::vector<std::string> canonical_render_arguments(const render_options& o, region_arguments region) {
  std::vector<std::string> a;
  auto add = [&a](const char* name, const std::string& value) {
    a.push_back(name);
    a.push_back(value);
  };
  if (o.width) add("--width", std::to_string(*o.width));
  if (o.height) add("--height", std::to_string(*o.height));
  add("--spp", std::to_string(o.samples_per_pixel));
  add("--sampler", o.sampler);
  add("--filter", o.filter);
  if (o.filter_radius) add("--filter-radius", number(*o.filter_radius));
  add("--adaptive-threshold", number(o.adaptive_threshold));
  add("--adaptive-depth", std::to_string(o.adaptive_depth));
  add("--tile-size", std::to_string(o.tile_size));
  if (!o.camera.empty()) add("--camera", o.camera);
  if (o.look_from) add("--look-from", triple(*o.look_from));
  if (o.look_at) add("--look-at", triple(*o.look_at));
  add("--up", triple(o.up));
  add("--fov", number(o.fov_degrees));
  if (o.scene_index >= 0) add("--scene", std::to_string(o.scene_index));
  if (o.full_float) a.push_back("--float");
  if (!o.channel_formats.empty()) add("--channel-format", o.channel_formats);
  add("--aovs", aov_list_name(o.aovs));
  add("--cryptomatte-depth", std::to_string(o.aovs.crypto_depth));
  add("--depth-mode", o.aovs.depth_kind == depth_mode::planar ? "planar" : "distance");
  // How the file stores the pixels: a stored file in another layout is stale too.
  add("--compression", o.exr.compression);
  if (o.exr.compression_level > 0) add("--compression-level", std::to_string(o.exr.compression_level));
  if (o.exr_tiled) a.push_back("--tiled");
  if (o.exr_tile_size > 0) add("--exr-tile-size", std::to_string(o.exr_tile_size));
  if (o.exr.multipart) a.push_back("--multipart");
  if (region == region_arguments::include) {
    if (o.crop)
      add("--crop", std::to_string(o.crop->x0) + "," + std::to_string(o.crop->y0) + "," +
                        std::to_string(o.crop->x1) + "," + std::to_string(o.crop->y1));
    if (o.tile_count > 0) add("--tile", std::to_string(o.tile_index) + "/" + std::to_string(o.tile_count));
  }
  add("--background", triple(o.background));
  if (o.show_background) a.push_back("--show-background");
  if (o.transmission_alpha != "opaque") add("--transmission-alpha", o.transmission_alpha);
  add("--accel", o.accel);
  // Pixels do not depend on the BVH build, but a plan must reproduce the run; --packets can pick
  // the other of two coincident surfaces, so it counts as a pixel setting.
  add("--bvh-quality", bvh_quality_name(o.embree.quality));
  if (o.embree.compact) a.push_back("--bvh-compact");
  add("--packets", o.packets ? "on" : "off");
  add("--grid-density", number(o.grid.density));
  if (o.grid.resolution) add("--grid-resolution", triple(glm::dvec3(*o.grid.resolution)));
  add("--grid-max-items", std::to_string(o.grid.max_items_per_cell));
  add("--grid-max-depth", std::to_string(o.grid.max_depth));
  if (!o.environment.empty()) add("--environment", fs::absolute(o.environment).lexically_normal().string());
  add("--environment-rotation", number(o.environment_rotation_degrees));
  add("--environment-intensity", number(o.environment_intensity));
  add("--max-depth", std::to_string(o.max_depth));
  add("--min-throughput", number(o.min_throughput));
  if (o.allow_outside_files) a.push_back("--allow-outside-files");
  add("--max-json-bytes", std::to_string(o.max_json_bytes));
  add("--max-json-depth", std::to_string(o.max_json_depth));
  add("--max-nodes", std::to_string(o.max_nodes));
  add("--max-instances", std::to_string(o.max_instances));
  add("--max-texels", std::to_string(o.max_texels));
  add("--max-pixels", std::to_string(o.max_pixels));
  return a;
}

std::string file_hash_hex(const std::string& path) {
  fnv1a hash;
  add_file(hash, path, max_gltf_file_bytes);
  return hash.hex();
}

render_fingerprint make_fingerprint(const render_options& options) {
  fnv1a inputs;
  add_file(inputs, options.input, max_gltf_file_bytes);
  // Each referenced file by its name and bytes, so renaming a buffer counts as a change too. The
  // list comes through the loader's URI rule: nothing outside the folder, no FIFO, no device.
  // A missing asset names nothing; the loader reports it.
  if (!input_file_missing(options.input)) {
    gltf_load_options rules;
    rules.allow_files_outside_folder = options.allow_outside_files;
    rules.limits.max_json_bytes = options.max_json_bytes;
    rules.cancel = &interrupt_requested();
    std::error_code ec;
    const fs::path folder = fs::weakly_canonical(fs::absolute(options.input, ec).parent_path(), ec);
    for (const std::string& file : gltf_referenced_files(options.input, rules)) {
      inputs.add(fs::path(file).lexically_relative(folder).string());
      fnv1a bytes;
      add_file(bytes, file, max_gltf_file_bytes);
      inputs.add(bytes.hex());
    }
  }
  if (!options.environment.empty()) {
    inputs.add("environment");
    fnv1a bytes;
    add_file(bytes, options.environment, max_environment_file_bytes, "--environment");
    inputs.add(bytes.hex());
  }
  fnv1a settings, frame;
  for (const std::string& argument : canonical_render_arguments(options, region_arguments::include))
    settings.add(argument);
  for (const std::string& argument : canonical_render_arguments(options, region_arguments::omit))
    frame.add(argument);
  return {inputs.hex(), settings.hex(), frame.hex()};
}

}  // namespace kiln
