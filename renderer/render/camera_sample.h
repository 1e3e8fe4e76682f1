// One camera sample: the ray through a film position, shaded, with what the AOVs and adaptive
// refinement need. A pure function of the position, so recomputing a sample gives the same bytes.
// Depends on shade and render; never on a backend.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film.h"
#include "render/motion_vectors.h"
#include "render/view_camera.h"
#include "shade/direct_light.h"
#include "shade/ray_cone.h"
#include "shade/whitted.h"

namespace kiln {

constexpr uint32_t no_instance = 0xFFFFFFFFu;  // the instance id of a sample that hit nothing

struct camera_sample {
  // Premultiplied: (radiance, alpha), alpha the camera path's coverage (1 for opaque hits and a
  // visible background, less through BLEND surfaces or transparent glass over nothing), 0 on a miss.
  vec4 rgba{0.0f};
  float depth = inf;  // ray distance of the hit; +inf on a miss
  // Cosine between the ray and the view axis: depth · view_cosine is the planar depth.
  float view_cosine = 1.0f;
  vec3 normal{0.0f};  // world shading normal of the hit; 0 on a miss
  uint32_t instance = no_instance;
  vec3 position{0.0f};    // world hit point; 0 on a miss
  vec3 albedo{0.0f};      // base colour after textures and vertex colours (only when asked for); 0 on a miss
  vec2 uv{0.0f};          // TEXCOORD_0; 0 on a miss
  int32_t node = -1;      // glTF node of the instance hit; -1 on a miss
  int32_t material = -1;  // glTF material index (material::source_index); -1 on a miss
  // With outputs.motion: the hit and its render-space point, from which the pixel's nearest sample
  // gets its motion (motion_of_nearest); motion stays 0 until then, and on a miss.
  hit surface_hit;
  dvec3 render_point{0.0};
  float time = 0.0f;  // when in the shutter the camera ray was traced (motion blur)
  vec4 motion{0.0f};
  // With outputs.groups: rgba's colour by light group (render/light_groups.h); else empty.
  std::vector<vec3> groups;
  // What the camera path collects for the filtered AOVs (shade/path_record.h): rgba's colour by
  // first event with outputs.split, the denoiser and relighting passes with outputs.passes, its
  // shadow mattes (one per light) only with outputs.shadow too.
  camera_passes passes;
  // The instances the sample covers and their coverage (summing to alpha), for Cryptomatte.
  path_layer layers[max_path_layers];
  int layer_count = 0;
  bool finite = true;  // false: the radiance was NaN or infinite; rgba is then 0 and it is counted
};

// What a camera sample records beside its colour and geometry AOVs.
struct sample_outputs {
  bool albedo = false;  // evaluates the material once more for the albedo AOV
  bool split = false;   // fills the light split of passes (direct, reflection, refraction)
  bool groups = false;  // fills groups
  bool passes = false;  // fills the other passes (albedo_filtered, N_filtered, diffuse, specular...)
  bool shadow = false;  // fills passes.shadow too (with passes)
  // Deep output: set to the caller's buffer, which each sample clears and fills with the surfaces
  // its camera path shades, their radiance summing to rgba's colour and their coverage to its
  // alpha (shade/path_record.h's camera_path::surfaces). Kept outside camera_sample, which adaptive
  // sampling stores for every pixel corner.
  std::vector<path_surface>* surfaces = nullptr;
  const scene_motion* motion = nullptr;  // fills surface_hit and render_point
  // The caller's triangle constants, kept from sample to sample (null: none); see triangle_memo.
  triangle_memo* memo = nullptr;
  // The sample's place in its pixel (count 0: not known, as for adaptive sampling's corners).
  pixel_stratum stratum;
};

// The sample outputs a film with aovs needs.
sample_outputs sample_outputs_for(const aov_set& aovs, const scene_motion* motion = nullptr);

// Traces and shades the camera ray through film position (px, py) in pixels (row 0 at the top).
// A miss sees the environment with alpha 1 when show_background is set, else it is transparent.
// cone is the ray's footprint at the camera (for texture filtering along the whole path).
camera_sample trace_camera_sample(const shading_context& ctx, const view_camera& cam, bool show_background,
                                  double px, double py, const ray_cone& cone, ray_counts& counts,
                                  const sample_outputs& outputs = {});

// A camera ray's first visible surface made ready to shade: the first half of shade_camera_hit,
// which the wave stage (render/tile_renderer.cpp) runs for a run of samples together.
struct camera_hit {
  ray r;  // the camera ray, its origin moved past culled back faces
  std::optional<hit> visible;
  float distance = 0.0f;  // from the camera ray's origin to the visible hit
  ray_cone at_hit;        // the ray's cone there
  shading_point p;        // the surface and material there (set when visible)
  // Its direct light, when plan_camera_light made it (in a run's light_terms, answered there).
  bool planned = false;
  planned_light light;
};

// The camera hit of the camera ray `start` whose closest hit `first` is known, with footprint cone.
void prepare_camera_hit(const shading_context& ctx, const ray& start, const std::optional<hit>& first,
                        const ray_cone& cone, ray_counts& counts, triangle_memo* memo, camera_hit& out);

// Plans the direct light of the prepared camera hit h into terms (its shadow rays to be answered
// with the run's, before h is shaded), when shading will ask for it: a visible lit surface that is
// not a matte. stratum and passes: what the sample's shading has (sample_outputs).
void plan_camera_light(const shading_context& ctx, const pixel_stratum& stratum, bool passes, camera_hit& h,
                       light_terms& terms);

// The sample of the camera ray `start` from its prepared camera hit: the second half of
// shade_camera_hit.
camera_sample shade_prepared_camera_hit(const shading_context& ctx, const view_camera& cam,
                                        bool show_background, const ray& start, const camera_hit& prepared,
                                        ray_counts& counts, const sample_outputs& outputs = {});

// trace_camera_sample for the camera ray `start` whose closest hit `first` is already known (the
// camera-ray stage of render/camera_rays.h traced it): prepare_camera_hit, then
// shade_prepared_camera_hit.
camera_sample shade_camera_hit(const shading_context& ctx, const view_camera& cam, bool show_background,
                               const ray& start, const std::optional<hit>& first, const ray_cone& cone,
                               ray_counts& counts, const sample_outputs& outputs = {});

// Makes `nearest` the sample that decides its pixel's AOVs, from s: the fields motion_of_nearest and
// store_nearest_sample read, not the path's layers, split and passes (hundreds of bytes and two
// vectors, copied for nothing on every nearer sample).
void keep_as_nearest(const camera_sample& s, camera_sample& nearest);

// Fills s.motion (forward and backward, in pixels) when s hit something and motion is set: once a
// pixel, for the sample that decides it, not for every sample.
void motion_of_nearest(camera_sample& s, const scene& world, const scene_motion* motion);

// Writes the AOVs of the sample that decides pixel i (the nearest) into the film's buffers that
// exist; Z as out.aovs.depth_kind says.
void store_nearest_sample(const camera_sample& s, film& out, size_t i);

}  // namespace kiln
