#include "job/frame_motion.h"

#include "job/render_job_steps.h"
#include "job/shutter_poses.h"
#include "job/turntable.h"

namespace kiln {

namespace {

uint64_t pose_bytes(const frame_pose& pose) {
  uint64_t bytes = pose.world_from_object.size() * (sizeof(dmat4) + sizeof(uint8_t));
  for (const std::vector<vec3>& positions : pose.deformed_positions) bytes += positions.size() * sizeof(vec3);
  return bytes;
}

}  // namespace

double motion_frame_seconds(const render_options& options) { return 1.0 / options.fps.value_or(24.0); }

namespace {

// The frame at `time` into p.world, with its neighbours in p.motion when the motion AOV asks.
void pose_frame_and_neighbours(gltf_sequence& asset, const render_options& options, double time,
                               scene* previous, std::vector<uint32_t>* posed, prepared_scene& p) {
  if (!options.aovs.has(aov::motion)) {
    p.world = asset.pose(time, previous, posed);
    return;
  }
  auto motion = std::make_shared<scene_motion>();
  // A turntable's neighbours are its frames before and after: the camera turns between them.
  const render_options options_before = turntable_neighbour(options, -1);
  const render_options options_after = turntable_neighbour(options, 1);
  const bounds3* framing = p.framing ? &*p.framing : nullptr;
  if (!asset.animated() || turntable_holds_pose(options)) {
    p.world = asset.pose(time, previous, posed);
    p.motion = motion;  // finish_loaded_scene copies the frame's own pose to both sides
    if (options.turntable > 0) {
      // The asset holds still; only the view moves.
      std::string description;
      motion->previous = current_pose(p.world, job_view(options_before, p.world, description, framing));
      motion->next = current_pose(p.world, job_view(options_after, p.world, description, framing));
    }
    return;
  }
  // Each pose takes over what the last one built and no animation changes (rigid meshes,
  // materials, images); the neighbours keep their transforms, cameras and deformed meshes. A
  // neighbour's view is chosen before the next pose takes its meshes (a default camera frames them).
  const double step = motion_frame_seconds(options);
  std::string description;
  std::vector<uint32_t> deformed_before, deformed_after;
  scene before = asset.pose(time - step, previous, &deformed_before);
  const view_camera view_before = job_view(options_before, before, description, framing);
  scene after = asset.pose(time + step, &before, &deformed_after);
  const view_camera view_after = job_view(options_after, after, description, framing);
  p.world = asset.pose(time, &after, posed);
  motion->previous = neighbour_pose(p.world, before, view_before, deformed_before);
  motion->next = neighbour_pose(p.world, after, view_after, deformed_after);
  // The neighbours' own posed meshes were released as each next pose charged its own; what is
  // kept of them for the render is charged here.
  p.motion_memory = std::make_shared<memory_charge>(p.memory.get());
  p.motion_memory->add(pose_bytes(motion->previous) + pose_bytes(motion->next), options.input,
                       "the neighbouring frames' poses (motion vectors)");
  p.motion = motion;
}

// The default camera of an animated file frames the union of its bounds at evenly spaced times of
// the animation, so it stands still through a shot and frame N looks the same rendered alone or in
// a sequence; so do the orbit views (--camera-view, --turntable), which ignore the file's cameras, and
// keep one distance all the way round. A held turntable frames the one pose it shows. Poses chain
// (each takes over what the last built); `held` keeps the last.
constexpr int framing_poses = 9;

void find_framing(gltf_sequence& asset, const render_options& options, scene*& previous, scene& held,
                  prepared_scene& p) {
  p.framing_checked = true;
  if (options.look_from || options.look_at || !options.camera.empty() || !asset.animated() ||
      turntable_holds_pose(options))
    return;
  const bool orbit = uses_orbit_view(options);
  const auto [first, last] = asset.time_range();
  bounds3 framing;
  for (int k = 0; k < framing_poses; ++k) {
    const double t = first + (last - first) * k / (framing_poses - 1);
    scene posed = asset.pose(t, previous);
    const bool has_camera = !posed.cameras.empty();
    framing.extend(world_bounds(posed));
    held = std::move(posed);  // what previous held is in it now
    previous = &held;
    if (has_camera && !orbit) return;  // the file's own camera is the view
  }
  if (!framing.empty()) p.framing = framing;
}

}  // namespace

void pose_job_frame(gltf_sequence& asset, const render_options& options, scene* previous,
                    std::vector<uint32_t>* posed, prepared_scene& p) {
  const double time = scene_time(options);
  p.motion.reset();
  p.motion_memory.reset();  // the last frame's neighbours and shutter steps go now
  p.shutter_memory.reset();
  // The shutter's steps first: each pose takes from the one before, and the frame's own comes last.
  scene framing_pose, last_step;
  if (!p.framing_checked) find_framing(asset, options, previous, framing_pose, p);
  const std::vector<shutter_step> steps =
      pose_shutter_steps(asset, options, time, p.framing ? &*p.framing : nullptr, previous, last_step);
  pose_frame_and_neighbours(asset, options, time, previous, posed, p);
  attach_shutter_motion(p.world, steps);
  p.camera_steps = shutter_camera_steps(options, p.world, steps);
  if (p.world.shutter.any()) {
    p.shutter_memory = std::make_shared<memory_charge>(p.memory.get());
    p.shutter_memory->add(shutter_motion_bytes(p.world.shutter), options.input, "the shutter's motion steps");
  }
}

}  // namespace kiln
