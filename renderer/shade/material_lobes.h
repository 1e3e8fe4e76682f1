// The lobes the glTF material extensions add to the metallic-roughness BRDF, each as its Khronos
// specification defines it: Charlie sheen with its directional albedo (KHR_materials_sheen), the
// thin-film Fresnel of Belcour and Barla (KHR_materials_iridescence), anisotropic GGX
// (KHR_materials_anisotropy) and Abbe-number dispersion (KHR_materials_dispersion). Free functions
// on plain values; material_eval composes them.
#pragma once

#include "core/math.h"
#include "shade/sheen_albedo.h"  // E(μ, r), the sheen lobe's directional albedo

namespace kiln {

// Charlie sheen distribution (Conty Estevez and Kulla 2017) for perceptual sheen roughness r:
// α = r², D = (2 + 1/α) · sin(θh)^(1/α) / 2π.
float charlie_distribution(float sheen_roughness, float n_dot_h);

// The specification's Charlie visibility, 1 / ((1 + Λ(n·v) + Λ(n·l)) · 4 · n·v · n·l).
float charlie_visibility(float sheen_roughness, float n_dot_v, float n_dot_l);

// The Charlie visibility's Λ(cos θ) for sheen roughness r, and the visibility from the view's Λ
// found once (lambda_v = charlie_lambda_at(r, n·v)): a point's light directions share the view's
// share, and each gives the same value as charlie_visibility.
float charlie_lambda_at(float sheen_roughness, float cos_theta);
float charlie_visibility_from(float sheen_roughness, float lambda_v, float n_dot_v, float n_dot_l);

// The iridescent Fresnel reflectance per R, G, B at cos θ (the half vector's angle to the view)
// of a thin film of ior film_ior and thickness in nanometres over a base of normal-incidence
// reflectance base_f0, seen from a medium of ior outside_ior (1, air).
vec3 iridescence_fresnel(float outside_ior, float film_ior, float cos_theta, float thickness_nm,
                         const vec3& base_f0);

// Anisotropic GGX: the distribution and the height-correlated Smith visibility with roughness
// αt along the tangent t and αb along the bitangent b, in the frame (t, b, n). Dot products with h,
// v and l are the caller's.
float ggx_anisotropic_distribution(float n_dot_h, float t_dot_h, float b_dot_h, float at, float ab);
float ggx_anisotropic_visibility(float n_dot_l, float n_dot_v, float t_dot_v, float b_dot_v, float t_dot_l,
                                 float b_dot_l, float at, float ab);

// KHR_materials_dispersion: the ior at R, G and B (656.3, 587.6, 486.1 nm) for ior n_d at 587.6 nm
// and the extension's dispersion (20 / Abbe number); ior itself when dispersion is 0.
vec3 dispersed_ior(float ior, float dispersion);

}  // namespace kiln
