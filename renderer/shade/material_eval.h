// Evaluates a glTF material at a shading point (factors times textures), and the glTF
// metallic-roughness BRDF for punctual lights (glTF 2.0 specification, appendix B: Lambert
// diffuse plus GGX/Smith specular with Schlick's Fresnel; KHR_materials_specular and
// KHR_materials_ior adjust the dielectric reflectance). Depends on scene and texture sampling.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/scene.h"
#include "shade/surface.h"
#include "shade/texture_sampling.h"

namespace kiln {

// The parameters of the lobe extensions at a point, for materials that have any of them.
struct material_layers {
  // KHR_materials_clearcoat: the coat's weight, perceptual roughness and normal (unit; zero: the
  // shading normal; prepare_shading sets the unmapped or coat-mapped normal).
  float clearcoat = 0.0f;
  float clearcoat_roughness = 0.0f;
  vec3 clearcoat_normal{0.0f};
  // KHR_materials_sheen: colour (zero: no sheen) and perceptual roughness.
  vec3 sheen_color{0.0f};
  float sheen_roughness = 0.0f;
  // KHR_materials_iridescence: share of the thin-film Fresnel, film ior and thickness (nm).
  float iridescence = 0.0f;
  float iridescence_ior = 1.3f;
  float iridescence_thickness = 400.0f;
  // KHR_materials_diffuse_transmission: share of the diffuse lobe passed through, and its colour.
  float diffuse_transmission = 0.0f;
  vec3 diffuse_transmission_color{1.0f};
  // KHR_materials_anisotropy: strength and the unit direction of stretch in the tangent plane
  // (zero: isotropic; prepare_shading sets it where the surface has a tangent frame).
  float anisotropy = 0.0f;
  vec3 anisotropy_direction{0.0f};
  vec2 anisotropy_tangent_space{1.0f, 0.0f};  // the direction in (tangent, bitangent), rotated
};

// A material's parameters at one point, textures already applied.
struct material_point {
  vec3 base_color{1.0f};
  float alpha = 1.0f;
  float metallic = 1.0f;
  float roughness = 1.0f;        // perceptual; GGX alpha = roughness²
  vec3 emission{0.0f};           // emitted radiance
  float specular_weight = 1.0f;  // KHR_materials_specular specularFactor
  vec3 dielectric_f0{0.04f};     // reflectance at normal incidence for the dielectric part
  float transmission = 0.0f;     // KHR_materials_transmission share of the dielectric part
  bool unlit = false;            // KHR_materials_unlit
  // The lobe extensions' parameters; empty unless the material has one of them (most points
  // have none, and then pay for no more than this flag).
  std::optional<material_layers> layers;
};

// A point's layers, or every lobe off (zero weights) when it has none.
inline const material_layers& layers_of(const material_point& mp) {
  static const material_layers none;
  return mp.layers ? *mp.layers : none;
}

// Share of light a diffuse-transmitting surface passes to its other side: the dielectric, not
// specularly transmitted part times the diffuse transmission factor.
inline float diffuse_see_through_weight(const material_point& mp) {
  if (!mp.layers) return 0.0f;
  return (1.0f - mp.metallic) * (1.0f - mp.transmission) * mp.layers->diffuse_transmission;
}

// Share of light that the surface passes on through itself: the dielectric part times the
// transmission factor. The diffuse lobe is scaled by one minus the transmission factor.
inline float see_through_weight(const material_point& mp) { return (1.0f - mp.metallic) * mp.transmission; }

// The texture coordinate sets and vertex colour at a shading point.
struct material_inputs {
  vec2 uv[2] = {vec2(0.0f), vec2(0.0f)};   // TEXCOORD_0, TEXCOORD_1
  vec4 color0{1.0f};                       // COLOR_0 (multiplies the base colour)
  uv_footprint footprint[2];               // ray-cone footprint per UV set; empty: point samples
  const texture_filter* filter = nullptr;  // mip-mapped minification; null: level 0 only
};

material_point evaluate_material(const scene& s, const material& m, const material_inputs& in);

// The texels of the lobe extensions' textures (see material_texels). Left unset on construction
// (glm does not initialise), so the many points without lobes pay nothing for them.
struct lobe_texels {
  vec4 clearcoat;                   // R weights the coat
  vec4 clearcoat_roughness;         // G
  vec4 clearcoat_normal;            // the coat's normal map (read with the normal map)
  vec4 sheen_color;                 // RGB
  vec4 sheen_roughness;             // A
  vec4 iridescence;                 // R
  vec4 iridescence_thickness;       // G
  vec4 diffuse_transmission;        // A
  vec4 diffuse_transmission_color;  // RGB
  vec4 anisotropy;                  // RG direction, B strength
};

// The texels of m's textures that shading at one point reads, white where m has no such texture
// or shading skips it (emissive without emission, transmission with a zero factor, the normal map
// unless asked for).
struct material_texels {
  vec4 base_color{1.0f};
  vec4 metallic_roughness{1.0f};
  vec4 emissive{1.0f};
  vec4 transmission{1.0f};
  vec4 specular{1.0f};        // KHR_materials_specular: A weights the Fresnel term
  vec4 specular_color{1.0f};  // KHR_materials_specular: RGB tints the dielectric F0
  vec4 normal{1.0f};
  // The lobe extensions' texels, white where absent like the others, but only when has_lobes
  // (the material has a lobe extension); unset otherwise.
  bool has_lobes = false;
  lobe_texels lobes;
};

// Every texture lookup of m at `in` in one batch (sample_textures: slots on one UV set, transform
// and sampler over images of one size plan their texels once), the normal maps' (base and coat)
// when with_normal.
material_texels sample_material_textures(const scene& s, const material& m, const material_inputs& in,
                                         bool with_normal);

// evaluate_material from texels sample_material_textures read at the same point.
material_point evaluate_material(const material& m, const material_inputs& in, const material_texels& t);

inline material_inputs material_inputs_at(const surface_point& sp) {
  material_inputs in;
  in.uv[0] = sp.uv0;
  in.uv[1] = sp.uv1;
  in.color0 = sp.color0;
  in.footprint[0] = sp.footprint0;
  in.footprint[1] = sp.footprint1;
  return in;
}

// A material's texture (present) at a shading point: its UV set, KHR_texture_transform, sampler.
vec4 sample_texture_ref(const scene& s, const texture_ref& ref, const material_inputs& in,
                        texel_encoding encoding);

// Only TEXCOORD_0, no vertex colour.
material_point evaluate_material(const scene& s, const material& m, vec2 uv0);

// Reflectance at normal incidence, mixed between dielectric and metal by metallic.
vec3 specular_f0(const material_point& mp);

// Schlick's Fresnel with F90 = 1.
inline vec3 fresnel_schlick(const vec3& f0, float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

// Schlick's Fresnel for f0 mixed toward the thin film's (KHR_materials_iridescence) over a base of
// that f0 by the layers' iridescence.
vec3 iridescent_fresnel(const material_point& mp, const vec3& f0, float cos_theta);

// The Fresnel reflectance of the dielectric part (specular weight not applied) and of the metal
// at cos θ: Schlick's, mixed toward the thin film's by the iridescence share. Inline: every light
// of every hit evaluates them.
inline vec3 dielectric_fresnel(const material_point& mp, float cos_theta) {
  return mp.layers && mp.layers->iridescence > 0.0f ? iridescent_fresnel(mp, mp.dielectric_f0, cos_theta)
                                                    : fresnel_schlick(mp.dielectric_f0, cos_theta);
}
inline vec3 metal_fresnel(const material_point& mp, float cos_theta) {
  return mp.layers && mp.layers->iridescence > 0.0f ? iridescent_fresnel(mp, mp.base_color, cos_theta)
                                                    : fresnel_schlick(mp.base_color, cos_theta);
}

// KHR_materials_clearcoat's Fresnel weight clearcoat · F(coat normal · v) with F0 0.04: the share of
// light the coat reflects; everything beneath is seen through 1 minus it.
inline float clearcoat_weight(const material_point& mp, float coat_cos_theta) {
  if (!mp.layers || !(mp.layers->clearcoat > 0.0f)) return 0.0f;
  return mp.layers->clearcoat * fresnel_schlick(vec3(0.04f), std::abs(coat_cos_theta)).x;
}

// The coat normal at a shading point whose base normal is n.
inline vec3 coat_normal_or(const material_point& mp, const vec3& n) {
  return !mp.layers || mp.layers->clearcoat_normal == vec3(0.0f) ? n : mp.layers->clearcoat_normal;
}

// How much of each glossy lobe a light lights. Punctual lights light all of them; the environment
// lights the part of a smooth surface's reflection that is not traced as a mirror ray (which sees
// the environment itself), and none of the dielectric's transmissive share, whose reflection is
// always traced (shade/delta_lobes.h).
struct glossy_weights {
  float dielectric = 1.0f;  // the dielectric GGX lobe
  float metal = 1.0f;       // the metal's GGX lobe
  float coat = 1.0f;        // the clearcoat's GGX lobe
};

// How much a punctual light's GGX lobe is widened (see highlight_footprint_of): α becomes
// sqrt(α² + along²) toward `axis` (unit, world, across the normal) and sqrt(α² + across²) at right
// angles to it; with no axis, sqrt(α² + along²) every way. All zero: not widened.
struct highlight_footprint {
  vec3 axis{0.0f};
  float along = 0.0f;
  float across = 0.0f;
};

// BRDF value f(v, l) for unit vectors around the shading normal n; zero below the horizon, the GGX
// lobes widened by footprint.
vec3 evaluate_brdf(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                   const highlight_footprint& footprint = {});

// The diffuse transmission lobe (KHR_materials_diffuse_transmission) for a light on the far side
// of the surface from the viewer (n·l < 0 < n·v): Lambert in the transmission colour, through the
// base's Fresnel, the sheen's albedo scaling and the coat; zero unless the material transmits
// diffusely.
vec3 evaluate_diffuse_btdf(const material_point& mp, const vec3& n, const vec3& v, const vec3& l);

// evaluate_brdf by lobe: the Lambert term and the glossy terms (GGX dielectric and metal, sheen,
// clearcoat); diffuse + specular equals evaluate_brdf to float rounding.
struct brdf_lobes {
  vec3 diffuse{0.0f};
  vec3 specular{0.0f};
};
brdf_lobes evaluate_brdf_lobes(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                               const highlight_footprint& footprint = {});

// evaluate_brdf_lobes with the glossy lobes weighted by weights (no footprint widening).
brdf_lobes evaluate_brdf_lobes(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                               const glossy_weights& weights);

// What a point's BRDF shares across its light directions, for the view v around the normal n: the
// view's cosine, the sheen's albedo and Charlie Λ at it, and the coat's normal, cosine and weight.
// Found once (brdf_view_of) and passed to each direction's evaluation below, which then gives the
// same bits as the evaluation without it.
struct brdf_view {
  float n_dot_v = 0.0f;
  float sheen_albedo_v = 0.0f;  // E(n·v, sheen roughness); 0 without sheen
  float sheen_lambda_v = 0.0f;  // the Charlie visibility's Λ(n·v); 0 without sheen
  vec3 coat_normal{0.0f};
  float coat_v = 0.0f;       // coat normal · v
  float coat_weight = 0.0f;  // clearcoat_weight at coat_v; 0 without a coat
};
brdf_view brdf_view_of(const material_point& mp, const vec3& n, const vec3& v);

vec3 evaluate_brdf(const brdf_view& view, const material_point& mp, const vec3& n, const vec3& v,
                   const vec3& l, const highlight_footprint& footprint);
brdf_lobes evaluate_brdf_lobes(const brdf_view& view, const material_point& mp, const vec3& n, const vec3& v,
                               const vec3& l, const highlight_footprint& footprint);
brdf_lobes evaluate_brdf_lobes(const brdf_view& view, const material_point& mp, const vec3& n, const vec3& v,
                               const vec3& l, const glossy_weights& weights);

// The albedo a denoiser divides out (Open Image Denoise's auxiliary albedo: the surface's
// reflectance independent of light and view, within [0, 1]): the base colour for the diffuse
// dielectric part and for metal (its reflectance at normal incidence), 1 for the transmissive part
// (OIDN's choice for glass), mixed by metallic and transmission; the base colour for unlit
// surfaces. Clamped to [0, 1].
vec3 denoising_albedo(const material_point& mp);

// The widening a punctual light's highlight needs so that it covers at least the footprint it is
// seen through, instead of a sub-pixel spike of up to ~1e4 that no sample count resolves (a delta
// light on a near-delta surface). Over the footprint the half vector turns by half the view's
// spread and half the light's angle across the footprint's width, every way, and the normal by
// curvature × width in each principal direction; the lobe's width is set to half of that range,
// direction by direction. spread, width: the ray cone at the hit (radians, world units);
// light_distance: infinite for directional lights.
// The widened lobe stays normalised (the footprint's share takes Beckmann's short-tailed slopes, see
// evaluate_brdf), and it widens only as far as the normal really turns across the footprint: a
// highlight is spread over the surface it would have lit, so its energy is kept (on a cylinder, a
// lobe widened along the axis by the turn around it stretched the highlight off the cylinder's
// ends). Images converge with spp, and the highlight sharpens as the footprint shrinks.
highlight_footprint highlight_footprint_of(float spread, float width, float light_distance,
                                           const surface_curvature& curvature);

}  // namespace kiln
