#include "shade/whitted.h"

#include <algorithm>

#include "core/float_bits.h"
#include "shade/environment.h"
#include "shade/lights.h"
#include "shade/material_eval.h"
#include "shade/normal_mapping.h"
#include "shade/shading_normal.h"
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

// Visibility of a light along a shadow ray. Without see-through materials one occlusion query
// answers it. With them the walk that attenuates by transmission colours runs directly: its first
// closest-hit query finds nothing exactly when occluded() would say the segment is clear (the
// accelerator tests hold the two queries to agree), so a separate occluded() first would only
// repeat that query's traversal for every blocked ray.
vec3 shadow_visibility(const shading_context& ctx, const ray& shadow, ray_counts& counts) {
  if (!ctx.see_through_shadows) {
    ++counts.shadow;
    return ctx.accel.occluded(shadow) ? vec3(0.0f) : vec3(1.0f);
  }
  return shadow_transmittance(ctx.world, ctx.accel, shadow, counts.shadow);
}

vec3 direct_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                  const vec3& to_viewer, const ray_cone& cone, ray_counts& counts) {
  vec3 total(0.0f);
  for (const light& l : ctx.world.lights) {
    light_sample ls = sample_light(l, sp.position);
    if (ls.irradiance == vec3(0.0f)) continue;
    // A light behind the surface cannot reach it, whatever the shading normal says. The surface is
    // the smooth one the vertex normals describe, not the flat facet: facets just past a low-poly
    // mesh's terminator still face the light there, and their shadow rays start on that smooth
    // surface (sp.smooth_position), above the neighbouring facets.
    if (glm::dot(sp.smooth_normal, ls.direction) <= 0.0f) continue;
    float cos_theta = glm::dot(sp.shading_normal, ls.direction);
    if (cos_theta <= 0.0f) continue;
    const float scale = ctx.options.highlight_footprint_scale;
    const float footprint_alpha =
        highlight_footprint_alpha(cone.spread * scale, cone.width * scale, ls.distance, sp.curvature);
    vec3 f = evaluate_brdf(mp, sp.shading_normal, to_viewer, ls.direction, footprint_alpha);
    if (f == vec3(0.0f)) continue;

    if (!l.casts_shadows) {
      total += f * ls.irradiance * cos_theta;
      continue;
    }
    ray shadow;
    // Always off the facet's front: a light just below the facet's plane is still above the smooth
    // surface the ray starts on.
    shadow.origin =
        offset_ray_origin(sp.smooth_position, sp.position_error, sp.geometric_normal, sp.geometric_normal);
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

float mean_component(const vec3& v) { return (v.x + v.y + v.z) / 3.0f; }

// The camera path's split, when it keeps one (null inside a refraction it follows for alpha).
light_split* split_of(camera_path* path) { return path ? path->split : nullptr; }

// Adds what a camera path sees directly (emission, direct light, background) to its split.
void add_direct(camera_path* path, const vec3& radiance) {
  if (path && path->split) path->split->direct += path->share * radiance;
}

// The refracted ray of shade_covered: traced as the camera's own path (so the background it reaches
// counts as transparent, scaled by the share the refraction carries) when transmission is
// transparent, else as an ordinary secondary ray that sees the environment.
vec3 trace_refraction(const shading_context& ctx, const ray& refracted, int depth, float throughput,
                      ray_counts& counts, const medium_stack& beyond, const ray_cone& cone,
                      const vec3& weight, camera_path* path) {
  if (!path || !path->transmission_transparent)
    return trace_radiance(ctx, refracted, depth, throughput, counts, beyond, cone);
  camera_path through = *path;
  through.share = path->share * mean_component(weight);
  through.split = nullptr;        // the caller files all of it under refraction
  through.record_layers = false;  // what glass shows bent belongs to the glass's matte
  const vec3 radiance = trace_camera_path(ctx, refracted, depth, throughput, counts, beyond, cone, &through);
  path->transparency = through.transparency;
  return radiance;
}

// Emission, direct light, mirror and refraction at a fully covering surface.
vec3 shade_covered(const shading_context& ctx, const ray& r, const surface_point& sp,
                   const material_point& mp, int depth, float throughput, ray_counts& counts,
                   const medium_stack& media, const ray_cone& cone, camera_path* path) {
  // KHR_materials_unlit: the base colour is the outgoing radiance; no lights, mirror or refraction.
  if (mp.unlit) {
    add_direct(path, mp.base_color);
    return mp.base_color;
  }
  const vec3 incident = glm::normalize(r.direction);
  const vec3 to_viewer = -incident;

  vec3 radiance = mp.emission + direct_light(ctx, sp, mp, to_viewer, cone, counts);
  add_direct(path, radiance);
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
        const vec3 refraction = weight * trace_refraction(ctx, refracted, depth + 1, next_throughput, counts,
                                                          crossing.beyond, bent, weight, path);
        if (light_split* split = split_of(path)) split->refraction += path->share * refraction;
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
    if (light_split* split = split_of(path)) split->reflection += path->share * reflection;
    radiance += reflection;
  }
  return radiance;
}

// shade_covered on a camera path: the surface covers its share of the sample, less what escapes
// through it (transparent transmission) into the background.
vec3 shade_covered_on_path(const shading_context& ctx, const ray& r, const surface_point& sp,
                           const material_point& mp, int depth, float throughput, ray_counts& counts,
                           const medium_stack& media, const ray_cone& cone, camera_path* path) {
  if (!path) return shade_covered(ctx, r, sp, mp, depth, throughput, counts, media, cone, nullptr);
  const float escaped_before = path->transparency;
  const vec3 radiance = shade_covered(ctx, r, sp, mp, depth, throughput, counts, media, cone, path);
  if (path->record_layers) path->cover(sp.instance, path->share - (path->transparency - escaped_before));
  return radiance;
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

shading_point prepare_shading(const shading_context& ctx, const ray& r, const surface_point& unmapped) {
  const material& m = ctx.world.materials[unmapped.material];
  material_inputs inputs = material_inputs_at(unmapped);
  inputs.filter = ctx.textures;
  shading_point p{unmapped, evaluate_material(ctx.world, m, inputs)};
  apply_normal_map(ctx.world, m, inputs, p.sp);
  p.sp.shading_normal =
      bend_toward_viewer(p.sp.geometric_normal, -glm::normalize(r.direction), p.sp.shading_normal);
  return p;
}

vec3 shade_surface(const shading_context& ctx, const ray& r, const surface_point& unmapped, int depth,
                   float throughput, ray_counts& counts, const medium_stack& media, const ray_cone& cone,
                   camera_path* path) {
  return shade_prepared(ctx, r, prepare_shading(ctx, r, unmapped), depth, throughput, counts, media, cone,
                        path);
}

vec3 shade_prepared(const shading_context& ctx, const ray& r, const shading_point& prepared, int depth,
                    float throughput, ray_counts& counts, const medium_stack& media, const ray_cone& cone,
                    camera_path* path) {
  const material& m = ctx.world.materials[prepared.sp.material];
  const surface_point& sp = prepared.sp;
  const material_point& mp = prepared.mp;
  if (m.alpha != alpha_mode::blend || mp.alpha >= 1.0f)
    return shade_covered_on_path(ctx, r, sp, mp, depth, throughput, counts, media, cone, path);

  // BLEND: the surface covers a share alpha of the ray; the rest continues unbent behind it (one
  // depth level, so stacked transparent layers stay bounded by max_depth).
  const float alpha = std::max(mp.alpha, 0.0f);
  vec3 radiance(0.0f);
  const float share = path ? path->share : 1.0f;
  if (alpha > 0.0f) {
    if (path) path->share = share * alpha;
    radiance +=
        alpha * shade_covered_on_path(ctx, r, sp, mp, depth, throughput * alpha, counts, media, cone, path);
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
    // camera's ray, so its path (split, alpha, mattes) follows it to the surface behind.
    if (path) path->share = share * (1.0f - alpha);
    radiance +=
        (1.0f - alpha) * trace_camera_path(ctx, through, depth + 1, behind, counts, media, cone, path);
  } else if (path && path->record_layers) {
    // The part behind is not traced (depth or throughput limit): it stays covered by this surface,
    // as opaque black, so the mattes still sum to alpha.
    path->share = share * (1.0f - alpha);
    path->cover(sp.instance, path->share);
  }
  if (path) path->share = share;
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
  return trace_camera_path(ctx, r_in, depth, throughput, counts, media, cone_in, nullptr);
}

namespace {

// What a ray that leaves the scene brings back: the environment, except on a camera path that does
// not show the background, where that share of the sample is transparent (alpha 0, no colour).
vec3 escape(const shading_context& ctx, const ray& r, camera_path* path, float weight = 1.0f) {
  if (path && !path->background_visible) {
    path->transparency += path->share * weight;
    return vec3(0.0f);
  }
  return environment_radiance(ctx.world, r.direction);
}

}  // namespace

vec3 trace_camera_path(const shading_context& ctx, const ray& r_in, int depth, float throughput,
                       ray_counts& counts, const medium_stack& media, const ray_cone& cone_in,
                       camera_path* path) {
  ray r = r_in;
  std::optional<hit> h = find_visible_hit(ctx, r, counts);
  const ray_cone cone = h ? cone_at(cone_in, distance_to_hit(r_in, r, *h)) : cone_in;
  if (media.empty()) {
    if (h)
      return shade_surface(ctx, r, make_surface_point(ctx.world, *h, r, cone.width), depth, throughput,
                           counts, media, cone, path);
    const vec3 background = escape(ctx, r, path);
    add_direct(path, background);
    return background;
  }

  // Inside a volume: Beer-Lambert over the distance to the next surface. A ray
  // that leaves the scene from inside (an open mesh, no exit surface) is
  // attenuated over the material's thickness.
  const material& inside = ctx.world.materials[media.innermost()];
  const float distance = h ? h->t * glm::length(r.direction) : inside.thickness_factor;
  vec3 absorption = beer_transmittance(inside.attenuation_color, inside.attenuation_distance, distance);
  if (absorption == vec3(0.0f)) return vec3(0.0f);
  vec3 arriving(0.0f);
  if (!h) {
    arriving = escape(ctx, r, path, mean_component(absorption));
  } else if (path) {
    // The camera's path goes on through the volume, its share attenuated like its radiance; the
    // split files what arrives once, below.
    camera_path inner = *path;
    inner.split = nullptr;
    inner.share = path->share * mean_component(absorption);
    arriving = shade_surface(ctx, r, make_surface_point(ctx.world, *h, r, cone.width), depth,
                             throughput * max_component(absorption), counts, media, cone, &inner);
    inner.split = path->split;
    inner.share = path->share;
    *path = inner;
  } else {
    arriving = shade_hit(ctx, r, *h, depth, throughput * max_component(absorption), counts, media, cone);
  }
  // Camera rays start outside every volume; should one not, its light counts as direct.
  add_direct(path, absorption * arriving);
  return absorption * arriving;
}

}  // namespace kiln
