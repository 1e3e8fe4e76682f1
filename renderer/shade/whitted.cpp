#include "shade/whitted.h"

#include <algorithm>

#include "core/float_bits.h"
#include "core/hash_random.h"
#include "shade/delta_lobes.h"
#include "shade/direct_light.h"
#include "shade/environment.h"
#include "shade/material_eval.h"
#include "shade/material_lobes.h"
#include "shade/normal_mapping.h"
#include "shade/shading_normal.h"
#include "shade/shadow_transmittance.h"
#include "shade/spawn_ray.h"

namespace kiln {

namespace {

// A ray passing more culled back faces than this is treated as a miss (bounds the work).
constexpr int max_culled_crossings = 16;

float max_component(const vec3& v) { return std::max({v.x, v.y, v.z}); }

// glTF: doubleSided false enables back-face culling. Transmissive volumes are exempt: their rays
// leave through back faces.
bool back_face_culled(const scene& s, const hit& h, const ray& r) {
  const instance& inst = s.instances[h.instance_id];
  // An invisible holdout exists for the camera's own rays only (they keep kind camera behind BLEND
  // surfaces); every other ray passes it like a culled face.
  if (inst.holdout == holdout_kind::invisible && r.kind != ray_kind::camera) return true;
  const material& m = s.materials[inst.material];
  if (m.double_sided || m.transmission_factor > 0.0f) return false;
  return glm::dot(h.geometric_normal, r.direction) > 0.0f;
}

}  // namespace

bool scene_has_see_through(const scene& s) {
  // Shadow rays walk past invisible holdouts, so those need the walk too.
  for (const instance& i : s.instances)
    if (i.holdout == holdout_kind::invisible) return true;
  for (const material& m : s.materials)
    if ((m.transmission_factor > 0.0f && m.metallic_factor < 1.0f) || m.alpha == alpha_mode::blend)
      return true;
  return false;
}

std::optional<hit> find_visible_hit(const shading_context& ctx, ray& r, ray_counts& counts) {
  return find_visible_hit_from(ctx, r, ctx.accel.intersect(r), counts);
}

std::optional<hit> find_visible_hit_from(const shading_context& ctx, ray& r, std::optional<hit> h,
                                         ray_counts& counts) {
  for (int i = 0; i < max_culled_crossings; ++i) {
    if (i > 0) h = ctx.accel.intersect(r);
    if (!h || !back_face_culled(ctx.world, *h, r)) return h;
    continue_past(make_surface_point(ctx.world, *h, r), r);
    ++counts.transparency;
  }
  return std::nullopt;
}

const std::optional<hit>& visible_hit_from(const shading_context& ctx, ray& r,
                                           const std::optional<hit>& first, std::optional<hit>& walked,
                                           ray_counts& counts) {
  if (!first || !back_face_culled(ctx.world, *first, r)) return first;
  walked = find_visible_hit_from(ctx, r, first, counts);
  return walked;
}

namespace {

float mean_component(const vec3& v) { return (v.x + v.y + v.z) / 3.0f; }

// Which of the rays a shading point spawns a child is (its random numbers are its own).
enum class spawned : uint32_t { mirror = 1, coat_mirror, behind, refraction };

// The seed of a ray spawned by the ray with seed `seed` (channel: a dispersive refraction's, else -1).
uint32_t child_seed(uint32_t seed, spawned which, int channel = -1) {
  return hash_u32(seed ^ hash_u32(uint32_t(which) * 4u + uint32_t(channel + 1)));
}

// The state of a ray spawned by s with weight along delta lobe `lobe`: one bounce deeper, in the
// lobe's media and channel, its record the lobe's (shade/path_record.h).
path_state spawned_state(const path_state& s, const delta_lobe& lobe, float throughput,
                         const ray_cone& cone) {
  path_state next = s;
  const bool refracts = lobe.kind == delta_kind::refraction;
  next.seed =
      refracts ? child_seed(s.seed, spawned::refraction, lobe.channel)
               : child_seed(s.seed, lobe.kind == delta_kind::mirror ? spawned::mirror : spawned::coat_mirror);
  next.stratum = {};
  next.planned = nullptr;
  ++next.depth;
  next.throughput = throughput;
  next.media = lobe.media;
  next.cone = cone;
  next.channel = lobe.channel;
  next.record = refracts ? refracted_record(s.record, lobe.weight)
                         : secondary_record(s.record, s.record.tint * lobe.weight);
  return next;
}

// The ray of delta lobe `lobe` at sp, traced (when the throughput and the budget allow) and filed
// under the split's reflection or refraction; its radiance times the lobe's weight.
vec3 trace_delta_lobe(const shading_context& ctx, const surface_point& sp, const vec3& incident,
                      const delta_lobe& lobe, const path_state& s, ray_counts& counts) {
  const float next_throughput = s.throughput * max_component(lobe.weight);
  if (!(next_throughput >= ctx.options.min_throughput) || !spend_ray(s.budget)) return vec3(0.0f);
  const bool refracts = lobe.kind == delta_kind::refraction;
  const ray spawned_ray =
      spawn_ray(sp, lobe.direction, refracts ? ray_kind::refraction : ray_kind::reflection);
  ++(refracts ? counts.refraction : counts.reflection);
  const ray_cone cone = !refracts ? reflected_cone(s.cone)
                        : lobe.bends
                            ? refracted_cone(s.cone, lobe.eta, glm::dot(incident, sp.geometric_normal),
                                             glm::dot(lobe.direction, sp.geometric_normal))
                            : s.cone;
  const path_state next = spawned_state(s, lobe, next_throughput, cone);
  const vec3 radiance = lobe.weight * trace_radiance(ctx, spawned_ray, next, counts);
  record_branch(s.record, refracts, radiance);
  return radiance;
}

// Emission, direct light, mirror and refraction at a fully covering surface.
vec3 shade_covered(const shading_context& ctx, const ray& r, const surface_point& sp,
                   const material_point& mp, const path_state& s, ray_counts& counts) {
  // KHR_materials_unlit: the base colour is the outgoing radiance; no lights, mirror or refraction.
  if (mp.unlit) {
    record_direct(s.record, mp.base_color);
    record_group(s.record, emission_group(ctx.world), mp.base_color);
    record_pass(s.record, aov::emission, mp.base_color);
    return mp.base_color;
  }
  const vec3 incident = glm::normalize(r.direction);
  const vec3 to_viewer = -incident;
  const float coat_cos_theta = std::max(glm::dot(coat_normal_or(mp, sp.shading_normal), to_viewer), 0.0f);
  // KHR_materials_clearcoat: the coat lies over the emission too.
  const vec3 emission = mp.emission * (1.0f - clearcoat_weight(mp, coat_cos_theta));
  record_group(s.record, emission_group(ctx.world), emission);
  record_pass(s.record, aov::emission, emission);
  vec3 radiance = emission + direct_light(ctx, sp, mp, to_viewer, s, counts);
  record_direct(s.record, radiance);
  if (s.depth >= ctx.options.max_depth) return radiance;

  // The BSDF's delta lobes, traced in its order; the refractions (three through a dispersive
  // volume) are summed apart first, so their sum is the same whatever follows.
  const delta_lobes deltas =
      delta_lobes_at(ctx.world, ctx.options.mirror_roughness_limit, sp, mp, incident, s.media, s.channel);
  vec3 refracted(0.0f);
  int i = 0;
  for (; i < deltas.count && deltas.lobes[i].kind == delta_kind::refraction; ++i)
    refracted += trace_delta_lobe(ctx, sp, incident, deltas.lobes[i], s, counts);
  radiance += refracted;
  for (; i < deltas.count; ++i) radiance += trace_delta_lobe(ctx, sp, incident, deltas.lobes[i], s, counts);
  return radiance;
}

// shade_covered, and the surface recorded as covering its share of the sample, less what escapes
// through it (transparent transmission) into the background.
vec3 shade_covered_on_path(const shading_context& ctx, const ray& r, const surface_point& sp,
                           const material_point& mp, const path_state& s, ray_counts& counts) {
  const float escaped_before = escaped_so_far(s.record);
  const vec3 radiance = shade_covered(ctx, r, sp, mp, s, counts);
  record_covered(s.record, sp, mp, radiance, escaped_before);
  return radiance;
}

// The part of a BLEND surface's ray that passes behind it (a share 1 − alpha), continued unbent
// from the surface: one depth level, so stacked transparent layers stay bounded by max_depth. What
// is not traced stays covered by the surface as opaque black, or, behind a holdout, transparent.
vec3 trace_behind(const shading_context& ctx, const ray& r, const surface_point& sp, float alpha,
                  const path_state& s, ray_counts& counts, bool holdout = false) {
  path_state next = s;
  next.seed = child_seed(s.seed, spawned::behind);
  next.stratum = {};
  next.planned = nullptr;
  next.throughput = s.throughput * (1.0f - alpha);
  next.record = scaled_record(s.record, 1.0f - alpha);
  if (s.depth >= ctx.options.max_depth || !(next.throughput >= ctx.options.min_throughput) ||
      !spend_ray(s.budget)) {
    if (holdout)
      record_holdout(next.record);
    else
      record_untraced_behind(s.record, sp, next.record.share);
    return vec3(0.0f);
  }
  // The same ray (its kind kept), continued behind a partly transparent surface.
  const ray through = spawn_ray(sp, glm::normalize(r.direction), r.kind);
  ++counts.transparency;
  // The continued ray starts where this cone ends: its width so far carries on. It is still the
  // camera's ray, so its path (split, alpha, mattes) follows it to the surface behind.
  ++next.depth;
  return (1.0f - alpha) * trace_radiance(ctx, through, next, counts);
}

// What a ray that leaves the scene brings back: the environment, except on a camera path that does
// not show the background, where that share of the sample is transparent (alpha 0, no colour).
vec3 escape(const shading_context& ctx, const ray& r, const path_state& s, float weight = 1.0f) {
  if (record_escape(s.record, weight)) return vec3(0.0f);
  return environment_radiance(ctx.world, r.direction);
}

// shade_prepared for the closest hit h of r; s.cone is r's at the hit.
vec3 shade_hit(const shading_context& ctx, const ray& r, const hit& h, const path_state& s,
               ray_counts& counts) {
  const surface_point sp = make_surface_point(ctx.world, h, r, s.cone.width, s.memo);
  return shade_prepared(ctx, r, prepare_shading(ctx, r, sp), s, counts);
}

// trace_radiance inside a volume: Beer-Lambert over the distance to the next surface. A ray that
// leaves the scene from inside (an open mesh, no exit surface) is attenuated over the material's
// thickness. r has been advanced to h; at_hit is s with the cone at the hit.
vec3 trace_in_volume(const shading_context& ctx, const ray& r, const std::optional<hit>& h,
                     const path_state& at_hit, ray_counts& counts) {
  const material& inside = ctx.world.materials[at_hit.media.innermost()];
  const float distance = h ? h->t * glm::length(r.direction) : inside.thickness_factor;
  const vec3 absorption = beer_transmittance(inside.attenuation_color, inside.attenuation_distance, distance);
  if (absorption == vec3(0.0f)) return vec3(0.0f);
  vec3 arriving(0.0f);
  if (!h) {
    arriving = escape(ctx, r, at_hit, mean_component(absorption));
    record_group(at_hit.record, environment_group(ctx.world), absorption * arriving);
  } else {
    // The camera's path goes on through the volume, its share attenuated like its radiance; the
    // split files what arrives once, below.
    path_state next = at_hit;
    next.throughput = at_hit.throughput * max_component(absorption);
    next.record = through_volume_record(at_hit.record, absorption);
    arriving = shade_hit(ctx, r, *h, next, counts);
  }
  // Camera rays start outside every volume; should one not, its light counts as direct.
  record_direct(at_hit.record, absorption * arriving);
  return absorption * arriving;
}

}  // namespace

namespace {

// The frames of the lobe extensions at a prepared point: the clearcoat's normal (its own normal
// map, else the unmapped normal, bent toward the viewer like the base's) and the direction of
// anisotropy in the world (the tangent frame turned by the material's direction; none without a
// tangent frame, and the lobe stays isotropic).
void set_layer_frames(const material& m, const material_texels& texels, const surface_point& unmapped,
                      const vec3& to_viewer, shading_point& p) {
  if (!p.mp.layers) return;
  material_layers& L = *p.mp.layers;
  if (L.clearcoat > 0.0f) {
    surface_point coat = unmapped;
    if (reads_clearcoat_normal_map(m, unmapped) && texels.has_lobes)
      apply_normal_map(m.clearcoat_normal_texture, texels.lobes.clearcoat_normal, coat);
    L.clearcoat_normal = bend_toward_viewer(coat.geometric_normal, to_viewer, coat.shading_normal);
  }
  if (L.anisotropy > 0.0f && unmapped.tangent != vec4(0.0f)) {
    const vec3 n = p.sp.shading_normal;
    vec3 t = vec3(unmapped.tangent);
    t -= n * glm::dot(n, t);
    const float length = glm::length(t);
    if (!(length > 0.0f) || !std::isfinite(length)) return;
    t /= length;
    const vec3 b =
        glm::cross(n, t) * (unmapped.tangent.w < 0.0f ? -1.0f : 1.0f) * (unmapped.front_face ? 1.0f : -1.0f);
    L.anisotropy_direction = t * L.anisotropy_tangent_space.x + b * L.anisotropy_tangent_space.y;
  }
}

}  // namespace

shading_point prepare_shading(const shading_context& ctx, const ray& r, const surface_point& unmapped) {
  const material& m = ctx.world.materials[unmapped.material];
  material_inputs inputs = material_inputs_at(unmapped);
  inputs.filter = ctx.textures;
  // One batch for every texture the point reads, the normal map's included.
  const bool mapped = reads_normal_map(m, unmapped);
  const material_texels texels =
      sample_material_textures(ctx.world, m, inputs, mapped || reads_clearcoat_normal_map(m, unmapped));
  shading_point p{unmapped, evaluate_material(m, inputs, texels)};
  if (mapped) apply_normal_map(m, texels.normal, p.sp);
  const vec3 to_viewer = -glm::normalize(r.direction);
  p.sp.shading_normal = bend_toward_viewer(p.sp.geometric_normal, to_viewer, p.sp.shading_normal);
  set_layer_frames(m, texels, unmapped, to_viewer, p);
  return p;
}

vec3 shade_prepared(const shading_context& ctx, const ray& r, const shading_point& prepared,
                    const path_state& s, ray_counts& counts) {
  const material& m = ctx.world.materials[prepared.sp.material];
  const surface_point& sp = prepared.sp;
  const material_point& mp = prepared.mp;
  const bool opaque = m.alpha != alpha_mode::blend || mp.alpha >= 1.0f;
  // BLEND: the surface covers a share alpha of the ray; the rest continues behind it.
  const float alpha = opaque ? 1.0f : std::max(mp.alpha, 0.0f);
  // A matte on the camera's path: the share of the sample it covers is transparent and brings no
  // colour; a BLEND matte covers alpha of it, so layers cut by it add up to the full render.
  if (is_matte(ctx.world.instances[sp.instance].holdout) && record_holdout(scaled_record(s.record, alpha)))
    return opaque ? vec3(0.0f) : trace_behind(ctx, r, sp, alpha, s, counts, true);
  if (opaque) return shade_covered_on_path(ctx, r, sp, mp, s, counts);

  vec3 radiance(0.0f);
  if (alpha > 0.0f) {
    path_state covered = s;
    covered.throughput = s.throughput * alpha;
    covered.record = scaled_record(s.record, alpha);
    radiance += alpha * shade_covered_on_path(ctx, r, sp, mp, covered, counts);
  }
  radiance += trace_behind(ctx, r, sp, alpha, s, counts);
  return radiance;
}

float distance_to_hit(const ray& start, const ray& r, const hit& h) {
  return glm::length(r.origin - start.origin) + h.t * glm::length(r.direction);
}

vec3 trace_radiance(const shading_context& ctx, const ray& r_in, const path_state& s, ray_counts& counts) {
  ray r = r_in;
  const std::optional<hit> h = find_visible_hit(ctx, r, counts);
  path_state at_hit = s;
  if (h) at_hit.cone = cone_at(s.cone, distance_to_hit(r_in, r, *h));
  if (!s.media.empty()) return trace_in_volume(ctx, r, h, at_hit, counts);
  if (h) return shade_hit(ctx, r, *h, at_hit, counts);
  const vec3 background = escape(ctx, r, s);
  record_direct(s.record, background);
  record_group(s.record, environment_group(ctx.world), background);
  return background;
}

}  // namespace kiln
