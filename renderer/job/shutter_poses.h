// Motion blur's poses (--shutter): the asset posed at evenly spaced times across the shutter, and
// what moves among them kept in the frame's scene (scene::shutter) for Embree's time steps and for
// shading at each ray's time. Internal to the job layer.
#pragma once

#include <cstdint>
#include <vector>

#include "io/gltf/gltf_loader.h"
#include "job/render_options.h"
#include "render/motion_vectors.h"

namespace kiln {

// The asset at one step of the shutter, in world space.
struct shutter_step {
  std::vector<instance_key> keys;        // per instance of the step's scene
  std::vector<dmat4> world_from_object;  // per instance
  std::vector<bounds3> shape_bounds;     // per instance: its shape's object-space bounds
  // Per mesh: its positions and normals when the step deformed it (a skin or morph), else empty.
  std::vector<std::vector<vec3>> positions, normals;
  view_camera view;  // the job's view of the step (world space)
};

// The fewest steps the default tries, and the most: 2, 3, 5, ..., 33.
constexpr uint32_t max_default_motion_steps = 33;

// The shutter's steps for the frame at `time` seconds: options.shutter's frame offsets at --fps.
// --motion-steps gives their count; by default it is the fewest of 2, 3, 5, 9, 17, 33 for which,
// halfway between two steps, linear interpolation stays within a quarter pixel (as the job's view
// sees it) of where the animation puts every moving shape's bounds and every deforming vertex. framing: the
// default camera's (job_view). `chain` is the scene posed last (gltf_sequence::pose's previous, or null); it
// then holds the last step's scene, which the next pose takes its unchanged parts from.
std::vector<shutter_step> pose_shutter_steps(gltf_sequence& asset, const render_options& options, double time,
                                             const bounds3* framing, scene*& chain, scene& last);

// Keeps in world.shutter what moves among the steps, matched to world's instances by instance_key
// (one a step lacks holds still there); leaves it empty when nothing moves.
void attach_shutter_motion(scene& world, const std::vector<shutter_step>& steps);

// The job's view at each step when it is a glTF camera that moves during the shutter (camera
// blur), in world space; empty otherwise. A look-at or default camera holds still.
std::vector<view_camera> shutter_camera_steps(const render_options& options, const scene& world,
                                              const std::vector<shutter_step>& steps);

// Bytes world.shutter holds.
uint64_t shutter_motion_bytes(const shutter_motion& motion);

}  // namespace kiln
