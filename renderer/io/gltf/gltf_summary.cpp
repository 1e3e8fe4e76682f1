#include "io/gltf/gltf_summary.h"

#include <algorithm>

#include "io/gltf/gltf_animation.h"
#include "io/gltf/gltf_parse.h"
#include "io/gltf/gltf_validate.h"
#include "io/gltf/gltf_variants.h"

namespace kiln {

using namespace gltf_internal;

const char* extension_support_name(extension_support support) {
  switch (support) {
    case extension_support::supported:
      return "supported";
    case extension_support::ignored:
      return "ignored";
    default:
      return "refused";
  }
}

extension_support gltf_extension_support(const std::string& name, bool required) {
  const auto& known = supported_extensions();
  if (std::find(known.begin(), known.end(), name) != known.end()) return extension_support::supported;
  return required ? extension_support::refused : extension_support::ignored;
}

namespace {

std::vector<gltf_extension_summary> extension_summaries(const tinygltf::Model& model) {
  std::vector<std::string> names = model.extensionsUsed;
  for (const std::string& name : model.extensionsRequired)
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  std::vector<gltf_extension_summary> out;
  for (const std::string& name : names) {
    gltf_extension_summary e;
    e.name = name;
    e.required = std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), name) !=
                 model.extensionsRequired.end();
    e.support = gltf_extension_support(name, e.required);
    out.push_back(e);
  }
  return out;
}

gltf_light_summary light_summary(const tinygltf::Light& src) {
  gltf_light_summary l;
  l.name = src.name;
  l.type = src.type;
  if (src.color.size() == 3) l.color = vec3(float(src.color[0]), float(src.color[1]), float(src.color[2]));
  l.intensity = src.intensity;
  l.range = src.range;
  return l;
}

}  // namespace

gltf_summary summarize_gltf(const std::string& path, const gltf_load_options& options) {
  memory_charge held(options.memory);
  return summarize_model(parse_gltf_file(path, options, &held), path);
}

gltf_summary summarize_model(const tinygltf::Model& model, const std::string& path) {
  gltf_summary s;
  s.generator = model.asset.generator;
  s.default_scene = model.defaultScene;
  for (const tinygltf::Scene& scene : model.scenes) s.scenes.push_back({scene.name, scene.nodes});
  for (const tinygltf::Node& node : model.nodes)
    s.nodes.push_back({node.name, node.mesh, node.camera, node_light_index(node), node.children});
  for (size_t i = 0; i < model.animations.size(); ++i) {
    const tinygltf::Animation& animation = model.animations[i];
    const auto [start, end] = animation_time_range(model, {int(i)}, path);
    s.animations.push_back({animation.name, start, end, animation.channels.size()});
  }
  s.variants = material_variant_names(model, path);
  for (const tinygltf::Light& light : model.lights) s.lights.push_back(light_summary(light));
  s.extensions = extension_summaries(model);
  return s;
}

}  // namespace kiln
