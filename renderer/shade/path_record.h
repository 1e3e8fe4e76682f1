// The camera sample's output layers as shading feeds them: beside the radiance it computes, each ray
// carries a path_record saying what share of the sample it is and where its light is filed (the
// light split by first event, the light groups by source, the camera's passes, alpha, the mattes
// and deep surfaces). Shading calls the record_* hooks below at a few events (a surface covered,
// light added, a branch taken, the scene left); off the camera's own path most of them do nothing.
// Adding a filtered output layer is a record_pass call in shading; the radiance never depends on it.
// Depends on core and shade/surface.h, shade/material_eval.h only.
#pragma once

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <vector>

#include "core/aov_id.h"
#include "core/math.h"
#include "shade/material_eval.h"
#include "shade/surface.h"

namespace kiln {

// What a camera sample's own path collects for the output layers filtered like the beauty: one
// colour per AOV from aov::direct on (core/aov_id.h), each times the share of the sample it is
// filed for, so a pixel's filtered value is premultiplied by coverage like R G B. Shading files a
// layer by naming its AOV (record_pass); the light groups' and shadow mattes' slots stay unused,
// they are kept apart.
// - direct, reflection, refraction: the radiance split by its first event: direct (emission,
//   direct light and what is seen straight through BLEND surfaces or past the scene), reflection
//   (all that arrives through the first mirror ray) and refraction (through the first refracted
//   ray). The three sum to the radiance.
// - albedo_filtered, normal_filtered: at the surfaces the path covers (the first visible one and
//   those behind BLEND surfaces), times the share each covers: the denoising albedo
//   (material_eval.h's denoising_albedo) and the shading normal the N AOV holds (normal map
//   applied, bent toward the viewer);
// - diffuse, specular: the punctual lights' and the environment's direct light there by lobe of the
//   BRDF (Lambert, and GGX for dielectric and metal), shadowed as the beauty is; their sum plus the
//   emission and the background the path sees is direct;
// - shadow (one per light, then the environment's; empty unless kept): the luminance share of that
//   source's unshadowed direct light that its shadow rays find blocked, 1 − Y(shadowed)/Y(unshadowed),
//   0 where it adds nothing (behind the surface, zero BRDF, a light that casts no shadows, a dark
//   environment).
constexpr int first_pass = int(aov::direct);
constexpr int pass_count = aov_count - first_pass;
struct camera_passes {
  vec3 filtered[pass_count];
  std::vector<float> shadow;

  camera_passes() { clear(); }
  vec3& value(aov a) { return filtered[int(a) - first_pass]; }
  const vec3& value(aov a) const { return filtered[int(a) - first_pass]; }
  // Every value and shadow matte back to 0 (the mattes keep their count).
  void clear() {
    std::fill(std::begin(filtered), std::end(filtered), vec3(0.0f));
    std::fill(shadow.begin(), shadow.end(), 0.0f);
  }
};

// A surface a camera sample covers, and how much of the sample it covers.
struct path_layer {
  uint32_t instance = 0;
  float coverage = 0.0f;
};
constexpr int max_path_layers = 8;

// A surface the camera's own path shades, for deep output: its distance from the camera along the
// ray, the radiance it adds to the sample (already times the share of the sample it covers, so the
// surfaces' radiance sums to the sample's) and its coverage (its layer's share, summing to alpha).
struct path_surface {
  uint32_t instance = 0;
  float distance = 0.0f;
  vec3 radiance{0.0f};
  float coverage = 0.0f;
};

// What the camera's own path through a sample collects: the ray itself, its continuations behind
// BLEND surfaces and, with transmission_transparent, its refractions. Alpha is coverage × opacity
// along it: what reaches a background the camera does not show is transparency (no colour, alpha
// 0), so a sample through BLEND layers α1, α2, ... over nothing has alpha 1 − Π(1 − αi). Every
// surface met covers its share less what escapes through it, so the layers' coverages plus the
// transparency sum to 1 and Cryptomatte coverage sums to alpha.
struct camera_path {
  bool background_visible = false;        // --show-background: the background is opaque, never escaped into
  bool transmission_transparent = false;  // refraction that reaches the background is transparent too
  float transparency = 0.0f;              // the part of the sample that escaped
  path_layer layers[max_path_layers];     // in the order met; a deeper layer folds into the last
  int layer_count = 0;
  // Deep output only (record_surfaces): each surface shaded on the path, in the order met; a deeper
  // one folds into the last. origin is the camera ray's, in render space, for the distances.
  bool record_surfaces = false;
  vec3 origin{0.0f};
  path_surface surfaces[max_path_layers];
  int surface_count = 0;

  // Adds coverage to instance's layer.
  void cover(uint32_t instance, float coverage);
  // With record_surfaces: adds a surface at position (render space) with its radiance and coverage.
  void add_surface(uint32_t instance, const vec3& position, const vec3& radiance, float coverage);
};

// Where one ray of a camera sample's tree files what it adds. Passed by value inside path_state:
// a branch changes its own copy.
struct path_record {
  // On the camera's own path (null for a secondary ray): alpha and mattes go there.
  camera_path* camera = nullptr;
  float share = 1.0f;         // the part of the camera sample this ray carries (BLEND layers, glass)
  bool record_layers = true;  // false inside a refraction: what glass shows is the glass's matte
  // Where this ray's radiance is filed by first event: the passes' direct, reflection and refraction
  // (null: not kept, or the caller files it).
  camera_passes* split = nullptr;
  // The camera sample's light groups (null: not kept): one colour per scene light, then emission,
  // then the environment (render/light_groups.h). Every ray of the tree files the light it adds,
  // times tint: the colour its radiance is weighted by in the sample (mirror and refraction
  // weights, BLEND alpha and absorption along the way).
  vec3* groups = nullptr;
  vec3 tint{1.0f};
  // Where the camera path files its passes (null: not kept, or off the camera's path; nulled with
  // split, so diffuse and specular are always the direct light of the split's direct).
  camera_passes* passes = nullptr;
};

// --- What a ray's light adds.

// What a camera path sees directly (emission, direct light, background): the split's direct.
inline void record_direct(const path_record& r, const vec3& radiance) {
  if (r.split) r.split->value(aov::direct) += r.share * radiance;
}

// Light the ray adds from source group `group` (a light's index, emission_group, environment_group).
inline void record_group(const path_record& r, size_t group, const vec3& radiance) {
  if (r.groups) r.groups[group] += r.tint * radiance;
}

// What a mirror (reflection) or refracted ray brought back, weighted: the split's reflection or
// refraction.
inline void record_branch(const path_record& r, bool refraction, const vec3& radiance) {
  if (r.split) r.split->value(refraction ? aov::refraction : aov::reflection) += r.share * radiance;
}

// Light `light`'s direct light at a camera-path surface, by lobe and shadowed by visibility, and the
// share of its unshadowed luminance that is blocked (the shadow matte).
void record_light_passes(const path_record& r, size_t light, const brdf_lobes& lobes,
                         const vec3& unshadowed_light, const vec3& visibility);

// What the camera path adds to the filtered pass of AOV a (one after the light split's, such as
// diffuse alone for a light through a diffusely transmitting surface): its share of value.
inline void record_pass(const path_record& r, aov a, const vec3& value) {
  if (r.passes) r.passes->value(a) += r.share * value;
}

// Light added to the diffuse pass alone (a light through a diffusely transmitting surface).
inline void record_diffuse(const path_record& r, const vec3& light) { record_pass(r, aov::diffuse, light); }

// The environment's direct light at a camera-path surface by lobe, and its shadow matte (matte: the
// index of the environment's, after the lights'): the luminance arriving before and after the
// shadow rays.
void record_environment_passes(const path_record& r, size_t matte, const vec3& diffuse, const vec3& specular,
                               float unshadowed, float lit);

// --- Coverage: alpha, mattes, deep surfaces and the passes that go by coverage.

// The camera path's transparency so far (0 off it): record_covered takes what a surface's shading
// let escape as the difference.
inline float escaped_so_far(const path_record& r) { return r.camera ? r.camera->transparency : 0.0f; }

// A surface shaded on the camera's path (mp at sp, its radiance): it covers its share of the sample
// less what escaped through it since escaped_before, for the mattes, deep output and the
// denoiser's albedo and normal.
void record_covered(const path_record& r, const surface_point& sp, const material_point& mp,
                    const vec3& radiance, float escaped_before);

// The part behind a BLEND surface that is not traced (depth, throughput or budget spent): it stays
// covered by the surface, as opaque black, so the mattes still sum to alpha.
void record_untraced_behind(const path_record& r, const surface_point& sp, float share);

// A ray leaving the scene with weight (its absorption): true when it is the camera's path and the
// background is not shown, so its share of the sample is transparent and it brings no colour.
bool record_escape(const path_record& r, float weight);

// A holdout met by the camera's path: its share of the sample is transparent (true); false off it.
bool record_holdout(const path_record& r);

// --- The records of the rays a ray spawns.

// A secondary ray's: off the camera's path (its light is filed by the parent), tint its weight.
path_record secondary_record(const path_record& r, const vec3& tint);

// A refracted ray's: traced as the camera's own path when transmission is transparent (so the
// background it reaches counts as transparent, scaled by the share the refraction carries), else a
// secondary ray's.
path_record refracted_record(const path_record& r, const vec3& weight);

// The covered part (alpha) or the part behind (1 - alpha, the weight) of a BLEND surface: the same
// path, its share and tint scaled.
path_record scaled_record(const path_record& r, float weight);

// The ray's path on through an absorbing volume: its share and tint attenuated, the split and the
// passes left to the caller, which files what arrives once.
path_record through_volume_record(const path_record& r, const vec3& absorption);

}  // namespace kiln
