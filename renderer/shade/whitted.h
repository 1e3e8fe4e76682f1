// Whitted-style shading: emission, direct light from every punctual light with a shadow ray
// (attenuated through see-through surfaces), recursive Fresnel-weighted mirror reflection for
// smooth surfaces, and refraction with exact dielectric Fresnel for transmissive materials. Sees the Scene
// and the accelerator interface only, never a backend.
#pragma once

#include <cstdint>

#include "accel/accelerator.h"
#include "scene/scene.h"
#include "shade/dielectric.h"
#include "shade/ray_cone.h"
#include "shade/surface.h"
#include "shade/texture_filter.h"

namespace kiln {

struct shading_options {
  int max_depth = 8;             // camera ray is depth 0; reflections stop after this many bounces
  float min_throughput = 1e-3f;  // a reflection whose weight falls below this is not traced
  // Whitted's mirror is perfect; a glTF surface's mirror term fades linearly from full strength
  // at roughness 0 to nothing at this roughness (rougher surfaces keep only their GGX highlight).
  float mirror_roughness_limit = 0.25f;
};

// Rays traced by kind, for statistics and benchmarks.
struct ray_counts {
  uint64_t camera = 0;
  uint64_t shadow = 0;
  uint64_t reflection = 0;
  uint64_t refraction = 0;
  uint64_t transparency = 0;  // continuations through BLEND surfaces and culled back faces
  uint64_t discarded_samples = 0;  // camera samples whose radiance was NaN or infinite, left out

  ray_counts& operator+=(const ray_counts& o) {
    transparency += o.transparency;
    discarded_samples += o.discarded_samples;
    camera += o.camera;
    shadow += o.shadow;
    reflection += o.reflection;
    refraction += o.refraction;
    return *this;
  }
};

struct shading_context {
  const scene& world;
  const accelerator& accel;
  const shading_options& options;
  // Some material lets light through (transmission): occluded shadow rays are then walked hit by
  // hit to attenuate them; otherwise one occlusion query decides. See scene_has_see_through().
  bool see_through_shadows = false;
  // Mip-mapped minification for ray-cone footprints; null: textures read level 0 only.
  const texture_filter* textures = nullptr;
};

// True when some material can pass light through itself (transmission or alphaMode BLEND), so
// shadow rays need the walk.
bool scene_has_see_through(const scene& s);

// The closest hit along r that is visible: back faces of single-sided (doubleSided false), opaque
// materials are culled, as glTF requires, by continuing the ray past them; r's origin moves with
// it. Shadow rays do not cull (a single-sided surface still casts a shadow from behind).
std::optional<hit> find_visible_hit(const shading_context& ctx, ray& r, ray_counts& counts);

// Distance from start.origin to the hit h of r, where r is start advanced by find_visible_hit past
// culled back faces (the ray cone keeps widening across them).
float distance_to_hit(const ray& start, const ray& r, const hit& h);

// A camera sample's radiance split by its first event: direct (emission, direct light and what is
// seen straight through BLEND surfaces or past the scene), reflection (all that arrives through the
// first mirror ray) and refraction (through the first refracted ray). The three sum to the radiance.
struct light_split {
  vec3 direct{0.0f};
  vec3 reflection{0.0f};
  vec3 refraction{0.0f};
  float scale = 1.0f;  // the share of the camera ray being shaded (BLEND layers); shading only
};

// Radiance leaving the shading point sp toward the origin of r (sp was built from r's closest hit).
// media: the closed volumes r travels in (empty for camera rays). cone: r's ray cone at the hit
// (the width sp's footprints were built with); reflected, refracted and continued rays carry it on.
// With split, also adds the radiance to it by first event (scaled by split->scale); the returned
// radiance is the same either way.
vec3 shade_surface(const shading_context& ctx, const ray& r, const surface_point& sp, int depth,
                   float throughput, ray_counts& counts, const medium_stack& media = medium_stack{},
                   const ray_cone& cone = {}, light_split* split = nullptr);

// Radiance arriving along r from the surface at h (the closest hit of r); cone is r's at the hit.
vec3 shade_hit(const shading_context& ctx, const ray& r, const hit& h, int depth, float throughput,
               ray_counts& counts, const medium_stack& media = medium_stack{}, const ray_cone& cone = {});

// Radiance arriving along r: shade the closest hit, or the environment on a miss; inside an
// absorbing volume the result is attenuated by Beer-Lambert over the travelled distance.
// cone: r's ray cone at its origin.
vec3 trace_radiance(const shading_context& ctx, const ray& r, int depth, float throughput, ray_counts& counts,
                    const medium_stack& media = medium_stack{}, const ray_cone& cone = {});

// trace_radiance for a camera ray (or its continuation through BLEND surfaces) that also adds what
// it sees to split by first event; the returned radiance is trace_radiance's.
vec3 trace_radiance_split(const shading_context& ctx, const ray& r, int depth, float throughput,
                          ray_counts& counts, const medium_stack& media, const ray_cone& cone,
                          light_split* split);

}  // namespace kiln
