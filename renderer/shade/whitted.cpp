#include "shade/whitted.h"

#include "core/float_bits.h"
#include "shade/lights.h"
#include "shade/material_eval.h"

#include <algorithm>

namespace kiln {

namespace {

// Shadow rays stop just short of the light so that a light placed on a surface is not shadowed
// by that surface; the margin is relative, so it holds at any scene scale.
constexpr float shadow_length_fraction = 1.0f - 1e-4f;

vec3 direct_light(const shading_context& ctx, const surface_point& sp, const material_point& mp,
                  const vec3& to_viewer, ray_counts& counts) {
  vec3 total(0.0f);
  for (const light& l : ctx.world.lights) {
    light_sample ls = sample_light(l, sp.position);
    if (ls.irradiance == vec3(0.0f)) continue;
    // A light behind the geometric surface cannot reach it, whatever the shading normal says.
    if (glm::dot(sp.geometric_normal, ls.direction) <= 0.0f) continue;
    float cos_theta = glm::dot(sp.shading_normal, ls.direction);
    if (cos_theta <= 0.0f) continue;
    vec3 f = evaluate_brdf(mp, sp.shading_normal, to_viewer, ls.direction);
    if (f == vec3(0.0f)) continue;

    ray shadow;
    shadow.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, ls.direction);
    shadow.direction = ls.direction;
    shadow.kind = ray_kind::shadow;
    shadow.tmax = std::isinf(ls.distance)
                      ? inf
                      : glm::length(vec3(l.position) - shadow.origin) * shadow_length_fraction;
    ++counts.shadow;
    if (ctx.accel.occluded(shadow)) continue;
    total += f * ls.irradiance * cos_theta;
  }
  return total;
}

// Fresnel weight of the perfect-mirror term, faded out with roughness (see shading_options).
vec3 mirror_weight(const shading_options& options, const material_point& mp, float cos_theta) {
  if (mp.roughness >= options.mirror_roughness_limit) return vec3(0.0f);
  float fade = 1.0f - mp.roughness / options.mirror_roughness_limit;
  return fresnel_schlick(specular_f0(mp), cos_theta) * fade;
}

}  // namespace

vec3 shade_surface(const shading_context& ctx, const ray& r, const surface_point& sp, int depth, float throughput,
                   ray_counts& counts) {
  const material& m = ctx.world.materials[sp.material];
  material_point mp = evaluate_material(ctx.world, m, sp.uv0);
  vec3 to_viewer = -glm::normalize(r.direction);

  vec3 radiance = mp.emission + direct_light(ctx, sp, mp, to_viewer, counts);

  if (depth < ctx.options.max_depth) {
    float cos_theta = std::max(glm::dot(sp.shading_normal, to_viewer), 0.0f);
    vec3 weight = mirror_weight(ctx.options, mp, cos_theta);
    float next_throughput = throughput * std::max({weight.x, weight.y, weight.z});
    if (next_throughput >= ctx.options.min_throughput) {
      vec3 direction = glm::reflect(-to_viewer, sp.shading_normal);
      // An interpolated normal can send the mirror ray below the surface; use the true plane then.
      if (glm::dot(direction, sp.geometric_normal) <= 0.0f)
        direction = glm::reflect(-to_viewer, sp.geometric_normal);
      ray reflected;
      reflected.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, direction);
      reflected.direction = glm::normalize(direction);
      reflected.kind = ray_kind::reflection;
      ++counts.reflection;
      radiance += weight * trace_radiance(ctx, reflected, depth + 1, next_throughput, counts);
    }
  }
  return radiance;
}

vec3 shade_hit(const shading_context& ctx, const ray& r, const hit& h, int depth, float throughput,
               ray_counts& counts) {
  return shade_surface(ctx, r, make_surface_point(ctx.world, h, r), depth, throughput, counts);
}

vec3 trace_radiance(const shading_context& ctx, const ray& r, int depth, float throughput, ray_counts& counts) {
  std::optional<hit> h = ctx.accel.intersect(r);
  if (!h) return ctx.world.env.color;
  return shade_hit(ctx, r, *h, depth, throughput, counts);
}

}  // namespace kiln
