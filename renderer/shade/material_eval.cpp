#include "shade/material_eval.h"

#include <algorithm>
#include <cmath>

#include "shade/texture_sampling.h"

namespace kiln {

namespace {

// The lookup sample_texture_ref makes for ref (present).
texture_lookup lookup_of(const texture_ref& ref, const material_inputs& in, texel_encoding encoding) {
  // Sets beyond TEXCOORD_1 are not stored; they read TEXCOORD_0 (the loader warned).
  const int set = ref.texcoord == 1 ? 1 : 0;
  texture_lookup l;
  l.texture = uint32_t(ref.texture);
  l.encoding = encoding;
  l.uv = transform_uv(ref, in.uv[set]);
  const uv_footprint& f = in.footprint[set];
  // An empty footprint stays empty: the lookup reads level 0 by the magnification filter.
  if (!f.empty()) l.footprint = uv_footprint{transform_uv_vector(ref, f.dx), transform_uv_vector(ref, f.dy)};
  return l;
}

// Whether a and b map a point's UVs to the same texture coordinates.
bool same_uv_mapping(const texture_ref& a, const texture_ref& b) {
  return (a.texcoord == 1) == (b.texcoord == 1) && a.offset == b.offset && a.rotation == b.rotation &&
         a.uv_scale == b.uv_scale;
}

}  // namespace

vec4 sample_texture_ref(const scene& s, const texture_ref& ref, const material_inputs& in,
                        texel_encoding encoding) {
  const texture_lookup l = lookup_of(ref, in, encoding);
  vec4 out;
  sample_textures(s, in.filter, &l, 1, &out);
  return out;
}

material_point evaluate_material(const scene& s, const material& m, vec2 uv0) {
  material_inputs in;
  in.uv[0] = in.uv[1] = uv0;
  return evaluate_material(s, m, in);
}

material_texels sample_material_textures(const scene& s, const material& m, const material_inputs& in,
                                         bool with_normal) {
  material_texels t;
  // Room for every texture slot a material can have (the core five and the extensions' slots).
  constexpr int max_slots = 24;
  texture_lookup lookups[max_slots];
  vec4* targets[max_slots];
  int count = 0;
  const texture_ref* previous = nullptr;
  auto add = [&](const texture_ref& ref, texel_encoding encoding, vec4& target) {
    // Slots on the same UV set and transform (the usual case) share the transformed uv and
    // footprint: the same arithmetic on the same inputs.
    if (previous && same_uv_mapping(*previous, ref)) {
      lookups[count] = lookups[count - 1];
      lookups[count].texture = uint32_t(ref.texture);
      lookups[count].encoding = encoding;
    } else {
      lookups[count] = lookup_of(ref, in, encoding);
    }
    previous = &ref;
    targets[count++] = &target;
  };
  if (m.base_color_texture.present()) add(m.base_color_texture, texel_encoding::srgb, t.base_color);
  if (m.metallic_roughness_texture.present())
    add(m.metallic_roughness_texture, texel_encoding::linear, t.metallic_roughness);
  if (m.emissive_texture.present() && m.emissive_factor * m.emissive_strength != vec3(0.0f))
    add(m.emissive_texture, texel_encoding::srgb, t.emissive);
  if (m.transmission_texture.present() && m.transmission_factor > 0.0f)
    add(m.transmission_texture, texel_encoding::linear, t.transmission);
  if (with_normal && m.normal_texture.present()) add(m.normal_texture, texel_encoding::linear, t.normal);
  vec4 texels[max_slots];
  sample_textures(s, in.filter, lookups, count, texels);
  for (int i = 0; i < count; ++i) *targets[i] = texels[i];
  return t;
}

material_point evaluate_material(const scene& s, const material& m, const material_inputs& in) {
  return evaluate_material(m, in, sample_material_textures(s, m, in, false));
}

material_point evaluate_material(const material& m, const material_inputs& in, const material_texels& t) {
  material_point mp;
  vec4 base = m.base_color_factor * in.color0;
  if (m.base_color_texture.present()) base *= t.base_color;
  mp.base_color = vec3(base);
  mp.alpha = base.a;
  mp.metallic = m.metallic_factor;
  mp.roughness = m.roughness_factor;
  if (m.metallic_roughness_texture.present()) {
    const vec4& mr = t.metallic_roughness;
    mp.roughness *= mr.g;
    mp.metallic *= mr.b;
  }
  mp.metallic = std::clamp(mp.metallic, 0.0f, 1.0f);
  mp.roughness = std::clamp(mp.roughness, 0.0f, 1.0f);
  vec3 emission = m.emissive_factor * m.emissive_strength;
  if (m.emissive_texture.present() && emission != vec3(0.0f)) emission *= vec3(t.emissive);
  mp.emission = emission;
  mp.specular_weight = m.specular_factor;
  float r = (m.ior - 1.0f) / (m.ior + 1.0f);
  mp.dielectric_f0 = glm::min(vec3(r * r) * m.specular_color_factor, vec3(1.0f));
  mp.transmission = m.transmission_factor;
  if (m.transmission_texture.present() && mp.transmission > 0.0f) mp.transmission *= t.transmission.r;
  mp.transmission = std::clamp(mp.transmission, 0.0f, 1.0f);
  mp.unlit = m.unlit;
  return mp;
}

vec3 specular_f0(const material_point& mp) {
  return glm::mix(mp.dielectric_f0 * mp.specular_weight, mp.base_color, mp.metallic);
}

vec3 fresnel_schlick(const vec3& f0, float cos_theta) {
  float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  float m2 = m * m;
  return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

float highlight_footprint_alpha(float spread, float width, float light_distance, float curvature) {
  const float light_angle =
      std::isinf(light_distance) || !(light_distance > 0.0f) ? 0.0f : width / light_distance;
  return 0.25f * spread + 0.25f * light_angle + 0.5f * curvature * width;
}

namespace {

// The BRDF's three terms: the dielectric's diffuse and specular parts and the metal's specular
// (unweighted by metallic).
struct brdf_terms {
  vec3 dielectric_diffuse{0.0f};
  vec3 dielectric_specular{0.0f};
  vec3 metal{0.0f};
  bool zero = true;  // below the horizon
};

brdf_terms brdf_terms_at(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                         float footprint_alpha) {
  brdf_terms out;
  float n_dot_l = glm::dot(n, l);
  float n_dot_v = glm::dot(n, v);
  if (n_dot_l <= 0.0f || n_dot_v <= 0.0f) return out;
  vec3 h = glm::normalize(v + l);
  float n_dot_h = std::max(glm::dot(n, h), 0.0f);
  float v_dot_h = std::max(glm::dot(v, h), 0.0f);

  // GGX distribution and height-correlated Smith visibility (glTF appendix B).
  const float material_alpha = std::max(mp.roughness * mp.roughness, 1e-3f);
  float alpha = material_alpha;
  if (footprint_alpha > 0.0f)
    alpha = std::min(std::sqrt(alpha * alpha + footprint_alpha * footprint_alpha), 1.0f);
  float a2 = alpha * alpha;
  float d_denominator = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  float distribution = a2 / (pi * d_denominator * d_denominator);
  if (alpha > material_alpha) {
    // The widening is a filter over the footprint, not roughness: its share of the lobe's variance
    // gets Beckmann's Gaussian slopes, whose tail ends within a few α, instead of GGX's long tail
    // (a chrome sphere under the sun would otherwise glow far beyond the footprint). Both are
    // normalised, so the highlight keeps its energy.
    const float filter_share = 1.0f - material_alpha * material_alpha / a2;
    const float cos2 = n_dot_h * n_dot_h;
    const float tan2 = std::max(1.0f - cos2, 0.0f) / std::max(cos2, 1e-12f);
    const float beckmann = std::exp(-tan2 / a2) / (pi * a2 * std::max(cos2 * cos2, 1e-24f));
    distribution += filter_share * (beckmann - distribution);
  }
  float visibility_l = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0f - a2) + a2);
  float visibility_v = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0f - a2) + a2);
  float visibility = 0.5f / std::max(visibility_l + visibility_v, 1e-8f);

  // Dielectric layer: Fresnel-weighted specular over Lambert (KHR_materials_specular weights
  // the Fresnel term); metal: specular only, tinted by base colour.
  vec3 dielectric_fresnel = mp.specular_weight * fresnel_schlick(mp.dielectric_f0, v_dot_h);
  vec3 metal_fresnel = fresnel_schlick(mp.base_color, v_dot_h);
  // Transmitted light is traced as refraction, so it leaves the diffuse lobe (glTF's mix).
  vec3 diffuse = mp.base_color * ((1.0f - mp.transmission) / pi);
  out.dielectric_diffuse = (vec3(1.0f) - dielectric_fresnel) * diffuse;
  out.dielectric_specular = dielectric_fresnel * (distribution * visibility);
  out.metal = metal_fresnel * (distribution * visibility);
  out.zero = false;
  return out;
}

}  // namespace

vec3 evaluate_brdf(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                   float footprint_alpha) {
  const brdf_terms t = brdf_terms_at(mp, n, v, l, footprint_alpha);
  if (t.zero) return vec3(0.0f);
  return glm::mix(t.dielectric_diffuse + t.dielectric_specular, t.metal, mp.metallic);
}

brdf_lobes evaluate_brdf_lobes(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                               float footprint_alpha) {
  const brdf_terms t = brdf_terms_at(mp, n, v, l, footprint_alpha);
  if (t.zero) return {};
  return {t.dielectric_diffuse * (1.0f - mp.metallic),
          t.dielectric_specular * (1.0f - mp.metallic) + t.metal * mp.metallic};
}

vec3 denoising_albedo(const material_point& mp) {
  if (mp.unlit) return glm::clamp(mp.base_color, 0.0f, 1.0f);
  const float see_through = see_through_weight(mp);
  return glm::clamp(mp.base_color * (1.0f - see_through) + vec3(see_through), 0.0f, 1.0f);
}

}  // namespace kiln
