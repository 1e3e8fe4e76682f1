// The option table's second part: the environment, holdouts, the loader's limits, the memory budget,
// the traversal backend and the job's time limit.
#include <string>
#include <vector>

#include "core/error.h"
#include "job/lighting.h"
#include "job/option_entries.h"

namespace kiln::option_entries {

void add_trace_options(std::vector<option_spec>& t) {
  // Settings of one view like the first part's (a batch job may override them per view).
  scoped_adder add{t, option_scope::view};
  add.group = option_group::lighting;
  add(file_option(
          "environment", &render_options::environment,
          "Equirectangular environment map (EXR, HDR, ...; linear radiance): lights every surface and "
          "is seen by rays that leave the scene"))
      .recorded_as = "kiln/environment";
  add(choice_option(
          "lighting", [](render_options & o) -> auto& { return o.lighting; }, lighting_choices(), "studio",
          "What lights the scene: auto (the file's lights, and --environment or --background when given, "
          "else kiln's studio environment), studio (the studio environment alone), headlight (the "
          "file's lights, or a light at the camera when it has none) or file (the file's lights and the "
          "environment given, nothing added)"))
      .recorded_as = "kiln/lighting_mode";
  add(number_option<double>(
          "environment-rotation", [](render_options & o) -> auto& { return o.environment_rotation_degrees; },
          -36000.0, 36000.0, "90",
          "Turn the environment map about +Y by DEG degrees (counter-clockwise seen from above)"))
      .recorded_as = "kiln/environment_rotation";
  add(number_option<float>(
          "environment-intensity", [](render_options & o) -> auto& { return o.environment_intensity; }, 0.0,
          1e9, "2", "Scale of the environment map's radiance"))
      .recorded_as = "kiln/environment_intensity";
  add(integer_option<int>(
          "environment-samples", [](render_options & o) -> auto& { return o.environment_samples; }, 1, 1024,
          "4",
          "Environment light samples per shading point (each a pair: one drawn from the map, one from "
          "the material's lobes, combined by multiple importance sampling)"))
      .recorded_as = "kiln/environment_samples";
  add(flag_option(
          "show-background", [](render_options & o) -> auto& { return o.show_background; },
          "Camera rays that miss see the environment colour with alpha 1 (default: transparent, alpha 0)"))
      .recorded_as = "kiln/show_background";
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
  add.group = option_group::layers;
  add(node_patterns(
          "holdout", &render_options::holdout,
          "Render these nodes and their subtrees (names, /paths or globs, comma-separated) as holdout "
          "mattes: they cut alpha to zero and hide what is behind them, but still cast shadows and show "
          "in reflections"))
      .recorded_as = "kiln/holdout";
  add(node_patterns("only", &render_options::only,
                    "Render only these nodes and their subtrees (names, /paths or globs); every other node "
                    "is outside the layer, as --others says (a render layer: flat layers add with plus, deep "
                    "ones merge by depth)"))
      .recorded_as = "kiln/only";
  add(flag_option(
          "holdout-invisible", [](render_options & o) -> auto& { return o.holdout_invisible; },
          "Holdouts matte the camera only: they cast no shadows and do not show in reflections or "
          "through glass"))
      .recorded_as = "kiln/holdout_invisible";
  option_spec others = choice_option(
      "others", [](render_options & o) -> auto& { return o.others; }, {"auto", "invisible", "matte"},
      "invisible",
      "What a render layer (--only, --holdout) does with the nodes outside it: invisible (the "
      "layer's camera rays pass them by; they still cast shadows and show in reflections and "
      "through glass: deep layers merge by depth), matte (they cut alpha to zero: flat layers add "
      "with plus) or auto (invisible with --deep, else matte)");
  // Recorded as what it resolved to, so a file says which layer it is.
  others.get = [](const render_options& o) -> std::optional<std::string> {
    if (o.others != "auto") return o.others;
    if (o.holdout.empty() && o.only.empty()) return std::nullopt;
    return std::string(o.deep && !o.holdout_invisible ? "invisible" : "matte");
  };
  add(std::move(others)).recorded_as = "kiln/others";
  add.group = option_group::sampling;
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
  add.group = option_group::limits;
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
  add.group = option_group::performance;
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
      "off", "Trace each pixel's camera rays together as Embree packets: on or off (default on)"));
  t.back().recorded_as = "kiln/packets";
  t.back().choices = {"on", "off"};
  add(choice_option(
          "shading", [](render_options & o) -> auto& { return o.shading; }, {"wave", "reference"},
          "reference",
          "How a tile's samples are shaded: wave (the camera's hits of a run of samples made ready "
          "together, grouped by material, then shaded) or reference (each sample from its camera ray to "
          "its last bounce, one at a time: the scalar path the wave is held to)"))
      .recorded_as = "kiln/shading";
  add.group = option_group::limits;
  add(number_option<double>(
          "time-limit", [](render_options & o) -> auto& { return o.time_limit_seconds; }, 0.0, 1e9, "60",
          "Stop a job still loading or rendering after this many seconds: nothing is written, "
          "exit 124 (0 = no limit)"))
      .effect = option_effect::none;
  add.group = option_group::progress;
  option_spec& quiet = add(flag_option(
      "quiet", [](render_options & o) -> auto& { return o.quiet; }, "No progress line or summary"));
  quiet.short_name = "q";
  quiet.effect = option_effect::none;
}

}  // namespace kiln::option_entries
