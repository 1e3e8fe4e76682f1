#include "render/camera_sample.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "core/hash_random.h"
#include "shade/environment.h"
#include "shade/material_eval.h"

namespace kiln {

namespace {

// A sample whose radiance is not finite contributes nothing (adaptive sampling sees a transparent
// black corner) and is counted. In place, as the sample's other steps: a camera sample (its path
// layers, split and passes) is hundreds of bytes, and returning a copy of it cost every sample.
void discard(camera_sample& s, ray_counts& counts) {
  ++counts.discarded_samples;
  s.rgba = vec4(0.0f);
  std::fill(s.groups.begin(), s.groups.end(), vec3(0.0f));
  s.passes.clear();
  s.layer_count = 0;
  s.finite = false;
}

}  // namespace

sample_outputs sample_outputs_for(const aov_set& aovs, const scene_motion* motion) {
  sample_outputs o;
  o.motion = aovs.has(aov::motion) ? motion : nullptr;
  o.albedo = aovs.has(aov::albedo);
  o.split = wants_light_split(aovs);
  o.groups = aovs.has(aov::light_groups);
  o.passes = wants_camera_passes(aovs);
  o.shadow = aovs.has(aov::shadow);
  return o;
}

camera_sample trace_camera_sample(const shading_context& ctx, const view_camera& cam, bool show_background,
                                  double px, double py, const ray_cone& cone, ray_counts& counts,
                                  const sample_outputs& outputs) {
  const ray start = generate_camera_ray(cam, px, py);
  return shade_camera_hit(ctx, cam, show_background, start, ctx.accel.intersect(start), cone, counts,
                          outputs);
}

namespace {

// The sample of a camera ray that hits nothing: the environment when the background is shown.
void missed(const shading_context& ctx, camera_sample& s, const ray& r, bool show_background, bool with_split,
            ray_counts& counts) {
  if (show_background) s.rgba = vec4(environment_radiance(ctx.world, r.direction), 1.0f);
  if (with_split) s.passes.value(aov::direct) = vec3(s.rgba);
  if (!s.groups.empty()) s.groups[environment_group(ctx.world)] = vec3(s.rgba);
  if (!is_finite(s.rgba)) discard(s, counts);
}

// The geometry AOVs of the hit h at p (distance from the camera, also behind culled back faces).
// They keep the hit even when its radiance has to be discarded. N is the normal the shading used:
// after the normal map and the bend toward the viewer.
void record_hit(const shading_context& ctx, const hit& h, const shading_point& p, float distance,
                const sample_outputs& outputs, camera_sample& s) {
  const surface_point& sp = p.sp;
  s.depth = distance;
  if (is_finite(sp.shading_normal)) s.normal = sp.shading_normal;
  s.instance = h.instance_id;
  s.position = vec3(dvec3(sp.position) + ctx.world.render_origin);  // render space -> world
  s.uv = sp.uv0;
  s.node = int32_t(ctx.world.instances[h.instance_id].node);
  s.material = ctx.world.materials[sp.material].source_index;
  if (outputs.albedo) s.albedo = p.mp.base_color;
  if (outputs.motion) {
    s.surface_hit = h;
    s.render_point = dvec3(sp.position);
    s.time = sp.time;
  }
}

// The seed of a camera sample's random numbers: a hash of its ray's bits (origin, direction and time),
// which its film position and time alone decide.
uint32_t camera_ray_seed(const ray& r) {
  const float parts[7] = {r.origin.x,    r.origin.y,    r.origin.z, r.direction.x,
                          r.direction.y, r.direction.z, r.time};
  uint32_t seed = 0x2C1B3C6Du;
  for (float p : parts) {
    uint32_t bits;
    std::memcpy(&bits, &p, sizeof bits);
    seed = hash_u32(seed ^ bits);
  }
  return seed;
}

// The colour, alpha and mattes of the camera path that starts at the visible hit p of r (at_hit:
// the ray's cone there; camera: the camera ray's origin, from which deep surfaces are measured).
// The sample's ray tree gets its own budget.
void shade_camera_path(const shading_context& ctx, const ray& r, const vec3& camera, const shading_point& p,
                       const ray_cone& at_hit, const planned_light* planned, bool show_background,
                       const sample_outputs& outputs, camera_sample& s, ray_counts& counts) {
  camera_path path;
  path.record_surfaces = outputs.surfaces != nullptr;
  path.origin = camera;
  path.background_visible = show_background;
  path.transmission_transparent = ctx.options.transmission_transparent;
  ray_budget budget{ctx.options.max_rays_per_sample, ctx.cancel};
  path_state state;
  state.cone = at_hit;
  state.budget = &budget;
  state.record.camera = &path;
  state.record.split = outputs.split ? &s.passes : nullptr;
  state.record.groups = s.groups.empty() ? nullptr : s.groups.data();
  state.record.passes = outputs.passes ? &s.passes : nullptr;
  state.memo = outputs.memo;
  state.seed = camera_ray_seed(r);
  state.stratum = outputs.stratum;
  state.planned = planned;
  const vec3 radiance = shade_prepared(ctx, r, p, state, counts);
  std::copy(path.layers, path.layers + path.layer_count, s.layers);
  s.layer_count = path.layer_count;
  if (outputs.surfaces) outputs.surfaces->assign(path.surfaces, path.surfaces + path.surface_count);
  // Opaque paths keep alpha exactly 1 (1 − 0).
  const float alpha = std::clamp(1.0f - path.transparency, 0.0f, 1.0f);
  if (!is_finite(radiance)) {
    discard(s, counts);
    return;
  }
  s.rgba = vec4(radiance, alpha);
}

}  // namespace

void prepare_camera_hit(const shading_context& ctx, const ray& start, const std::optional<hit>& first,
                        const ray_cone& cone, ray_counts& counts, triangle_memo* memo, camera_hit& out) {
  out.r = start;  // find_visible_hit moves the origin past culled back faces
  out.planned = false;
  std::optional<hit> walked;
  out.visible = visible_hit_from(ctx, out.r, first, walked, counts);
  if (!out.visible) return;
  out.distance = distance_to_hit(start, out.r, *out.visible);
  out.at_hit = cone_at(cone, out.distance);
  out.p =
      prepare_shading(ctx, out.r, make_surface_point(ctx.world, *out.visible, out.r, out.at_hit.width, memo));
}

void plan_camera_light(const shading_context& ctx, const pixel_stratum& stratum, bool passes, camera_hit& h,
                       light_terms& terms) {
  h.planned = false;
  if (!h.visible || h.p.mp.unlit || is_matte(ctx.world.instances[h.visible->instance_id].holdout)) return;
  // A BLEND surface that covers nothing of the ray is not shaded, only passed.
  if (ctx.world.materials[h.p.sp.material].alpha == alpha_mode::blend && !(h.p.mp.alpha > 0.0f)) return;
  // What shade_camera_path's state gives direct_light at this point.
  light_query q;
  q.cone = h.at_hit;
  q.seed = camera_ray_seed(h.r);
  q.stratum = stratum;
  q.camera = true;
  q.passes = passes;
  h.light.terms = &terms;
  h.light.span = plan_direct_light(ctx, h.p.sp, h.p.mp, -glm::normalize(h.r.direction), q, terms);
  h.planned = true;
}

camera_sample shade_prepared_camera_hit(const shading_context& ctx, const view_camera& cam,
                                        bool show_background, const ray& start, const camera_hit& prepared,
                                        ray_counts& counts, const sample_outputs& outputs) {
  camera_sample s;
  if (outputs.surfaces) outputs.surfaces->clear();  // a miss shades no surface
  if (outputs.groups) s.groups.assign(ctx.world.lights.size() + 2, vec3(0.0f));
  if (outputs.passes && outputs.shadow) s.passes.shadow.assign(ctx.world.lights.size() + 1, 0.0f);
  // Orthographic rays run along the view axis from the window plane: their distance is planar.
  if (cam.kind == projection::perspective) s.view_cosine = float(glm::dot(dvec3(start.direction), cam.view));
  ++counts.camera;
  if (!prepared.visible) {
    missed(ctx, s, prepared.r, show_background, outputs.split, counts);
    return s;  // every path returns s, so it is built in the caller's slot
  }
  // A matte belongs to no layer: its pixels keep a miss's Z, P, N, uv, ids, albedo and motion, so
  // a matte picked from them selects only objects the layer holds.
  if (!is_matte(ctx.world.instances[prepared.visible->instance_id].holdout))
    record_hit(ctx, *prepared.visible, prepared.p, prepared.distance, outputs, s);
  shade_camera_path(ctx, prepared.r, start.origin, prepared.p, prepared.at_hit,
                    prepared.planned ? &prepared.light : nullptr, show_background, outputs, s, counts);
  return s;
}

camera_sample shade_camera_hit(const shading_context& ctx, const view_camera& cam, bool show_background,
                               const ray& start, const std::optional<hit>& first, const ray_cone& cone,
                               ray_counts& counts, const sample_outputs& outputs) {
  camera_hit prepared;
  prepare_camera_hit(ctx, start, first, cone, counts, outputs.memo, prepared);
  return shade_prepared_camera_hit(ctx, cam, show_background, start, prepared, counts, outputs);
}

void keep_as_nearest(const camera_sample& s, camera_sample& nearest) {
  nearest.depth = s.depth;
  nearest.view_cosine = s.view_cosine;
  nearest.normal = s.normal;
  nearest.instance = s.instance;
  nearest.position = s.position;
  nearest.albedo = s.albedo;
  nearest.uv = s.uv;
  nearest.node = s.node;
  nearest.material = s.material;
  nearest.surface_hit = s.surface_hit;
  nearest.render_point = s.render_point;
  nearest.time = s.time;
  nearest.motion = s.motion;
}

void motion_of_nearest(camera_sample& s, const scene& world, const scene_motion* motion) {
  if (motion && s.instance != no_instance)
    s.motion = hit_motion(*motion, world, s.surface_hit, s.render_point, s.time);
}

void store_nearest_sample(const camera_sample& s, film& out, size_t i) {
  if (!out.depth.empty())
    out.depth[i] = out.aovs.depth_kind == depth_mode::planar ? s.depth * s.view_cosine : s.depth;
  const std::pair<aov, const vec3*> nearest[] = {
      {aov::normal, &s.normal}, {aov::position, &s.position}, {aov::albedo, &s.albedo}};
  for (const auto& [a, value] : nearest)
    if (!out.vec3_layer(a).empty()) out.vec3_layer(a)[i] = *value;
  if (!out.uv.empty()) out.uv[i] = s.uv;
  if (!out.ids.empty())
    out.ids[i] = glm::ivec3(s.node, s.material, s.instance == no_instance ? -1 : int32_t(s.instance));
  if (!out.motion.empty()) out.motion[i] = s.motion;
}

}  // namespace kiln
