// Everything a render is asked to do, as plain data: the asset, the output and every option of the
// option table (job/option_table.h), which is the one place that names, parses, validates,
// hashes and records them. The CLI, batch manifests and the Python module all fill this struct
// through that table.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "accel/embree/embree_options.h"
#include "accel/grid/grid.h"
#include "core/math.h"
#include "io/exr/exr_storage.h"
#include "io/gltf/gltf_loader.h"
#include "render/aov_list.h"
#include "render/tile_renderer.h"

namespace kiln {

// Bounds of --time and --frame: far past any shot, small enough that a frame's time is exact.
constexpr double max_scene_seconds = 1e9;
constexpr long long max_frame_number = 1000000000;

struct render_options {
  std::string input;
  // An asset in memory (kiln.load of a dict or bytes), which input then only names; null: the file.
  std::shared_ptr<const gltf_memory_asset> in_memory;
  std::string output;
  std::optional<int> width;
  std::optional<int> height;
  int spp_given = 0;                   // --spp; 0: not given (samples_per_pixel_of gives the default)
  std::string filter = "box";          // box | tent | gaussian | blackman-harris
  std::string sampler = "stratified";  // stratified | random (sample positions inside a pixel)
  std::optional<float> filter_radius;  // empty: the filter's default radius
  float adaptive_threshold = 0.0f;     // > 0: Whitted's adaptive supersampling instead of --spp
  int adaptive_depth = 4;  // chart 1: depth 2 stalls at RMSE 0.027 on the demo scene, 4 reaches 0.015
  int threads = 0;
  int tile_size = 32;
  std::string camera;  // glTF camera name or index; empty: the first camera, else a default view
  std::optional<dvec3> look_from;
  std::optional<dvec3> look_at;
  dvec3 up{0.0, 1.0, 0.0};
  double fov_degrees = 45.0;
  int scene_index = -1;
  // The pose (job/render_job.h: scene_time); each nullopt until given, so a still's settings stay.
  std::optional<double> time;            // --time SECONDS
  std::optional<long long> frame;        // --frame N
  std::optional<double> fps;             // --fps F (default 24)
  std::optional<long long> frame_start;  // --frame-start N: the frame at time 0 (default 1)
  std::optional<std::string> animation;  // --animation NAME|INDEX|all (default all)
  std::optional<std::string> variant;    // --variant NAME|INDEX: a KHR_materials_variants variant
  // --shutter OPEN,CLOSE: motion blur over that interval, in frames relative to the frame
  // (job/shutter_poses.h); empty: none. --motion-steps N: its time steps (0: chosen by the motion).
  std::optional<std::pair<double, double>> shutter;
  int motion_steps = 0;
  // --frames FIRST-LAST[:STEP]: a sequence (job/render_sequence.h), each frame its own --frame
  // and output; empty: one image.
  std::string frames;
  // --camera-view front|three-quarter|top|AZIMUTH,ELEVATION: the default camera's framing seen from
  // another direction (job/turntable.h); empty: the default camera (or the file's).
  std::string camera_view;
  // --turntable N: N frames orbiting the asset about +Y through its bounds' centre (job/turntable.h);
  // 0: none. Its elevation and start azimuth in degrees (defaults 20 and 0) and whether the animation
  // plays along (play, the default) or holds its pose (hold), each unset until given.
  long long turntable = 0;
  std::optional<double> turntable_elevation;
  std::optional<double> turntable_start;
  std::optional<std::string> turntable_animation;
  bool full_float = false;      // --float: every colour-like layer float
  std::string channel_formats;  // --channel-format AOV=half|float,... (checked when parsed)
  // --compression, --compression-level, --multipart; the formats come from resolve_exr_settings.
  exr_settings exr;
  bool exr_tiled = false;  // --tiled
  int exr_tile_size = 0;   // --exr-tile-size N (implies --tiled); 0: 64 when tiled
  std::string preview;     // --preview FILE.png|FILE.jpg; empty: none
  double preview_exposure = 0.0;
  // Colour (job/working_space.h): the OpenColorIO config (empty: $OCIO, else kiln's own), the
  // working space (empty: glTF's linear Rec.709, nothing converted and OpenColorIO never loaded),
  // and the preview's display and view (empty: the config's defaults).
  std::string ocio_config;
  std::string working_space;
  std::string display;
  std::string view;
  bool deep = false;                   // --deep: also a deep EXR beside -o (job/deep_output.h)
  aov_set aovs;                        // --aovs; the default is beauty, Z and N
  std::optional<pixel_rect> crop;      // --crop x0,y0,x1,y1; checked against the image size once it is known
  int band_index = 0, band_count = 0;  // --band i/N: band i of N (render/frame_bands.h); 0 bands: off
  std::optional<vec3> background;      // --background R,G,B: a constant environment; empty: not given
  bool show_background = false;
  std::string transmission_alpha = "opaque";    // --transmission-alpha opaque|transparent
  std::string holdout;                          // --holdout NODE,...: node names or globs held out
  std::string only;                             // --only NODE,...: everything else held out
  bool holdout_invisible = false;               // --holdout-invisible: holdouts only matte the camera
  std::string others = "auto";                  // --others auto|invisible|matte (job/holdouts.h)
  std::string accel = "embree";                 // embree | grid | adaptive-grid
  grid_options grid = adaptive_grid_options();  // --grid-*; the uniform grid drops max_depth
  embree_options embree;                        // --bvh-quality, --bvh-compact
  bool packets = true;                          // --packets on|off: trace each pixel's camera rays together
  std::string shading = "wave";                 // --shading wave|reference (render/tile_renderer.h)
  std::string environment;                      // equirectangular map file; empty: the --background colour
  std::string lighting = "auto";                // --lighting auto|studio|headlight|file (job/lighting.h)
  double environment_rotation_degrees = 0.0;
  float environment_intensity = 1.0f;
  int environment_samples = 2;  // --environment-samples: pairs of environment samples per shading point
  int max_depth = 8;
  float min_throughput = 1e-3f;
  uint64_t max_rays_per_sample = shading_options{}.max_rays_per_sample;  // --max-rays-per-sample
  bool allow_outside_files = false;
  gltf_limits limits;                   // --max-json-bytes, --max-json-depth, --max-nodes, ...
  size_t max_pixels = size_t(1) << 28;  // width × height; the film alone takes 32 bytes a pixel
  uint64_t max_memory = 0;  // --max-memory: the job's memory budget in bytes; 0: job/memory_limit.h's default
  double time_limit_seconds = 0.0;  // --time-limit: the whole job (load and render); 0: none
  bool quiet = false;
  bool summary_line = true;        // the closing line with timings and ray counts (kiln batch prints its own)
  double progress_interval = 5.0;  // seconds between progress lines when stderr is not a terminal
  bool batch_job = false;          // run by `kiln batch` as one of its jobs (hidden --batch-command-line)
  std::string command_line;
};

// Samples per pixel when --spp is not given: enough for anti-aliased edges and an environment's light
// without visible noise on the shipped assets (docs/rendering.md, "Anti-aliasing", has the measurements).
constexpr int default_samples_per_pixel = 16;

// The samples per pixel a render takes: --spp, else the default (1 under adaptive supersampling,
// which places its own samples).
inline int samples_per_pixel_of(const render_options& o) {
  if (o.spp_given > 0) return o.spp_given;
  return o.adaptive_threshold > 0.0f ? 1 : default_samples_per_pixel;
}

}  // namespace kiln
