// The canonical render arguments and the two hashes a batch resumes by: every option that can
// change pixels changes the settings hash, the ones that cannot (threads, quiet, output) do not;
// the canonical arguments read back through the render parser to the same settings; the input
// hash follows the asset, its buffer and image files, and the environment map.
#include "app/render_fingerprint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <utility>

#include "app/batch_command.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

std::string settings_hash(const render_options& o) { return make_fingerprint(o).settings_hash; }

TEST(render_fingerprint, every_pixel_setting_changes_the_settings_hash) {
  const render_options base;
  const std::vector<std::pair<const char*, std::function<void(render_options&)>>> changes = {
      {"width", [](render_options& o) { o.width = 64; }},
      {"height", [](render_options& o) { o.height = 48; }},
      {"spp", [](render_options& o) { o.samples_per_pixel = 4; }},
      {"filter", [](render_options& o) { o.filter = "tent"; }},
      {"sampler", [](render_options& o) { o.sampler = "random"; }},
      {"filter radius", [](render_options& o) { o.filter_radius = 0.75f; }},
      {"adaptive threshold", [](render_options& o) { o.adaptive_threshold = 0.1f; }},
      {"adaptive depth", [](render_options& o) { o.adaptive_depth = 2; }},
      {"tile size", [](render_options& o) { o.tile_size = 16; }},
      {"camera", [](render_options& o) { o.camera = "1"; }},
      {"look from", [](render_options& o) { o.look_from = dvec3(1, 2, 3); }},
      {"look at", [](render_options& o) { o.look_at = dvec3(0, 0, -1); }},
      {"up", [](render_options& o) { o.up = dvec3(0, 0, 1); }},
      {"fov", [](render_options& o) { o.fov_degrees = 30.0; }},
      {"scene", [](render_options& o) { o.scene_index = 1; }},
      {"float", [](render_options& o) { o.full_float = true; }},
      {"aovs", [](render_options& o) { o.aovs.normal = false; }},
      {"cryptomatte depth", [](render_options& o) { o.aovs.crypto_depth = 4; }},
      {"depth mode", [](render_options& o) { o.aovs.depth_kind = depth_mode::planar; }},
      {"cryptomatte", [](render_options& o) { o.aovs.crypto_object = true; }},
      {"light split", [](render_options& o) { o.aovs.reflection = true; }},
      {"bvh quality", [](render_options& o) { o.embree.quality = bvh_quality::high; }},
      {"bvh compact", [](render_options& o) { o.embree.compact = true; }},
      {"packets", [](render_options& o) { o.packets = true; }},
      {"channel format", [](render_options& o) { o.channel_formats = "N=float"; }},
      {"compression", [](render_options& o) { o.exr.compression = "piz"; }},
      {"compression level", [](render_options& o) { o.exr.compression_level = 9; }},
      {"tiled", [](render_options& o) { o.exr_tiled = true; }},
      {"exr tile size", [](render_options& o) { o.exr_tile_size = 16; }},
      {"multipart", [](render_options& o) { o.exr.multipart = true; }},
      {"crop",
       [](render_options& o) {
         o.crop = pixel_rect{0, 0, 8, 8};
       }},
      {"tile", [](render_options& o) { o.tile_index = 1, o.tile_count = 4; }},
      {"background", [](render_options& o) { o.background = vec3(0.5f); }},
      {"show background", [](render_options& o) { o.show_background = true; }},
      {"transmission alpha", [](render_options& o) { o.transmission_alpha = "transparent"; }},
      {"accel", [](render_options& o) { o.accel = "grid"; }},
      {"grid density", [](render_options& o) { o.grid.density = 4.0; }},
      {"grid resolution", [](render_options& o) { o.grid.resolution = glm::ivec3(8); }},
      {"grid max items", [](render_options& o) { o.grid.max_items_per_cell = 3; }},
      {"grid max depth", [](render_options& o) { o.grid.max_depth = 1; }},
      {"environment", [](render_options& o) { o.environment = "sky.hdr"; }},
      {"environment rotation", [](render_options& o) { o.environment_rotation_degrees = 90.0; }},
      {"environment intensity", [](render_options& o) { o.environment_intensity = 2.0f; }},
      {"max depth", [](render_options& o) { o.max_depth = 2; }},
      {"min throughput", [](render_options& o) { o.min_throughput = 0.01f; }},
      {"outside files", [](render_options& o) { o.allow_outside_files = true; }},
      {"max json bytes", [](render_options& o) { o.max_json_bytes = 1000; }},
      {"max json depth", [](render_options& o) { o.max_json_depth = 10; }},
      {"max nodes", [](render_options& o) { o.max_nodes = 10; }},
      {"max instances", [](render_options& o) { o.max_instances = 10; }},
      {"max texels", [](render_options& o) { o.max_texels = 10; }},
      {"max pixels", [](render_options& o) { o.max_pixels = 10; }},
  };
  const std::string reference = settings_hash(base);
  EXPECT_EQ(reference.size(), 16u);
  for (const auto& [name, change] : changes) {
    render_options changed = base;
    change(changed);
    EXPECT_NE(settings_hash(changed), reference) << name << " does not reach the settings hash";
  }
}

TEST(render_fingerprint, threads_quiet_output_and_command_line_leave_the_settings_hash) {
  render_options base, other;
  other.threads = 3;
  other.quiet = true;
  other.output = "elsewhere.exr";
  other.command_line = "kiln render x";
  other.summary_line = false;
  EXPECT_EQ(settings_hash(other), settings_hash(base));
}

TEST(render_fingerprint, canonical_arguments_parse_back_to_the_same_settings) {
  render_options o;
  o.width = 33;
  o.samples_per_pixel = 5;
  o.filter = "gaussian";
  o.filter_radius = 1.2345678f;
  o.camera = "Main Cam";
  o.look_from = dvec3(0.1, -2.5, 1e-7);
  o.look_at = dvec3(0, 0, -1);
  o.fov_degrees = 33.333333333333336;
  o.full_float = true;
  o.aovs.albedo = true;
  o.aovs.depth = false;
  o.tile_index = 2;
  o.tile_count = 3;
  o.background = vec3(0.1f, 0.2f, 0.3f);
  o.show_background = true;
  o.transmission_alpha = "transparent";
  o.accel = "adaptive-grid";
  o.grid.resolution = glm::ivec3(4, 5, 6);
  o.min_throughput = 0.0123f;
  o.max_nodes = 77;
  o.channel_formats = "beauty=float,uv=half";
  o.exr.compression = "dwaa";
  o.exr.compression_level = 60;
  o.exr_tile_size = 32;
  o.exr.multipart = true;
  o.aovs.crypto_material = true;
  o.aovs.crypto_depth = 8;
  o.embree.quality = bvh_quality::low;
  o.packets = true;
  o.aovs.depth_kind = depth_mode::planar;
  const std::vector<std::string> args = canonical_render_arguments(o, region_arguments::include);
  render_options parsed;
  apply_render_arguments(parsed, args);
  EXPECT_EQ(canonical_render_arguments(parsed, region_arguments::include), args);
  EXPECT_EQ(settings_hash(parsed), settings_hash(o));
  EXPECT_EQ(parsed.filter_radius, o.filter_radius);
  EXPECT_EQ(parsed.look_from, o.look_from);
  EXPECT_EQ(parsed.fov_degrees, o.fov_degrees);
  EXPECT_EQ(parsed.min_throughput, o.min_throughput);
  EXPECT_EQ(parsed.camera, "Main Cam");
  EXPECT_EQ(parsed.transmission_alpha, "transparent");
  EXPECT_EQ(parsed.tile_count, 3);
  EXPECT_EQ(parsed.exr.compression, "dwaa");
  EXPECT_EQ(parsed.exr.compression_level, 60);
  EXPECT_EQ(parsed.exr_tile_size, 32);
  EXPECT_TRUE(parsed.exr.multipart);
  EXPECT_TRUE(parsed.aovs.crypto_material);
  EXPECT_EQ(parsed.aovs.crypto_depth, 8);
  EXPECT_EQ(parsed.embree.quality, bvh_quality::low);
  EXPECT_TRUE(parsed.packets);
  EXPECT_EQ(parsed.aovs.depth_kind, depth_mode::planar);
  EXPECT_EQ(parsed.channel_formats, "beauty=float,uv=half");
  // Without the region the same settings lack only --tile.
  const std::vector<std::string> without = canonical_render_arguments(o, region_arguments::omit);
  EXPECT_EQ(without.size() + 2, args.size());
  EXPECT_EQ(std::find(without.begin(), without.end(), "--tile"), without.end());
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(render_fingerprint, input_hash_follows_the_asset_and_every_file_it_names) {
  const fs::path dir = fs::temp_directory_path() / ("kiln_fingerprint_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  write(dir / "a.gltf",
        R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "geo%20metry.bin", "byteLength": 4}],
            "images": [{"uri": "tex.png"}, {"uri": "data:image/png;base64,AAAA"}]})");
  write(dir / "geo metry.bin", "abcd");
  write(dir / "tex.png", "png1");
  write(dir / "sky.hdr", "sky1");
  render_options o;
  o.input = (dir / "a.gltf").string();
  o.environment = (dir / "sky.hdr").string();
  const std::string first = make_fingerprint(o).input_hash;
  EXPECT_EQ(make_fingerprint(o).input_hash, first);  // the same bytes, the same hash
  write(dir / "geo metry.bin", "abce");
  const std::string after_buffer = make_fingerprint(o).input_hash;
  EXPECT_NE(after_buffer, first);
  write(dir / "tex.png", "png2");
  const std::string after_image = make_fingerprint(o).input_hash;
  EXPECT_NE(after_image, after_buffer);
  write(dir / "sky.hdr", "sky2");
  EXPECT_NE(make_fingerprint(o).input_hash, after_image);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kiln
