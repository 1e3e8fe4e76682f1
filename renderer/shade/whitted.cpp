#include "shade/whitted.h"

#include <algorithm>

#include "core/float_bits.h"
#include "shade/environment.h"
#include "shade/lights.h"
#include "shade/material_eval.h"
#include "shade/normal_mapping.h"
#include "shade/shadow_transmittance.h"

namespace kiln {

namespace {

// Shadow rays stop just short of the light so that a light placed on a surface
// is not shadowed by that surface; the margin is relative, so it holds at any
// scene scale.
constexpr float shadow_length_fraction = 1.0f - 1e-4f;

// A ray passing more culled back faces than this is treated as a miss (bounds the work).
constexpr int max_culled_crossings = 16;

float max_component(const vec3& v) { return std::max({v.x, v.y, v.z}); }

// glTF: doubleSided false enables back-face culling. Transmissive volumes are exempt: their rays
// leave through back faces.
bool back_face_culled(const scene& s, const hit& h, const ray& r) {
  const material& m = s.materials[s.instances[h.instance_id].material];
  if (m.double_sided || m.transmission_factor > 0.0f) return false;
  return glm::dot(h.geometric_normal, r.direction) > 0.0f;
}

// Visibility of a light along a shadow ray: one occlusion query, then (only for
// an occluded ray in a scene with see-through materials) the walk that
// attenuates by transmission colours.
vec3 shadow_visibility(const shading_context& ctx, const ray& shadow, ray_counts& counts) {
  ++counts.shadow;
  if (!ctx.accel.occluded(shadow)) return vec3(1.0f);
  if (!ctx.see_through_shadows) return vec3(0.0f);
  return shadow_transmittance(ctx.world, ctx.accel, shadow, counts.shadow);
}

vec3 direct_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                  const vec3& to_viewer, ray_counts& counts) {
  vec3 total(0.0f);
  for (const light& l : ctx.world.lights) {
    light_sample ls = sample_light(l, sp.position);
    if (ls.irradiance == vec3(0.0f)) continue;
    // A light behind the geometric surface cannot reach it, whatever the
    // shading normal says.
    if (glm::dot(sp.geometric_normal, ls.direction) <= 0.0f) continue;
    float cos_theta = glm::dot(sp.shading_normal, ls.direction);
    if (cos_theta <= 0.0f) continue;
    vec3 f = evaluate_brdf(mp, sp.shading_normal, to_viewer, ls.direction);
    if (f == vec3(0.0f)) continue;

    if (!l.casts_shadows) {
      total += f * ls.irradiance * cos_theta;
      continue;
    }
    ray shadow;
    shadow.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, ls.direction);
    shadow.direction = ls.direction;
    shadow.kind = ray_kind::shadow;
    shadow.tmax = std::isinf(ls.distance)
                      ? inf
                      : glm::length(vec3(l.position) - shadow.origin) * shadow_length_fraction;
    vec3 visibility = shadow_visibility(ctx, shadow, counts);
    if (visibility == vec3(0.0f)) continue;
    total += f * ls.irradiance * cos_theta * visibility;
  }
  return total;
}

// Weight of the perfect-mirror term for the opaque part of a surface: Schlick's
// Fresnel (linear in F0, so metal and dielectric mix), faded out with roughness
// (see shading_options). The transmissive part reflects by exact Fresnel
// instead (see shade_surface).
vec3 mirror_weight(const shading_options& options, const material_point& mp, float cos_theta) {
  if (mp.roughness >= options.mirror_roughness_limit) return vec3(0.0f);
  float fade = 1.0f - mp.roughness / options.mirror_roughness_limit;
  vec3 metal = fresnel_schlick(mp.base_color, cos_theta) * mp.metallic;
  vec3 dielectric = fresnel_schlick(mp.dielectric_f0 * mp.specular_weight, cos_theta) *
                    ((1.0f - mp.metallic) * (1.0f - mp.transmission));
  return (metal + dielectric) * fade;
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
interface_crossing cross_interface(const scene& s, const surface_point& sp, const medium_stack& media) {
  interface_crossing c;
  const material& m = s.materials[sp.material];
  const float ior = material_ior(m);
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
  for (const material& m : s.materials)
    if ((m.transmission_factor > 0.0f && m.metallic_factor < 1.0f) || m.alpha == alpha_mode::blend)
      return true;
  return false;
}

std::optional<hit> find_visible_hit(const shading_context& ctx, ray& r, ray_counts& counts) {
  for (int i = 0; i < max_culled_crossings; ++i) {
    std::optional<hit> h = ctx.accel.intersect(r);
    if (!h || !back_face_culled(ctx.world, *h, r)) return h;
    surface_point sp = make_surface_point(ctx.world, *h, r);
    vec3 origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, r.direction);
    if (!std::isinf(r.tmax)) r.tmax = std::max(r.tmax - glm::length(origin - r.origin), 0.0f);
    r.origin = origin;
    ++counts.transparency;
  }
  return std::nullopt;
}

namespace {

// Emission, direct light, mirror and refraction at a fully covering surface.
vec3 shade_covered(const shading_context& ctx, const ray& r, const surface_point& sp,
                   const material_point& mp, int depth, float throughput, ray_counts& counts,
                   const medium_stack& media, const ray_cone& cone, light_split* split) {
  // KHR_materials_unlit: the base colour is the outgoing radiance; no lights, mirror or refraction.
  if (mp.unlit) {
    if (split) split->direct += split->scale * mp.base_color;
    return mp.base_color;
  }
  const vec3 incident = glm::normalize(r.direction);
  const vec3 to_viewer = -incident;

  vec3 radiance = mp.emission + direct_light(ctx, sp, mp, to_viewer, counts);
  if (split) split->direct += split->scale * radiance;
  if (depth >= ctx.options.max_depth) return radiance;

  const float cos_theta = std::max(glm::dot(sp.shading_normal, to_viewer), 0.0f);
  vec3 reflect_weight = mirror_weight(ctx.options, mp, cos_theta);

  // Transmissive share: a smooth dielectric whatever its roughness (Whitted has
  // no blurred refraction), split by exact Fresnel into reflected and refracted
  // rays.
  const float see_through = see_through_weight(mp);
  if (see_through > 0.0f) {
    interface_crossing crossing = cross_interface(ctx.world, sp, media);
    float fresnel = fresnel_dielectric(cos_theta, crossing.eta);
    reflect_weight += vec3(see_through * mp.specular_weight * fresnel);
    // Thin walls pass light on unbent; volumes bend it by Snell's law about the
    // shading normal, falling back to the geometric normal when that would not
    // cross the surface.
    std::optional<vec3> direction = incident;
    if (crossing.bends) {
      direction = refract_direction(incident, sp.shading_normal, crossing.eta);
      if (direction && glm::dot(*direction, sp.geometric_normal) >= 0.0f)
        direction = refract_direction(incident, sp.geometric_normal, crossing.eta);
    }
    if (!direction) {
      // Total internal reflection: all of the transmissive share goes to the
      // mirror ray.
      reflect_weight += vec3(see_through * (1.0f - mp.specular_weight * fresnel));
    } else {
      vec3 weight = mp.base_color * (see_through * (1.0f - fresnel));
      float next_throughput = throughput * max_component(weight);
      if (next_throughput >= ctx.options.min_throughput) {
        ray refracted;
        refracted.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, *direction);
        refracted.direction = *direction;
        refracted.kind = ray_kind::refraction;
        ++counts.refraction;
        const ray_cone bent =
            crossing.bends ? refracted_cone(cone, crossing.eta, glm::dot(incident, sp.geometric_normal),
                                            glm::dot(*direction, sp.geometric_normal))
                           : cone;
        const vec3 refraction = weight * trace_radiance(ctx, refracted, depth + 1, next_throughput, counts,
                                                        crossing.beyond, bent);
        if (split) split->refraction += split->scale * refraction;
        radiance += refraction;
      }
    }
  }

  float next_throughput = throughput * max_component(reflect_weight);
  if (next_throughput >= ctx.options.min_throughput) {
    vec3 direction = glm::reflect(incident, sp.shading_normal);
    // An interpolated normal can send the mirror ray below the surface; use the
    // true plane then.
    if (glm::dot(direction, sp.geometric_normal) <= 0.0f)
      direction = glm::reflect(incident, sp.geometric_normal);
    ray reflected;
    reflected.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, direction);
    reflected.direction = glm::normalize(direction);
    reflected.kind = ray_kind::reflection;
    ++counts.reflection;
    // A reflected ray stays in the medium it came from.
    const vec3 reflection = reflect_weight * trace_radiance(ctx, reflected, depth + 1, next_throughput,
                                                            counts, media, reflected_cone(cone));
    if (split) split->reflection += split->scale * reflection;
    radiance += reflection;
  }
  return radiance;
}

}  // namespace

vec3 shade_surface(const shading_context& ctx, const ray& r, const surface_point& unmapped, int depth,
                   float throughput, ray_counts& counts, const medium_stack& media, const ray_cone& cone,
                   light_split* split) {
  const material& m = ctx.world.materials[unmapped.material];
  material_inputs inputs = material_inputs_at(unmapped);
  inputs.filter = ctx.textures;
  material_point mp = evaluate_material(ctx.world, m, inputs);
  surface_point sp = unmapped;
  apply_normal_map(ctx.world, m, inputs, sp);
  if (m.alpha != alpha_mode::blend || mp.alpha >= 1.0f)
    return shade_covered(ctx, r, sp, mp, depth, throughput, counts, media, cone, split);

  // BLEND: the surface covers a share alpha of the ray; the rest continues unbent behind it (one
  // depth level, so stacked transparent layers stay bounded by max_depth).
  const float alpha = std::max(mp.alpha, 0.0f);
  vec3 radiance(0.0f);
  const float scale = split ? split->scale : 1.0f;
  if (alpha > 0.0f) {
    if (split) split->scale = scale * alpha;
    radiance += alpha * shade_covered(ctx, r, sp, mp, depth, throughput * alpha, counts, media, cone, split);
  }
  const float behind = throughput * (1.0f - alpha);
  if (depth < ctx.options.max_depth && behind >= ctx.options.min_throughput) {
    ray through;
    through.direction = glm::normalize(r.direction);
    through.kind = r.kind;  // the same ray, continued behind a partly transparent surface
    through.origin =
        offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, through.direction);
    ++counts.transparency;
    // The continued ray starts where this cone ends: its width so far carries on. It is still the
    // camera's ray, so the split follows it to the surface behind.
    if (split) split->scale = scale * (1.0f - alpha);
    radiance +=
        (1.0f - alpha) * trace_radiance_split(ctx, through, depth + 1, behind, counts, media, cone, split);
  }
  if (split) split->scale = scale;
  return radiance;
}

vec3 shade_hit(const shading_context& ctx, const ray& r, const hit& h, int depth, float throughput,
               ray_counts& counts, const medium_stack& media, const ray_cone& cone) {
  return shade_surface(ctx, r, make_surface_point(ctx.world, h, r, cone.width), depth, throughput, counts,
                       media, cone);
}

float distance_to_hit(const ray& start, const ray& r, const hit& h) {
  return glm::length(r.origin - start.origin) + h.t * glm::length(r.direction);
}

vec3 trace_radiance(const shading_context& ctx, const ray& r_in, int depth, float throughput,
                    ray_counts& counts, const medium_stack& media, const ray_cone& cone_in) {
  return trace_radiance_split(ctx, r_in, depth, throughput, counts, media, cone_in, nullptr);
}

vec3 trace_radiance_split(const shading_context& ctx, const ray& r_in, int depth, float throughput,
                          ray_counts& counts, const medium_stack& media, const ray_cone& cone_in,
                          light_split* split) {
  ray r = r_in;
  std::optional<hit> h = find_visible_hit(ctx, r, counts);
  const ray_cone cone = h ? cone_at(cone_in, distance_to_hit(r_in, r, *h)) : cone_in;
  if (media.empty()) {
    if (h)
      return shade_surface(ctx, r, make_surface_point(ctx.world, *h, r, cone.width), depth, throughput,
                           counts, media, cone, split);
    const vec3 background = environment_radiance(ctx.world, r.direction);
    if (split) split->direct += split->scale * background;
    return background;
  }

  // Inside a volume: Beer-Lambert over the distance to the next surface. A ray
  // that leaves the scene from inside (an open mesh, no exit surface) is
  // attenuated over the material's thickness.
  const material& inside = ctx.world.materials[media.innermost()];
  const float distance = h ? h->t * glm::length(r.direction) : inside.thickness_factor;
  vec3 absorption = beer_transmittance(inside.attenuation_color, inside.attenuation_distance, distance);
  if (absorption == vec3(0.0f)) return vec3(0.0f);
  vec3 arriving =
      h ? shade_hit(ctx, r, *h, depth, throughput * max_component(absorption), counts, media, cone)
        : environment_radiance(ctx.world, r.direction);
  // Camera rays start outside every volume; should one not, its light counts as direct.
  if (split) split->direct += split->scale * (absorption * arriving);
  return absorption * arriving;
}

}  // namespace kiln
