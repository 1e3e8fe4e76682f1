#include "app/info_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <iostream>
#include <utility>

#include "app/interrupt.h"
#include "app/render_command.h"
#include "core/memory_budget.h"
#include "core/message_text.h"
#include "job/asset_info.h"

namespace kiln {

namespace {

// Deeper nodes are printed at this indent, with their depth: a chain of a million nodes stays
// a million lines, not a terabyte of spaces.
constexpr size_t max_indent_depth = 32;

std::string named(const std::string& name) { return name.empty() ? "(unnamed)" : quoted(name); }

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string triple(double x, double y, double z) {
  return "(" + number(x) + ", " + number(y) + ", " + number(z) + ")";
}

void print_cameras(const asset_info& info) {
  std::printf("cameras: %zu%s\n", info.cameras.size(),
              info.cameras.empty() ? "" : " (--camera INDEX or NAME)");
  for (size_t i = 0; i < info.cameras.size(); ++i) {
    const camera& c = info.cameras[i];
    const std::string lens =
        c.kind == projection::perspective
            ? "perspective, yfov " + number(c.yfov * 180.0 / glm::pi<double>()) + " degrees"
            : "orthographic, xmag " + number(c.xmag) + ", ymag " + number(c.ymag);
    std::printf("  %zu %s: %s\n", i, named(c.name).c_str(), lens.c_str());
  }
}

void print_declarations(const gltf_summary& d) {
  std::printf("animations: %zu%s\n", d.animations.size(),
              d.animations.empty() ? "" : " (--animation INDEX or NAME)");
  for (size_t i = 0; i < d.animations.size(); ++i) {
    const gltf_animation_summary& a = d.animations[i];
    std::printf("  %zu %s: %s s, %s to %s s, %zu channel%s\n", i, named(a.name).c_str(),
                number(a.end - a.start).c_str(), number(a.start).c_str(), number(a.end).c_str(), a.channels,
                a.channels == 1 ? "" : "s");
  }
  std::printf("variants: %zu%s\n", d.variants.size(), d.variants.empty() ? "" : " (--variant INDEX or NAME)");
  for (size_t i = 0; i < d.variants.size(); ++i) std::printf("  %zu %s\n", i, named(d.variants[i]).c_str());
  std::printf("lights: %zu\n", d.lights.size());
  for (size_t i = 0; i < d.lights.size(); ++i) {
    const gltf_light_summary& l = d.lights[i];
    std::printf("  %zu %s: %s, colour %s, intensity %s %s\n", i, named(l.name).c_str(), shown(l.type).c_str(),
                triple(l.color.r, l.color.g, l.color.b).c_str(), number(l.intensity).c_str(),
                l.type == "directional" ? "lx" : "cd");
  }
  std::printf("extensions: %zu\n", d.extensions.size());
  for (const gltf_extension_summary& e : d.extensions)
    std::printf("  %s (%s): %s\n", shown(e.name).c_str(), e.required ? "required" : "used",
                extension_support_name(e.support));
}

// One node's line: its index, name, what it holds and the geometry it places.
void print_node(const asset_info& info, int index, size_t depth) {
  const gltf_node_summary& n = info.declared.nodes[size_t(index)];
  const node_geometry& g = info.geometry[size_t(index)];
  std::string line(2 * std::min(depth + 1, max_indent_depth), ' ');
  if (depth >= max_indent_depth) line += "[depth " + std::to_string(depth) + "] ";
  line += std::to_string(index) + " " + named(n.name);
  if (n.mesh >= 0) line += ", mesh " + std::to_string(n.mesh);
  if (n.camera >= 0) line += ", camera " + std::to_string(n.camera);
  if (n.light >= 0) line += ", light " + std::to_string(n.light);
  if (g.triangles) line += ": " + std::to_string(g.triangles) + " triangles";
  if (g.quadrics) line += std::string(g.triangles ? ", " : ": ") + std::to_string(g.quadrics) + " quadrics";
  std::printf("%s\n", line.c_str());
}

// The scene's node tree, depth first, without recursion (the loader allows a million nodes deep).
void print_nodes(const asset_info& info) {
  const gltf_summary& d = info.declared;
  std::printf("scenes: %zu\n", d.scenes.size());
  for (size_t i = 0; i < d.scenes.size(); ++i)
    std::printf("  %zu %s: %zu root nodes%s\n", i, named(d.scenes[i].name).c_str(), d.scenes[i].nodes.size(),
                int(i) == info.scene_index ? " (rendered)" : "");
  if (info.scene_index < 0 || size_t(info.scene_index) >= d.scenes.size()) return;
  std::printf("nodes of scene %d:\n", info.scene_index);
  std::vector<std::pair<int, size_t>> stack;
  const std::vector<int>& roots = d.scenes[size_t(info.scene_index)].nodes;
  for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.emplace_back(*root, 0);
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    if (index < 0 || size_t(index) >= d.nodes.size()) continue;
    print_node(info, index, depth);
    const std::vector<int>& children = d.nodes[size_t(index)].children;
    for (auto child = children.rbegin(); child != children.rend(); ++child)
      stack.emplace_back(*child, depth + 1);
  }
}

void print_text(const asset_info& info) {
  std::printf("file: %s\n", shown(info.file).c_str());
  if (!info.declared.generator.empty())
    std::printf("generator: %s\n", shown(info.declared.generator).c_str());
  print_cameras(info);
  print_declarations(info.declared);
  print_nodes(info);
  std::printf("geometry: %llu triangles, %llu quadrics; %llu instances of %llu meshes\n",
              (unsigned long long)info.triangles, (unsigned long long)info.quadrics,
              (unsigned long long)info.instances, (unsigned long long)info.meshes);
  if (info.bounds.empty())
    std::printf("bounds: empty\n");
  else
    std::printf("bounds: %s to %s\n",
                triple(info.bounds.lower.x, info.bounds.lower.y, info.bounds.lower.z).c_str(),
                triple(info.bounds.upper.x, info.bounds.upper.y, info.bounds.upper.z).c_str());
  const plan_estimate& e = info.estimate;
  std::printf("render: %dx%d, %d spp, view %s, %s\n", info.width, info.height, info.samples_per_pixel,
              info.view.c_str(), info.lighting.c_str());
  std::printf("estimate: peak memory %s, load %.2f s, render %.2f s on one thread\n",
              memory_text(e.peak_memory_bytes).c_str(), e.load_seconds, e.render_seconds);
}

}  // namespace

void add_info_options(CLI::App& app, info_options& o) {
  add_view_options(app, o.view);
  app.add_flag("--json", o.json, "Print one JSON document (its keys: docs/info.md)");
}

void run_info(const info_options& options) {
  const asset_info info =
      describe_asset(options.view, &interrupt_requested(), [&options](const std::string& line) {
        if (!options.view.quiet) std::cerr << "kiln: " << line << '\n';
      });
  if (options.json)
    std::printf("%s\n", asset_info_json(info).c_str());
  else
    print_text(info);
}

}  // namespace kiln
