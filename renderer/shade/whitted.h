// Whitted-style shading: emission, direct light from every punctual light with a shadow ray
// (attenuated through see-through surfaces), recursive Fresnel-weighted mirror reflection for
// smooth surfaces, and refraction with exact dielectric Fresnel for transmissive materials. Sees the Scene
// and the accelerator interface only, never a backend.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/accelerator.h"
#include "scene/scene.h"
#include "shade/dielectric.h"
#include "shade/environment_light.h"
#include "shade/material_eval.h"
#include "shade/path_record.h"
#include "shade/ray_budget.h"
#include "shade/ray_cone.h"
#include "shade/surface.h"
#include "shade/texture_filter.h"

namespace kiln {

struct planned_light;

struct shading_options {
  int max_depth = 8;             // camera ray is depth 0; reflections stop after this many bounces
  float min_throughput = 1e-3f;  // a reflection whose weight falls below this is not traced
  // Reflected, refracted and continued rays one camera sample may spawn in all (its shadow rays
  // are not counted: each shaded hit casts one per light). Past it the tree is cut where it has
  // got to: a ray not spawned brings nothing back, like one under min_throughput.
  uint64_t max_rays_per_sample = 4096;
  // Whitted's mirror is perfect; a glTF surface's mirror term fades linearly from full strength
  // at roughness 0 to nothing at this roughness (rougher surfaces keep only their GGX highlight).
  float mirror_roughness_limit = 0.25f;
  // What glass (KHR_materials_transmission) contributes to alpha. false: it holds out, like any
  // surface (alpha 1; what is seen through it, the environment included, is baked into the colour).
  // true: light refracted through it that reaches a background the camera does not show is
  // transparent, so glass over nothing comps over a plate (Cycles' "transparent glass").
  bool transmission_transparent = false;
  // A punctual light's highlight is widened to the pixel's footprint (material_eval.h,
  // highlight_footprint_of), not a supersample's: the ray cones shrink by 1/√spp, so the
  // renderer sets this to the inverse of that factor. A highlight then converges with spp.
  float highlight_footprint_scale = 1.0f;
  // Pairs of environment samples (one from the map's importance, one from the material's lobes) each
  // shading point takes when the environment lights the scene (--environment-samples).
  int environment_samples = 2;
};

// Rays traced by kind, for statistics and benchmarks.
struct ray_counts {
  uint64_t camera = 0;
  uint64_t shadow = 0;
  uint64_t reflection = 0;
  uint64_t refraction = 0;
  uint64_t transparency = 0;       // continuations through BLEND surfaces and culled back faces
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
  // Raised (from another thread): camera samples stop spawning rays (see ray_budget.h).
  const std::atomic<bool>* cancel = nullptr;
  // The environment as a light (shade/environment_light.h); null or dark: it lights nothing, and is
  // seen only by rays that leave the scene.
  const environment_light* environment = nullptr;
  // The wave's shadow rays go to the accelerator as occlusion batches (shade/direct_light.h). Off in
  // scenes with quadrics, whose user geometry answers a packet lane by lane: slower than single rays.
  bool shadow_packets = true;
};

// True when some material can pass light through itself (transmission or alphaMode BLEND), so
// shadow rays need the walk.
bool scene_has_see_through(const scene& s);

// The closest hit along r that is visible: back faces of single-sided (doubleSided false), opaque
// materials are culled, as glTF requires, by continuing the ray past them; r's origin moves with
// it. Shadow rays do not cull (a single-sided surface still casts a shadow from behind).
std::optional<hit> find_visible_hit(const shading_context& ctx, ray& r, ray_counts& counts);

// find_visible_hit for a ray whose closest hit is already known (first = ctx.accel.intersect(r)).
std::optional<hit> find_visible_hit_from(const shading_context& ctx, ray& r, std::optional<hit> first,
                                         ray_counts& counts);

// find_visible_hit_from's answer by reference: `first` itself when it is visible (the usual case),
// else the walk's hit, kept in `walked`. The camera's first hits are read where their batch holds
// them: copied in and out of the walk, each copy stalled on store forwarding.
const std::optional<hit>& visible_hit_from(const shading_context& ctx, ray& r,
                                           const std::optional<hit>& first, std::optional<hit>& walked,
                                           ray_counts& counts);

// Distance from start.origin to the hit h of r, where r is start advanced by find_visible_hit past
// culled back faces (the ray cone keeps widening across them).
float distance_to_hit(const ray& start, const ray& r, const hit& h);

// A camera sample's place among its pixel's samples, which stratifies the environment samples of the
// surface it sees first across the pixel (count 0: none, the samples are independent).
struct pixel_stratum {
  uint32_t scramble = 0;  // the pixel's, from a hash of its coordinates
  uint32_t index = 0;     // the sample's index, 0 to count - 1, shuffled per pixel
  uint32_t count = 0;     // the pixel's samples
};

// What one ray of a camera sample's tree carries down the Whitted recursion. Passed by value: a
// branch changes its own copy, so nothing is changed and restored around a recursive call.
struct path_state {
  int depth = 0;                 // bounces so far: the camera ray is depth 0
  float throughput = 1.0f;       // the weight of this ray's radiance in the sample
  medium_stack media;            // the closed volumes the ray travels in (empty for camera rays)
  ray_cone cone;                 // the ray's cone: at its origin when traced, at the hit when shaded
  float time = 0.0f;             // the sample's time in the shutter; unused until motion blur
  ray_budget* budget = nullptr;  // the sample's rays left and cancel flag; null: unbounded
  // What this ray's light and surfaces add to the camera sample's output layers (shade/path_record.h):
  // its share of the sample and where its light is filed. Nothing of it changes the radiance.
  path_record record;
  // KHR_materials_dispersion: the colour channel (0-2) a ray split off by a dispersive refraction
  // carries, whose ior it refracts by from then on; -1: all three.
  int channel = -1;
  // The caller's triangle constants (shade/surface.h), shared by every ray of the tree; null: none.
  triangle_memo* memo = nullptr;
  // Where this ray's random numbers come from (core/hash_random.h): the camera sample's (a hash of
  // its ray), and each ray spawned from it its own, derived from its parent's and which ray it is.
  uint32_t seed = 0;
  // Set on the camera's own first shading point only (shade/direct_light.h stratifies by it).
  pixel_stratum stratum;
  // The direct light of the camera's own first shading point, when the wave planned it and answered
  // its shadow rays with the rest of its run (shade/direct_light.h); null: shading computes it.
  const planned_light* planned = nullptr;
};

// Where path_state::groups files emission and the environment, after the lights.
inline size_t emission_group(const scene& s) { return s.lights.size(); }
inline size_t environment_group(const scene& s) { return s.lights.size() + 1; }

// A hit made ready to shade: the material evaluated there, and the shading normal as shading uses
// it (the normal map applied, then bent toward the viewer where it faces away: see
// shade/shading_normal.h). The camera's N and albedo AOVs read it.
struct shading_point {
  surface_point sp;
  material_point mp;
};

// The shading point of sp, as seen along r (sp was built from r's closest hit).
shading_point prepare_shading(const shading_context& ctx, const ray& r, const surface_point& sp);

// Radiance leaving the shading point p toward the origin of r (p was built from r's closest hit, with
// the width of state.cone there). On a camera path its alpha, mattes and split are filled in (the
// returned radiance is premultiplied by the path's coverage).
vec3 shade_prepared(const shading_context& ctx, const ray& r, const shading_point& p, const path_state& state,
                    ray_counts& counts);

// Radiance arriving along r (state.cone at r's origin): shade the closest visible hit, or what a
// miss sees; inside an absorbing volume the result is attenuated by Beer-Lambert over the travelled
// distance. A miss on the camera's path is transparent unless the path shows the background.
vec3 trace_radiance(const shading_context& ctx, const ray& r, const path_state& state, ray_counts& counts);

}  // namespace kiln
