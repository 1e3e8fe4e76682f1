#include "job/shutter_poses.h"

#include <algorithm>
#include <map>

#include "job/frame_motion.h"
#include "job/render_job_steps.h"
#include "job/turntable.h"

namespace kiln {

namespace {

// Halfway between two steps, how far linear interpolation may stray from the posed motion, in
// pixels of the frame (a quarter pixel: below what 16 or more samples a pixel resolve).
constexpr double interpolation_tolerance_pixels = 0.25;

shutter_step record_step(const render_options& options, const bounds3* framing, const scene& posed,
                         const std::vector<uint32_t>& deformed) {
  shutter_step step;
  std::string description;
  step.view = job_view(options, posed, description, framing);
  step.keys = instance_keys(posed);
  for (const instance& inst : posed.instances) {
    step.world_from_object.push_back(inst.world_from_object);
    step.shape_bounds.push_back(inst.kind == shape_kind::quadric ? posed.quadrics[inst.shape].bounds
                                                                 : posed.meshes[inst.shape].bounds);
  }
  step.positions.resize(posed.meshes.size());
  step.normals.resize(posed.meshes.size());
  for (uint32_t m : deformed) {
    if (m >= posed.meshes.size()) continue;
    step.positions[m] = posed.meshes[m].positions;
    step.normals[m] = posed.meshes[m].normals;
  }
  return step;
}

// The pixels between two world points as view v sees them (its full frame); 0 when either lies
// behind it, where no pixel shows the error.
double pixel_distance(const view_camera& v, const dmat4& world_to_ndc_matrix, const dvec3& p,
                      const dvec3& q) {
  const dvec4 a = world_to_ndc_matrix * dvec4(p, 1.0), b = world_to_ndc_matrix * dvec4(q, 1.0);
  if (!(a.w > 0.0) || !(b.w > 0.0)) return 0.0;
  const glm::dvec2 d = glm::dvec2(a.x / a.w - b.x / b.w, a.y / a.w - b.y / b.w);
  return glm::length(d * glm::dvec2(v.width, v.height));
}

// Whether `mid`, posed halfway between a and b, is where linear interpolation of a and b puts it,
// to within interpolation_tolerance_pixels as mid's view sees it: every corner of a moving
// instance's bounds, every vertex of a deforming mesh.
bool follows_linear(const shutter_step& a, const shutter_step& mid, const shutter_step& b) {
  const dmat4 to_ndc = world_to_ndc(mid.view);
  auto strays = [&](const dvec3& posed, const dvec3& interpolated) {
    return pixel_distance(mid.view, to_ndc, posed, interpolated) > interpolation_tolerance_pixels;
  };
  std::map<instance_key, size_t> in_a, in_b;
  for (size_t i = 0; i < a.keys.size(); ++i) in_a.emplace(a.keys[i], i);
  for (size_t i = 0; i < b.keys.size(); ++i) in_b.emplace(b.keys[i], i);
  std::vector<const dmat4*> placing(mid.positions.size(), nullptr);  // per mesh: an instance's transform
  for (size_t i = 0; i < mid.keys.size(); ++i) {
    const auto [node, kind, shape, order] = mid.keys[i];
    if (kind == int(shape_kind::mesh) && shape < placing.size()) placing[shape] = &mid.world_from_object[i];
    const auto ia = in_a.find(mid.keys[i]), ib = in_b.find(mid.keys[i]);
    if (ia == in_a.end() || ib == in_b.end()) continue;  // it holds still where a step lacks it
    const dmat4& posed = mid.world_from_object[i];
    const dmat4 interpolated = 0.5 * (a.world_from_object[ia->second] + b.world_from_object[ib->second]);
    const bounds3& box = mid.shape_bounds[i];
    if (box.empty()) continue;
    for (int corner = 0; corner < 8; ++corner) {
      const dvec4 c((corner & 1) ? box.upper.x : box.lower.x, (corner & 2) ? box.upper.y : box.lower.y,
                    (corner & 4) ? box.upper.z : box.lower.z, 1.0);
      if (strays(dvec3(posed * c), dvec3(interpolated * c))) return false;
    }
  }
  for (size_t m = 0; m < mid.positions.size(); ++m) {
    const std::vector<vec3>& p = mid.positions[m];
    if (p.empty() || !placing[m] || m >= a.positions.size() || m >= b.positions.size() ||
        a.positions[m].size() != p.size() || b.positions[m].size() != p.size())
      continue;
    for (size_t v = 0; v < p.size(); ++v) {
      const vec3 interpolated = 0.5f * (a.positions[m][v] + b.positions[m][v]);
      if (strays(transform_point(*placing[m], dvec3(p[v])),
                 transform_point(*placing[m], dvec3(interpolated))))
        return false;
    }
  }
  return true;
}

}  // namespace

std::vector<shutter_step> pose_shutter_steps(gltf_sequence& asset, const render_options& options, double time,
                                             const bounds3* framing, scene*& chain, scene& last) {
  if (!options.shutter || !asset.animated()) return {};
  const double frame = motion_frame_seconds(options);
  const double open = time + options.shutter->first * frame, close = time + options.shutter->second * frame;
  auto pose_at = [&](double u) {
    std::vector<uint32_t> deformed;
    scene posed = asset.pose(open + u * (close - open), chain, &deformed);
    shutter_step step = record_step(options, framing, posed, deformed);
    last = std::move(posed);  // what chain pointed to has given up its parts
    chain = &last;
    return step;
  };
  if (options.motion_steps >= 2) {
    std::vector<shutter_step> steps;
    const int n = options.motion_steps;
    for (int k = 0; k < n; ++k) steps.push_back(pose_at(double(k) / double(n - 1)));
    return steps;
  }
  // Steps on a grid of 32 intervals, halved until every new midpoint lies where the coarser steps
  // already put it.
  const uint32_t grid = max_default_motion_steps - 1;
  std::map<uint32_t, shutter_step> posed;
  posed.emplace(0, pose_at(0.0));
  posed.emplace(grid, pose_at(1.0));
  for (uint32_t spacing = grid; spacing > 1; spacing /= 2) {
    bool linear = true;
    for (uint32_t g = spacing / 2; g < grid; g += spacing) {
      posed.emplace(g, pose_at(double(g) / double(grid)));
      linear = linear && follows_linear(posed.at(g - spacing / 2), posed.at(g), posed.at(g + spacing / 2));
    }
    if (linear) {
      std::vector<shutter_step> steps;
      for (uint32_t g = 0; g <= grid; g += spacing) steps.push_back(std::move(posed.at(g)));
      return steps;
    }
  }
  std::vector<shutter_step> steps;
  for (auto& entry : posed) steps.push_back(std::move(entry.second));
  return steps;
}

void attach_shutter_motion(scene& world, const std::vector<shutter_step>& steps) {
  world.shutter = shutter_motion();
  if (steps.size() < 2) return;
  shutter_motion motion;
  motion.steps = uint32_t(steps.size());
  const std::vector<instance_key> keys = instance_keys(world);
  std::vector<std::map<instance_key, size_t>> index(steps.size());
  for (size_t k = 0; k < steps.size(); ++k)
    for (size_t i = 0; i < steps[k].keys.size(); ++i) index[k].emplace(steps[k].keys[i], i);
  bool moves = false;
  motion.instance_steps.resize(world.instances.size());
  for (size_t i = 0; i < world.instances.size(); ++i) {
    std::vector<dmat4> placements;
    for (size_t k = 0; k < steps.size(); ++k) {
      const auto found = index[k].find(keys[i]);
      placements.push_back(found == index[k].end() ? world.instances[i].world_from_object
                                                   : steps[k].world_from_object[found->second]);
    }
    if (std::all_of(placements.begin(), placements.end(), [&](const dmat4& m) { return m == placements[0]; }))
      continue;
    motion.instance_steps[i] = std::move(placements);
    moves = true;
  }
  // A mesh deforms during the shutter when every step posed it with the frame's vertex count.
  motion.mesh_positions.resize(world.meshes.size());
  motion.mesh_normals.resize(world.meshes.size());
  for (size_t m = 0; m < world.meshes.size(); ++m) {
    const mesh& frame = world.meshes[m];
    const bool posed_everywhere = std::all_of(steps.begin(), steps.end(), [&](const shutter_step& s) {
      return m < s.positions.size() && !s.positions[m].empty() &&
             s.positions[m].size() == frame.positions.size();
    });
    if (!posed_everywhere) continue;
    if (std::all_of(steps.begin(), steps.end(),
                    [&](const shutter_step& s) { return s.positions[m] == steps[0].positions[m]; }))
      continue;
    for (const shutter_step& s : steps) {
      motion.mesh_positions[m].push_back(s.positions[m]);
      if (!frame.normals.empty())
        motion.mesh_normals[m].push_back(s.normals[m].size() == frame.normals.size() ? s.normals[m]
                                                                                     : frame.normals);
    }
    moves = true;
  }
  if (moves) world.shutter = std::move(motion);
}

std::vector<view_camera> shutter_camera_steps(const render_options& options, const scene& world,
                                              const std::vector<shutter_step>& steps) {
  // Only a glTF camera follows the animation; the default and orbit cameras frame each pose anew,
  // which is not a camera moving.
  if (options.look_from || uses_orbit_view(options) || (options.camera.empty() && world.cameras.empty()) ||
      steps.size() < 2)
    return {};
  std::vector<view_camera> views;
  for (const shutter_step& step : steps) views.push_back(step.view);
  const auto same = [&](const view_camera& v) {
    return v.eye == views[0].eye && v.view == views[0].view && v.up == views[0].up &&
           v.left == views[0].left && v.right_edge == views[0].right_edge && v.bottom == views[0].bottom &&
           v.top == views[0].top && v.distance == views[0].distance;
  };
  if (std::all_of(views.begin(), views.end(), same)) return {};
  return views;
}

uint64_t shutter_motion_bytes(const shutter_motion& motion) {
  uint64_t bytes = 0;
  for (const auto& placements : motion.instance_steps) bytes += placements.size() * sizeof(dmat4);
  for (const auto* per_mesh : {&motion.mesh_positions, &motion.mesh_normals})
    for (const auto& mesh_steps : *per_mesh)
      for (const auto& vertices : mesh_steps) bytes += vertices.size() * sizeof(vec3);
  return bytes;
}

}  // namespace kiln
