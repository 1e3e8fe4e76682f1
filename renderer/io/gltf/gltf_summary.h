// What a glTF file declares, for `kiln info` and kiln.info(): its scenes, node tree, animations
// with their durations, material variants, punctual lights and extensions with kiln's support for
// each. Reads the file as the loader does (no scene is built); depends on io/gltf's parser only.
#pragma once

#include <string>
#include <vector>

#include "io/gltf/gltf_loader.h"

namespace tinygltf {
class Model;
}

namespace kiln {

// What kiln does with an extension a file names: implements it, leaves it out of the render (an
// optional extension it does not know), or refuses the file (a required one it does not know).
enum class extension_support { supported, ignored, refused };

// "supported", "ignored" or "refused".
const char* extension_support_name(extension_support support);

// The loader's own answer for one extension, from the list of extensions it implements.
extension_support gltf_extension_support(const std::string& name, bool required);

struct gltf_extension_summary {
  std::string name;
  bool required = false;  // listed in extensionsRequired (every such one is also in extensionsUsed)
  extension_support support = extension_support::supported;
};

struct gltf_node_summary {
  std::string name;
  int mesh = -1, camera = -1, light = -1;  // glTF indices; -1: none
  std::vector<int> children;
};

struct gltf_scene_summary {
  std::string name;
  std::vector<int> nodes;  // root nodes
};

struct gltf_animation_summary {
  std::string name;
  double start = 0.0, end = 0.0;  // first and last keyframe times, seconds
  size_t channels = 0;
};

// A KHR_lights_punctual definition (a node places it; units are glTF's).
struct gltf_light_summary {
  std::string name;
  std::string type;  // point, spot or directional
  vec3 color{1.0f};
  double intensity = 1.0;  // candela (point, spot) or lux (directional)
  double range = 0.0;      // 0: infinite
};

struct gltf_summary {
  std::string generator;   // asset.generator
  int default_scene = -1;  // the file's "scene"; -1: none marked
  std::vector<gltf_scene_summary> scenes;
  std::vector<gltf_node_summary> nodes;
  std::vector<gltf_animation_summary> animations;
  std::vector<std::string> variants;  // KHR_materials_variants, in order
  std::vector<gltf_light_summary> lights;
  std::vector<gltf_extension_summary> extensions;  // extensionsUsed, then any required but unused
};

// Reads and parses path as load_gltf does (the same limits, folder rules and refusals) and
// summarises it. Throws kiln::error (input) when that fails.
gltf_summary summarize_gltf(const std::string& path, const gltf_load_options& options = {});

// The summary of a model parsed already (gltf_sequence::summary); path names it in errors.
gltf_summary summarize_model(const tinygltf::Model& model, const std::string& path);

}  // namespace kiln
