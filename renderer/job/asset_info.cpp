#include "job/asset_info.h"

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "job/render_job.h"
#include "job/render_job_steps.h"

namespace kiln {

namespace {

using json = nlohmann::json;

// The scene a render shows: --scene, else the file's default, else the first (the loader's rule).
int shown_scene(const render_options& options, const gltf_summary& declared) {
  if (declared.scenes.empty()) return -1;
  if (options.scene_index >= 0) return options.scene_index;
  return declared.default_scene >= 0 ? declared.default_scene : 0;
}

void count_geometry(const scene& world, asset_info& info) {
  info.geometry.assign(info.declared.nodes.size(), {});
  for (const instance& inst : world.instances) {
    const bool mesh = inst.kind == shape_kind::mesh;
    const uint64_t triangles = mesh ? world.meshes[inst.shape].indices.size() / 3 : 0;
    info.triangles += triangles;
    info.quadrics += mesh ? 0 : 1;
    if (inst.node >= info.geometry.size()) continue;
    info.geometry[inst.node].triangles += triangles;
    info.geometry[inst.node].quadrics += mesh ? 0 : 1;
  }
  info.instances = world.instances.size();
  info.meshes = world.meshes.size();
}

json vector_json(const dvec3& v) { return json::array({v.x, v.y, v.z}); }

json camera_json(const camera& c, size_t index) {
  json j = {{"index", index}, {"name", c.name}};
  if (c.kind == projection::perspective) {
    j["type"] = "perspective";
    j["yfov_degrees"] = double(c.yfov) * 180.0 / glm::pi<double>();
  } else {
    j["type"] = "orthographic";
    j["xmag"] = c.xmag;
    j["ymag"] = c.ymag;
  }
  if (c.aspect_ratio > 0.0f) j["aspect_ratio"] = c.aspect_ratio;
  j["position"] = vector_json(dvec3(c.world_from_camera[3]));
  return j;
}

json node_json(const gltf_node_summary& n, size_t index, const node_geometry& g) {
  json j = {{"index", index},
            {"name", n.name},
            {"children", n.children},
            {"triangles", g.triangles},
            {"quadrics", g.quadrics}};
  if (n.mesh >= 0) j["mesh"] = n.mesh;
  if (n.camera >= 0) j["camera"] = n.camera;
  if (n.light >= 0) j["light"] = n.light;
  return j;
}

json declared_json(const gltf_summary& d) {
  json j;
  j["scenes"] = json::array();
  for (const gltf_scene_summary& s : d.scenes) j["scenes"].push_back({{"name", s.name}, {"nodes", s.nodes}});
  j["animations"] = json::array();
  for (size_t i = 0; i < d.animations.size(); ++i) {
    const gltf_animation_summary& a = d.animations[i];
    j["animations"].push_back({{"index", i},
                               {"name", a.name},
                               {"start", a.start},
                               {"end", a.end},
                               {"duration", a.end - a.start},
                               {"channels", a.channels}});
  }
  j["variants"] = d.variants;
  j["lights"] = json::array();
  for (size_t i = 0; i < d.lights.size(); ++i) {
    const gltf_light_summary& l = d.lights[i];
    j["lights"].push_back({{"index", i},
                           {"name", l.name},
                           {"type", l.type},
                           {"color", {l.color.r, l.color.g, l.color.b}},
                           {"intensity", l.intensity},
                           {"range", l.range}});
  }
  j["extensions"] = json::array();
  for (const gltf_extension_summary& e : d.extensions)
    j["extensions"].push_back(
        {{"name", e.name}, {"required", e.required}, {"support", extension_support_name(e.support)}});
  return j;
}

}  // namespace

asset_info describe_asset(const render_options& options, const std::atomic<bool>* cancel,
                          const std::function<void(const std::string&)>& warn) {
  const prepared_scene prepared = prepare_scene(options, cancel, warn);
  return describe_prepared(options, prepared,
                           summarize_gltf(options.input, job_load_options(options, cancel, nullptr)));
}

asset_info describe_prepared(const render_options& options, const prepared_scene& prepared,
                             gltf_summary declared) {
  asset_info info;
  info.file = options.input;
  info.declared = std::move(declared);
  info.scene_index = shown_scene(options, info.declared);
  info.cameras = prepared.world.cameras;
  // Back from camera-relative render space (render/render_space.h) to the file's world space.
  for (camera& c : info.cameras) c.world_from_camera[3] += dvec4(prepared.world.render_origin, 0.0);
  count_geometry(prepared.world, info);
  info.bounds = world_bounds(prepared.world);
  if (!info.bounds.empty()) {
    info.bounds.lower += prepared.world.render_origin;
    info.bounds.upper += prepared.world.render_origin;
  }
  info.view = prepared.camera_description;
  info.lighting = prepared.lighting;
  info.width = prepared.cam.width;
  info.height = prepared.cam.height;
  info.samples_per_pixel = samples_per_pixel_of(options);
  info.estimate = estimate_job(prepared, options);
  return info;
}

std::string asset_info_json(const asset_info& info) {
  json j = declared_json(info.declared);
  j["file"] = info.file;
  j["generator"] = info.declared.generator;
  j["scene"] = info.scene_index;
  j["cameras"] = json::array();
  for (size_t i = 0; i < info.cameras.size(); ++i) j["cameras"].push_back(camera_json(info.cameras[i], i));
  j["nodes"] = json::array();
  for (size_t i = 0; i < info.declared.nodes.size(); ++i)
    j["nodes"].push_back(node_json(info.declared.nodes[i], i, info.geometry[i]));
  j["geometry"] = {{"triangles", info.triangles},
                   {"quadrics", info.quadrics},
                   {"instances", info.instances},
                   {"meshes", info.meshes}};
  j["bounds"] = info.bounds.empty()
                    ? json(nullptr)
                    : json{{"min", vector_json(info.bounds.lower)}, {"max", vector_json(info.bounds.upper)}};
  const plan_estimate& e = info.estimate;
  j["render"] = {{"width", info.width},
                 {"height", info.height},
                 {"spp", info.samples_per_pixel},
                 {"view", info.view},
                 {"lighting", info.lighting},
                 {"peak_memory_bytes", e.peak_memory_bytes},
                 {"load_seconds", e.load_seconds},
                 {"render_seconds_one_thread", e.render_seconds}};
  return j.dump(2, ' ', false, json::error_handler_t::replace);
}

}  // namespace kiln
