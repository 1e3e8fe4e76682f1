#include "shade/whitted.h"

#include <algorithm>

#include "core/float_bits.h"
#include "core/hash_random.h"
#include "shade/direct_light.h"
#include "shade/environment.h"
#include "shade/material_eval.h"
#include "shade/material_lobes.h"
#include "shade/normal_mapping.h"
#include "shade/shading_normal.h"
#include "shade/shadow_transmittance.h"

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

// Weight of the perfect-mirror term for the opaque part of a surface: the BRDF's Fresnel at the
// view (linear in F0, so metal and dielectric mix; iridescent where the material is), faded out
// with roughness (see shading_options), seen through the sheen and the coat. The transmissive part
// reflects by exact Fresnel instead (see shade_surface); the coat's own mirror is coat_mirror_weight.
vec3 mirror_weight(const shading_options& options, const material_point& mp, float cos_theta) {
  if (mp.roughness >= options.mirror_roughness_limit) return vec3(0.0f);
  float fade = 1.0f - mp.roughness / options.mirror_roughness_limit;
  vec3 metal = metal_fresnel(mp, cos_theta) * mp.metallic;
  vec3 dielectric = mp.specular_weight * dielectric_fresnel(mp, cos_theta) *
                    ((1.0f - mp.metallic) * (1.0f - mp.transmission));
  return (metal + dielectric) * fade;
}

// The share of the base's reflection and transmission that reaches the viewer through the layers
// above it: the sheen's albedo scaling at the view and 1 − the coat's Fresnel weight.
float through_layers(const material_point& mp, float cos_theta, float coat_cos_theta) {
  if (!mp.layers) return 1.0f;
  const material_layers& L = *mp.layers;
  float share = 1.0f - clearcoat_weight(mp, coat_cos_theta);
  if (L.sheen_color != vec3(0.0f))
    share *= std::max(1.0f - std::max({L.sheen_color.x, L.sheen_color.y, L.sheen_color.z}) *
                                 sheen_directional_albedo(cos_theta, L.sheen_roughness),
                      0.0f);
  return share;
}

// The clearcoat's mirror: its Fresnel weight, faded out with the coat's roughness like the base's.
float coat_mirror_weight(const shading_options& options, const material_point& mp, float coat_cos_theta) {
  const material_layers& L = layers_of(mp);
  if (!(L.clearcoat > 0.0f) || L.clearcoat_roughness >= options.mirror_roughness_limit) return 0.0f;
  return clearcoat_weight(mp, coat_cos_theta) *
         (1.0f - L.clearcoat_roughness / options.mirror_roughness_limit);
}

// The refraction event at a transmissive surface: the ior pair, the media on
// the far side, and whether the ray bends (a thin-walled surface has no volume:
// rays pass straight through).
struct interface_crossing {
  float eta = 1.0f;  // n_incident / n_transmitted
  medium_stack beyond;
  bool bends = true;
};

// Entering or leaving is decided by the geometric normal's side
// (sp.front_face), never by the shading normal. A back-face hit on a volume not
// in the stack (a camera inside glass, an open mesh) still counts as leaving
// that material.
interface_crossing cross_interface(const scene& s, const surface_point& sp, const medium_stack& media,
                                   int channel) {
  interface_crossing c;
  const material& m = s.materials[sp.material];
  // A ray of one colour channel refracts by that channel's ior (KHR_materials_dispersion); the
  // media around the surface keep their single ior.
  const float ior = channel >= 0 ? dispersed_ior(material_ior(m), m.dispersion)[channel] : material_ior(m);
  if (!m.has_volume()) {
    c.eta = media.ior(s) / ior;
    c.beyond = media;
    c.bends = false;
    return c;
  }
  if (sp.front_face) {
    c.eta = media.ior(s) / ior;
    c.beyond = media.with(sp.material);
  } else {
    c.beyond = media.without(sp.material);
    c.eta = ior / c.beyond.ior(s);
  }
  return c;
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
    surface_point sp = make_surface_point(ctx.world, *h, r);
    vec3 origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, r.direction);
    if (!std::isinf(r.tmax)) r.tmax = std::max(r.tmax - glm::length(origin - r.origin), 0.0f);
    r.origin = origin;
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

// Adds what a camera path sees directly (emission, direct light, background) to its split.
void add_direct(const path_state& s, const vec3& radiance) {
  if (s.split) s.split->direct += s.share * radiance;
}

// Files light of a source group (emission, environment) that ray s adds.
void add_to_group(const path_state& s, size_t group, const vec3& radiance) {
  if (s.groups) s.groups[group] += s.tint * radiance;
}

// Which of the rays a shading point spawns a child is (its random numbers are its own).
enum class spawned : uint32_t { mirror = 1, coat_mirror, behind, refraction };

// The seed of a ray spawned by the ray with seed `seed` (channel: a dispersive refraction's, else -1).
uint32_t child_seed(uint32_t seed, spawned which, int channel = -1) {
  return hash_u32(seed ^ hash_u32(uint32_t(which) * 4u + uint32_t(channel + 1)));
}

// The state of a secondary ray spawned by s: one bounce deeper, off the camera's path.
path_state secondary(const path_state& s, float throughput, const medium_stack& media, const ray_cone& cone,
                     uint32_t seed) {
  path_state next = s;
  next.seed = seed;
  next.stratum = {};
  ++next.depth;
  next.throughput = throughput;
  next.media = media;
  next.cone = cone;
  next.camera = nullptr;
  next.split = nullptr;
  next.passes = nullptr;
  return next;
}

// The refracted ray's state: traced as the camera's own path (so the background it reaches counts
// as transparent, scaled by the share the refraction carries) when transmission is transparent,
// else as an ordinary secondary ray that sees the environment.
path_state refracted_state(const path_state& s, float throughput, const medium_stack& beyond,
                           const ray_cone& cone, const vec3& weight) {
  path_state next =
      secondary(s, throughput, beyond, cone, child_seed(s.seed, spawned::refraction, s.channel));
  if (!s.camera || !s.camera->transmission_transparent) return next;
  next.camera = s.camera;
  next.share = s.share * mean_component(weight);
  next.record_layers = false;  // what glass shows bent belongs to the glass's matte; the caller
                               // files all of its light under refraction
  return next;
}

// The direction a refracted ray leaves in (empty: total internal reflection). Thin walls pass light
// on unbent; volumes bend it by Snell's law about the shading normal, falling back to the geometric
// normal when that would not cross the surface.
std::optional<vec3> refraction_direction(const surface_point& sp, const vec3& incident,
                                         const interface_crossing& crossing) {
  if (!crossing.bends) return incident;
  std::optional<vec3> direction = refract_direction(incident, sp.shading_normal, crossing.eta);
  if (direction && glm::dot(*direction, sp.geometric_normal) >= 0.0f)
    direction = refract_direction(incident, sp.geometric_normal, crossing.eta);
  return direction;
}

// The refracted ray through a transmissive surface with weight `weight`, traced (when the throughput
// and the budget allow) and filed under the split's refraction.
vec3 trace_refracted(const shading_context& ctx, const surface_point& sp, const vec3& incident,
                     const vec3& direction, const interface_crossing& crossing, const vec3& weight,
                     const path_state& s, ray_counts& counts) {
  const float next_throughput = s.throughput * max_component(weight);
  if (!(next_throughput >= ctx.options.min_throughput) || !spend_ray(s.budget)) return vec3(0.0f);
  ray refracted;
  refracted.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, direction);
  refracted.direction = direction;
  refracted.kind = ray_kind::refraction;
  refracted.time = sp.time;
  ++counts.refraction;
  const ray_cone bent = crossing.bends
                            ? refracted_cone(s.cone, crossing.eta, glm::dot(incident, sp.geometric_normal),
                                             glm::dot(direction, sp.geometric_normal))
                            : s.cone;
  path_state next = refracted_state(s, next_throughput, crossing.beyond, bent, weight);
  next.tint = s.tint * weight;
  const vec3 refraction = weight * trace_radiance(ctx, refracted, next, counts);
  if (s.split) s.split->refraction += s.share * refraction;
  return refraction;
}

// The refracted part of a transmissive surface for one crossing (channel -1: all three colours,
// else that channel alone): exact Fresnel splits it into the refracted ray traced here and a
// reflected part added to reflect_weight (all of it under total internal reflection). layers: the
// share seen through the sheen and the coat.
vec3 refract_channel(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                     const vec3& incident, float cos_theta, float layers, int channel, const path_state& s,
                     vec3& reflect_weight, ray_counts& counts) {
  const float see_through = see_through_weight(mp) * layers;
  const vec3 mask = channel < 0 ? vec3(1.0f) : vec3(channel == 0, channel == 1, channel == 2);
  const interface_crossing crossing = cross_interface(ctx.world, sp, s.media, channel);
  const float fresnel = fresnel_dielectric(cos_theta, crossing.eta);
  reflect_weight += mask * (see_through * mp.specular_weight * fresnel);
  const std::optional<vec3> direction = refraction_direction(sp, incident, crossing);
  if (!direction) {
    reflect_weight += mask * (see_through * (1.0f - mp.specular_weight * fresnel));
    return vec3(0.0f);
  }
  const vec3 weight = mask * mp.base_color * (see_through * (1.0f - fresnel));
  if (channel == s.channel)
    return trace_refracted(ctx, sp, incident, *direction, crossing, weight, s, counts);
  path_state channel_state = s;
  channel_state.channel = channel;
  return trace_refracted(ctx, sp, incident, *direction, crossing, weight, channel_state, counts);
}

// The transmissive share of a surface: a smooth dielectric whatever its roughness (Whitted has no
// blurred refraction). A dispersive volume (KHR_materials_dispersion) entered by a ray of all
// colours splits it into one refracted ray per channel, each bent by its own ior.
vec3 shade_transmission(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                        const vec3& incident, float cos_theta, float layers, const path_state& s,
                        vec3& reflect_weight, ray_counts& counts) {
  if (!(see_through_weight(mp) > 0.0f)) return vec3(0.0f);
  const material& m = ctx.world.materials[sp.material];
  if (s.channel >= 0 || !(m.dispersion > 0.0f) || !m.has_volume())
    return refract_channel(ctx, sp, mp, incident, cos_theta, layers, s.channel, s, reflect_weight, counts);
  vec3 radiance(0.0f);
  for (int channel = 0; channel < 3; ++channel)
    radiance += refract_channel(ctx, sp, mp, incident, cos_theta, layers, channel, s, reflect_weight, counts);
  return radiance;
}

// The mirror ray with weight reflect_weight, traced (when the throughput and the budget allow) and
// filed under the split's reflection.
vec3 trace_mirror(const shading_context& ctx, const surface_point& sp, const vec3& normal,
                  const vec3& incident, const vec3& reflect_weight, const path_state& s, spawned which,
                  ray_counts& counts) {
  const float next_throughput = s.throughput * max_component(reflect_weight);
  if (!(next_throughput >= ctx.options.min_throughput) || !spend_ray(s.budget)) return vec3(0.0f);
  vec3 direction = glm::reflect(incident, normal);
  // An interpolated normal can send the mirror ray below the surface; use the true plane then.
  if (glm::dot(direction, sp.geometric_normal) <= 0.0f)
    direction = glm::reflect(incident, sp.geometric_normal);
  ray reflected;
  reflected.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, direction);
  reflected.direction = glm::normalize(direction);
  reflected.kind = ray_kind::reflection;
  reflected.time = sp.time;
  ++counts.reflection;
  // A reflected ray stays in the medium it came from.
  path_state next = secondary(s, next_throughput, s.media, reflected_cone(s.cone), child_seed(s.seed, which));
  next.tint = s.tint * reflect_weight;
  const vec3 reflection = reflect_weight * trace_radiance(ctx, reflected, next, counts);
  if (s.split) s.split->reflection += s.share * reflection;
  return reflection;
}

// Emission, direct light, mirror and refraction at a fully covering surface.
vec3 shade_covered(const shading_context& ctx, const ray& r, const surface_point& sp,
                   const material_point& mp, const path_state& s, ray_counts& counts) {
  // KHR_materials_unlit: the base colour is the outgoing radiance; no lights, mirror or refraction.
  if (mp.unlit) {
    add_direct(s, mp.base_color);
    add_to_group(s, emission_group(ctx.world), mp.base_color);
    return mp.base_color;
  }
  const vec3 incident = glm::normalize(r.direction);
  const vec3 to_viewer = -incident;
  const float cos_theta = std::max(glm::dot(sp.shading_normal, to_viewer), 0.0f);
  const vec3 coat_normal = coat_normal_or(mp, sp.shading_normal);
  const float coat_cos_theta = std::max(glm::dot(coat_normal, to_viewer), 0.0f);
  // KHR_materials_clearcoat: the coat lies over the emission too.
  const vec3 emission = mp.emission * (1.0f - clearcoat_weight(mp, coat_cos_theta));
  add_to_group(s, emission_group(ctx.world), emission);
  vec3 radiance = emission + direct_light(ctx, sp, mp, to_viewer, s, counts);
  add_direct(s, radiance);
  if (s.depth >= ctx.options.max_depth) return radiance;

  const float layers = through_layers(mp, cos_theta, coat_cos_theta);
  vec3 reflect_weight = mirror_weight(ctx.options, mp, cos_theta) * layers;
  radiance += shade_transmission(ctx, sp, mp, incident, cos_theta, layers, s, reflect_weight, counts);
  // The coat's mirror joins the base's when both reflect about the same normal.
  const float coat_mirror = coat_mirror_weight(ctx.options, mp, coat_cos_theta);
  const bool separate_coat = coat_mirror > 0.0f && coat_normal != sp.shading_normal;
  if (!separate_coat) reflect_weight += vec3(coat_mirror);
  radiance += trace_mirror(ctx, sp, sp.shading_normal, incident, reflect_weight, s, spawned::mirror, counts);
  if (separate_coat)
    radiance +=
        trace_mirror(ctx, sp, coat_normal, incident, vec3(coat_mirror), s, spawned::coat_mirror, counts);
  return radiance;
}

// shade_covered on a camera path: the surface covers its share of the sample, less what escapes
// through it (transparent transmission) into the background.
vec3 shade_covered_on_path(const shading_context& ctx, const ray& r, const surface_point& sp,
                           const material_point& mp, const path_state& s, ray_counts& counts) {
  if (!s.camera) return shade_covered(ctx, r, sp, mp, s, counts);
  const float escaped_before = s.camera->transparency;
  const vec3 radiance = shade_covered(ctx, r, sp, mp, s, counts);
  const float covered = s.share - (s.camera->transparency - escaped_before);
  if (s.record_layers) s.camera->cover(sp.instance, covered);
  // The sample's radiance is Σ share · radiance over the surfaces its path covers (BLEND and
  // trace_behind scale by the same shares), so each deep surface gets its own term.
  if (s.record_layers) s.camera->add_surface(sp.instance, sp.position, s.share * radiance, covered);
  // The denoiser's albedo and normal go by the surface's coverage, like its matte.
  if (s.passes && s.record_layers && covered > 0.0f) {
    s.passes->albedo += covered * denoising_albedo(mp);
    if (is_finite(sp.shading_normal)) s.passes->normal += covered * sp.shading_normal;
  }
  return radiance;
}

// The part of a BLEND surface's ray that passes behind it (a share 1 − alpha), continued unbent
// from the surface: one depth level, so stacked transparent layers stay bounded by max_depth.
vec3 trace_behind(const shading_context& ctx, const ray& r, const surface_point& sp, float alpha,
                  const path_state& s, ray_counts& counts) {
  path_state next = s;
  next.seed = child_seed(s.seed, spawned::behind);
  next.stratum = {};
  next.throughput = s.throughput * (1.0f - alpha);
  next.share = s.share * (1.0f - alpha);
  next.tint = s.tint * (1.0f - alpha);
  if (s.depth >= ctx.options.max_depth || !(next.throughput >= ctx.options.min_throughput) ||
      !spend_ray(s.budget)) {
    // Not traced: the part behind stays covered by this surface, as opaque black, so the mattes
    // still sum to alpha.
    if (s.camera && s.record_layers) {
      s.camera->cover(sp.instance, next.share);
      s.camera->add_surface(sp.instance, sp.position, vec3(0.0f), next.share);
    }
    return vec3(0.0f);
  }
  ray through;
  through.direction = glm::normalize(r.direction);
  through.kind = r.kind;  // the same ray, continued behind a partly transparent surface
  through.time = r.time;
  through.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, through.direction);
  ++counts.transparency;
  // The continued ray starts where this cone ends: its width so far carries on. It is still the
  // camera's ray, so its path (split, alpha, mattes) follows it to the surface behind.
  ++next.depth;
  return (1.0f - alpha) * trace_radiance(ctx, through, next, counts);
}

// What a ray that leaves the scene brings back: the environment, except on a camera path that does
// not show the background, where that share of the sample is transparent (alpha 0, no colour).
vec3 escape(const shading_context& ctx, const ray& r, const path_state& s, float weight = 1.0f) {
  if (s.camera && !s.camera->background_visible) {
    s.camera->transparency += s.share * weight;
    return vec3(0.0f);
  }
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
    add_to_group(at_hit, environment_group(ctx.world), absorption * arriving);
  } else {
    // The camera's path goes on through the volume, its share attenuated like its radiance; the
    // split files what arrives once, below.
    path_state next = at_hit;
    next.throughput = at_hit.throughput * max_component(absorption);
    next.share = at_hit.share * mean_component(absorption);
    next.split = nullptr;
    next.passes = nullptr;
    next.tint = at_hit.tint * absorption;
    arriving = shade_hit(ctx, r, *h, next, counts);
  }
  // Camera rays start outside every volume; should one not, its light counts as direct.
  add_direct(at_hit, absorption * arriving);
  return absorption * arriving;
}

}  // namespace

void camera_path::cover(uint32_t instance, float coverage) {
  if (!(coverage > 0.0f)) return;
  for (int i = 0; i < layer_count; ++i)
    if (layers[i].instance == instance) {
      layers[i].coverage += coverage;
      return;
    }
  if (layer_count == max_path_layers) {
    layers[layer_count - 1].coverage += coverage;  // deeper layers than that are folded into the last
    return;
  }
  layers[layer_count++] = {instance, coverage};
}

void camera_path::add_surface(uint32_t instance, const vec3& position, const vec3& radiance, float coverage) {
  if (!record_surfaces) return;
  if (surface_count == max_path_layers) {
    // Deeper surfaces than that fold into the last, so the colours still sum to the sample's.
    path_surface& last = surfaces[surface_count - 1];
    last.radiance += radiance;
    last.coverage += coverage;
    return;
  }
  surfaces[surface_count++] = {instance, glm::length(position - origin), radiance, coverage};
}

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
  // A holdout on the camera's path: its share of the sample is transparent and brings no colour,
  // and nothing behind it is traced.
  if (s.camera && ctx.world.instances[prepared.sp.instance].holdout != holdout_kind::none) {
    s.camera->transparency += s.share;
    return vec3(0.0f);
  }
  const material& m = ctx.world.materials[prepared.sp.material];
  const surface_point& sp = prepared.sp;
  const material_point& mp = prepared.mp;
  if (m.alpha != alpha_mode::blend || mp.alpha >= 1.0f)
    return shade_covered_on_path(ctx, r, sp, mp, s, counts);

  // BLEND: the surface covers a share alpha of the ray; the rest continues behind it.
  const float alpha = std::max(mp.alpha, 0.0f);
  vec3 radiance(0.0f);
  if (alpha > 0.0f) {
    path_state covered = s;
    covered.throughput = s.throughput * alpha;
    covered.share = s.share * alpha;
    covered.tint = s.tint * alpha;
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
  add_direct(s, background);
  add_to_group(s, environment_group(ctx.world), background);
  return background;
}

}  // namespace kiln
