// Directions drawn from a material's lobes, for lighting by the environment: a mixture of a cosine
// lobe (Lambert and sheen), GGX visible normals (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals") for the base's and the coat's glossy lobes, and a cosine lobe below the surface
// (diffuse transmission), each chosen in proportion to an estimate of its albedo at the view. The
// mixture's density is what multiple importance sampling weighs the environment's own against.
// Depends on material_eval only.
#pragma once

#include <optional>

#include "shade/material_eval.h"

namespace kiln {

struct lobe_sampler {
  vec3 normal{0.0f, 0.0f, 1.0f};  // the shading normal
  vec3 coat_normal{0.0f, 0.0f, 1.0f};
  float alpha = 1.0f;       // GGX alpha of the base's glossy lobe (isotropic stand-in when anisotropic)
  float coat_alpha = 1.0f;  // and of the coat's
  // Selection probabilities, summing to 1, or all 0 when no lobe reflects anything.
  float diffuse = 0.0f;
  float specular = 0.0f;
  float coat = 0.0f;
  float back = 0.0f;  // diffuse transmission, below the surface
};

// The sampler of mp's lobes at shading normal n (unit) for the unit view direction v, with the glossy
// lobes weighted as the light that uses it weighs them.
lobe_sampler make_lobe_sampler(const material_point& mp, const vec3& n, const vec3& v,
                               const glossy_weights& weights);

// A unit direction drawn from the mixture by three uniform numbers in [0, 1) (u.x picks the lobe);
// empty when no lobe is drawn or the lobe's draw fails (a GGX normal that reflects below the surface).
std::optional<vec3> sample_lobes(const lobe_sampler& s, const vec3& v, const vec3& u);

// The mixture's density per steradian of drawing the unit direction l.
float lobe_pdf(const lobe_sampler& s, const vec3& v, const vec3& l);

// GGX's distribution of visible normals: a half vector drawn for the view v, both in the frame whose
// z is the normal, and the density of l = reflect(−v, h) in it.
vec3 sample_ggx_visible_normal(const vec3& v_local, float alpha, const vec2& u);
float ggx_reflection_pdf(float alpha, float n_dot_v, float n_dot_h);

}  // namespace kiln
