// Motion vectors (--aovs motion): where the surface point a pixel's nearest sample hit lies one
// frame later and one frame earlier, as that frame's camera sees it, in pixels. The point is
// followed on its own surface: by its object-space position for rigid motion, by its triangle and
// barycentrics through a skin or morph. Depends on scene and render/view_camera.
//
// Conventions (docs/output.md, "What the EXR holds"): Nuke's forward and backward layers. forward = where the
// point is at the next frame minus where it is now, backward = at the previous frame minus now, u to the
// right and v up (Nuke's and Blender's y-up pixel space; the EXR's rows run down). Blender's
// Vector pass points back in time in both pairs: (backward.u, backward.v, −forward.u, −forward.v).
#pragma once

#include <cstdint>
#include <tuple>
#include <vector>

#include "core/math.h"
#include "core/ray.h"
#include "render/view_camera.h"
#include "scene/scene.h"

namespace kiln {

// The scene at one time as motion vectors need it, for the instances of the frame being rendered.
struct frame_pose {
  dmat4 world_to_raster{1.0};  // that time's camera: world -> full-frame pixels (y down), homogeneous
  std::vector<dmat4> world_from_object;  // per instance of the rendered frame, in world space
  std::vector<uint8_t> present;          // per instance: 0 when nothing at that time matches it
  // Per mesh of the rendered frame: its object-space positions at that time when it deforms there
  // (a skin or morph posed it); empty when the rendered frame's positions hold.
  std::vector<std::vector<vec3>> deformed_positions;
};

struct scene_motion {
  frame_pose previous, current, next;
};

// An instance's identity across times: its node, what it places, and its place among the
// instances of that node and shape (EXT_mesh_gpu_instancing places many).
using instance_key = std::tuple<uint32_t, int, uint32_t, uint32_t>;
std::vector<instance_key> instance_keys(const scene& s);

// The pose of `s` itself as camera `cam` sees it. Both in world space (before render space).
frame_pose current_pose(const scene& s, const view_camera& cam);

// The pose of `neighbour` (the same asset at another time, world space, seen by `cam`) for the
// instances of `current`. Instances are matched by glTF node, shape and order within the node (so
// one that drops out at some time does not shift the others); `deformed` lists the meshes the
// neighbour posed (gltf_sequence::pose's posed_meshes).
frame_pose neighbour_pose(const scene& current, const scene& neighbour, const view_camera& cam,
                          const std::vector<uint32_t>& deformed);

// (forward.u, forward.v, backward.u, backward.v) of hit h of `world` (the rendered frame, in render
// space; render_position is the hit point there, found at `time` in the shutter). A side whose
// point is unknown at that time (no matching instance, behind that camera) is 0.
vec4 hit_motion(const scene_motion& m, const scene& world, const hit& h, const dvec3& render_position,
                float time = 0.0f);

}  // namespace kiln
