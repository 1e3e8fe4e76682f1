#include "render/light_groups.h"

#include <set>

namespace kiln {

namespace {

constexpr const char* layer_prefix = "lightgroup_";

std::string sanitized(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    out += keep ? c : '_';
  }
  return out;
}

}  // namespace

std::vector<std::string> light_group_layers(const scene& world) {
  // The source groups' names are taken first, so a light called "emission" becomes "emission_2".
  std::set<std::string> taken = {"emission", "environment"};
  std::vector<std::string> layers;
  for (size_t i = 0; i < world.lights.size(); ++i) {
    const std::string base =
        world.lights[i].name.empty() ? "light" + std::to_string(i) : sanitized(world.lights[i].name);
    std::string name = base;
    for (int n = 2; taken.count(name); ++n) name = base + "_" + std::to_string(n);
    taken.insert(name);
    layers.push_back(layer_prefix + name);
  }
  layers.push_back(std::string(layer_prefix) + "emission");
  layers.push_back(std::string(layer_prefix) + "environment");
  return layers;
}

}  // namespace kiln
