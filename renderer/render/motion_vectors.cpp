#include "render/motion_vectors.h"

#include <map>
#include <optional>
#include <tuple>

#include "scene/shutter_motion.h"

namespace kiln {

namespace {

dmat4 raster_from_world(const view_camera& cam) {
  dmat4 to_pixels(1.0);
  to_pixels[0][0] = double(cam.width);
  to_pixels[1][1] = double(cam.height);
  return to_pixels * world_to_ndc(cam);
}

// Where the hit lies in its shape's object space at a pose: by barycentrics on the triangle (through
// that pose's deformed positions), or the render-space point taken back for a quadric.
dvec3 object_point(const frame_pose& pose, const scene& world, const hit& h, const dvec3& render_position,
                   float time) {
  const instance& inst = world.instances[h.instance_id];
  if (inst.kind != shape_kind::mesh)  // taken back where the instance was when the ray met it
    return dvec3(instance_at(world, h.instance_id, time).object_from_world * dvec4(render_position, 1.0));
  const mesh& m = world.meshes[inst.shape];
  const bool deformed =
      inst.shape < pose.deformed_positions.size() && !pose.deformed_positions[inst.shape].empty();
  const std::vector<vec3>& positions = deformed ? pose.deformed_positions[inst.shape] : m.positions;
  const uint32_t* idx = &m.indices[size_t(h.primitive_id) * 3];
  const double u = h.u, v = h.v;
  return (1.0 - u - v) * dvec3(positions[idx[0]]) + u * dvec3(positions[idx[1]]) +
         v * dvec3(positions[idx[2]]);
}

// The pixel position of the hit at a pose, if it is in front of that camera.
std::optional<glm::dvec2> raster_at(const frame_pose& pose, const scene& world, const hit& h,
                                    const dvec3& render_position, float time) {
  if (h.instance_id >= pose.present.size() || !pose.present[h.instance_id]) return std::nullopt;
  const dvec4 world_point =
      pose.world_from_object[h.instance_id] * dvec4(object_point(pose, world, h, render_position, time), 1.0);
  const dvec4 clip = pose.world_to_raster * world_point;
  if (!(clip.w > 0.0)) return std::nullopt;
  return glm::dvec2(clip.x / clip.w, clip.y / clip.w);
}

}  // namespace

std::vector<instance_key> instance_keys(const scene& s) {
  std::map<std::tuple<uint32_t, int, uint32_t>, uint32_t> seen;
  std::vector<instance_key> keys;
  keys.reserve(s.instances.size());
  for (const instance& inst : s.instances) {
    uint32_t& order = seen[{inst.node, int(inst.kind), inst.shape}];
    keys.emplace_back(inst.node, int(inst.kind), inst.shape, order++);
  }
  return keys;
}

frame_pose current_pose(const scene& s, const view_camera& cam) {
  frame_pose pose;
  pose.world_to_raster = raster_from_world(cam);
  pose.world_from_object.reserve(s.instances.size());
  for (const instance& inst : s.instances) pose.world_from_object.push_back(inst.world_from_object);
  pose.present.assign(s.instances.size(), 1);
  return pose;
}

frame_pose neighbour_pose(const scene& current, const scene& neighbour, const view_camera& cam,
                          const std::vector<uint32_t>& deformed) {
  frame_pose pose;
  pose.world_to_raster = raster_from_world(cam);
  std::map<instance_key, uint32_t> at_neighbour;
  const std::vector<instance_key> neighbour_keys = instance_keys(neighbour);
  for (uint32_t i = 0; i < neighbour_keys.size(); ++i) at_neighbour.emplace(neighbour_keys[i], i);
  const std::vector<instance_key> keys = instance_keys(current);
  pose.world_from_object.assign(keys.size(), dmat4(1.0));
  pose.present.assign(keys.size(), 0);
  for (size_t i = 0; i < keys.size(); ++i) {
    const auto found = at_neighbour.find(keys[i]);
    if (found == at_neighbour.end()) continue;
    pose.world_from_object[i] = neighbour.instances[found->second].world_from_object;
    pose.present[i] = 1;
  }
  // A deformed mesh follows its vertices; one whose vertex count changed cannot be followed, and
  // its instances have no motion.
  pose.deformed_positions.resize(current.meshes.size());
  for (uint32_t m : deformed) {
    if (m >= current.meshes.size() || m >= neighbour.meshes.size()) continue;
    if (neighbour.meshes[m].positions.size() == current.meshes[m].positions.size()) {
      pose.deformed_positions[m] = neighbour.meshes[m].positions;
      continue;
    }
    for (size_t i = 0; i < keys.size(); ++i)
      if (current.instances[i].kind == shape_kind::mesh && current.instances[i].shape == m)
        pose.present[i] = 0;
  }
  return pose;
}

vec4 hit_motion(const scene_motion& m, const scene& world, const hit& h, const dvec3& render_position,
                float time) {
  const std::optional<glm::dvec2> now = raster_at(m.current, world, h, render_position, time);
  if (!now) return vec4(0.0f);
  // Pixels run down the image; motion vectors' v runs up.
  auto toward = [&](const frame_pose& pose) {
    const std::optional<glm::dvec2> there = raster_at(pose, world, h, render_position, time);
    return there ? vec2(float(there->x - now->x), float(now->y - there->y)) : vec2(0.0f);
  };
  const vec2 forward = toward(m.next), backward = toward(m.previous);
  return vec4(forward, backward);
}

}  // namespace kiln
