#include "shade/material_eval.h"

#include <algorithm>
#include <cmath>

#include "shade/material_lobes.h"
#include "shade/texture_sampling.h"

namespace kiln {

namespace {

// ref's texture coordinates at the point: its UV set's uv and footprint through its transform.
inline void map_uv(const texture_ref& ref, const material_inputs& in, vec2& uv, uv_footprint& footprint) {
  // Sets beyond TEXCOORD_1 are not stored; they read TEXCOORD_0 (the loader warned).
  const int set = ref.texcoord == 1 ? 1 : 0;
  uv = transform_uv(ref, in.uv[set]);
  const uv_footprint& f = in.footprint[set];
  // An empty footprint stays empty: the lookup reads level 0 by the magnification filter.
  footprint = f.empty() ? uv_footprint{}
                        : uv_footprint{transform_uv_vector(ref, f.dx), transform_uv_vector(ref, f.dy)};
}

// The lookup sample_texture_ref makes for ref (present).
texture_lookup lookup_of(const texture_ref& ref, const material_inputs& in, texel_encoding encoding) {
  texture_lookup l;
  l.texture = uint32_t(ref.texture);
  l.encoding = encoding;
  map_uv(ref, in, l.uv, l.footprint);
  return l;
}

// Whether a and b map a point's UVs to the same texture coordinates.
bool same_uv_mapping(const texture_ref& a, const texture_ref& b) {
  return (a.texcoord == 1) == (b.texcoord == 1) && a.offset == b.offset && a.rotation == b.rotation &&
         a.uv_scale == b.uv_scale;
}

// Every lobe texel white: what a slot without a texture reads.
const lobe_texels& white_lobe_texels() {
  static const lobe_texels white = [] {
    lobe_texels t;
    for (vec4* v : {&t.clearcoat, &t.clearcoat_roughness, &t.clearcoat_normal, &t.sheen_color,
                    &t.sheen_roughness, &t.iridescence, &t.iridescence_thickness, &t.diffuse_transmission,
                    &t.diffuse_transmission_color, &t.anisotropy})
      *v = vec4(1.0f);
    return t;
  }();
  return white;
}

// The lobe extensions' factors times their textures (each texture's channel as its specification
// says), clamped to the ranges the lobes are defined on.
void evaluate_lobe_extensions(const material& m, const material_texels& texels, material_point& mp) {
  if (!m.has_lobe_extensions()) return;
  material_layers& L = mp.layers.emplace();
  const lobe_texels& t = texels.has_lobes ? texels.lobes : white_lobe_texels();
  if (m.clearcoat_factor > 0.0f) {
    L.clearcoat = m.clearcoat_factor * (m.clearcoat_texture.present() ? t.clearcoat.r : 1.0f);
    L.clearcoat_roughness = m.clearcoat_roughness_factor *
                            (m.clearcoat_roughness_texture.present() ? t.clearcoat_roughness.g : 1.0f);
    L.clearcoat = std::clamp(L.clearcoat, 0.0f, 1.0f);
    L.clearcoat_roughness = std::clamp(L.clearcoat_roughness, 0.0f, 1.0f);
  }
  if (m.sheen_color_factor != vec3(0.0f)) {
    L.sheen_color = m.sheen_color_factor;
    if (m.sheen_color_texture.present()) L.sheen_color *= vec3(t.sheen_color);
    L.sheen_roughness =
        m.sheen_roughness_factor * (m.sheen_roughness_texture.present() ? t.sheen_roughness.a : 1.0f);
    L.sheen_roughness = std::clamp(L.sheen_roughness, 0.0f, 1.0f);
  }
  if (m.iridescence_factor > 0.0f) {
    L.iridescence = m.iridescence_factor * (m.iridescence_texture.present() ? t.iridescence.r : 1.0f);
    L.iridescence = std::clamp(L.iridescence, 0.0f, 1.0f);
    // Beyond these the film shows no interference the spectral fit resolves (its terms have
    // vanished), and the optical path would overflow float.
    constexpr float max_film_ior = 100.0f, max_thickness_nm = 1e6f;
    L.iridescence_ior = std::min(m.iridescence_ior, max_film_ior);
    L.iridescence_thickness =
        std::clamp(m.iridescence_thickness_texture.present()
                       ? glm::mix(m.iridescence_thickness_minimum, m.iridescence_thickness_maximum,
                                  t.iridescence_thickness.g)
                       : m.iridescence_thickness_maximum,
                   0.0f, max_thickness_nm);
  }
  if (m.diffuse_transmission_factor > 0.0f) {
    L.diffuse_transmission = m.diffuse_transmission_factor *
                             (m.diffuse_transmission_texture.present() ? t.diffuse_transmission.a : 1.0f);
    L.diffuse_transmission = std::clamp(L.diffuse_transmission, 0.0f, 1.0f);
    L.diffuse_transmission_color = m.diffuse_transmission_color_factor;
    if (m.diffuse_transmission_color_texture.present())
      L.diffuse_transmission_color *= vec3(t.diffuse_transmission_color);
  }
  if (m.anisotropy_strength > 0.0f) {
    vec2 direction(1.0f, 0.0f);
    float strength = m.anisotropy_strength;
    if (m.anisotropy_texture.present()) {
      direction = vec2(t.anisotropy) * 2.0f - 1.0f;
      strength *= t.anisotropy.b;
      const float length = glm::length(direction);
      direction = length > 0.0f ? direction / length : vec2(1.0f, 0.0f);
    }
    const float c = std::cos(m.anisotropy_rotation), s = std::sin(m.anisotropy_rotation);
    L.anisotropy_tangent_space = vec2(c * direction.x - s * direction.y, s * direction.x + c * direction.y);
    L.anisotropy = std::clamp(strength, 0.0f, 1.0f);
  }
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
  // Uninitialised room (only the first `count` are written, then read): zeroing all of it was a
  // visible cost of every shaded hit.
  alignas(texture_lookup) unsigned char lookup_storage[sizeof(texture_lookup) * max_slots];
  texture_lookup* lookups = reinterpret_cast<texture_lookup*>(lookup_storage);
  const texture_ref* refs[max_slots];
  texel_encoding encodings[max_slots];
  vec4* targets[max_slots];
  int count = 0;
  auto add = [&](const texture_ref& ref, texel_encoding encoding, vec4& target) {
    refs[count] = &ref;
    encodings[count] = encoding;
    targets[count++] = &target;
  };
  if (m.base_color_texture.present()) add(m.base_color_texture, texel_encoding::srgb, t.base_color);
  if (m.metallic_roughness_texture.present())
    add(m.metallic_roughness_texture, texel_encoding::linear, t.metallic_roughness);
  if (m.emissive_texture.present() && m.emissive_factor * m.emissive_strength != vec3(0.0f))
    add(m.emissive_texture, texel_encoding::srgb, t.emissive);
  if (m.transmission_texture.present() && m.transmission_factor > 0.0f)
    add(m.transmission_texture, texel_encoding::linear, t.transmission);
  if (m.specular_texture.present()) add(m.specular_texture, texel_encoding::linear, t.specular);
  if (m.specular_color_texture.present())
    add(m.specular_color_texture, texel_encoding::srgb, t.specular_color);
  if (m.has_lobe_extensions()) {
    t.has_lobes = true;
    lobe_texels& lt = t.lobes = white_lobe_texels();
    if (m.clearcoat_factor > 0.0f) {
      if (m.clearcoat_texture.present()) add(m.clearcoat_texture, texel_encoding::linear, lt.clearcoat);
      if (m.clearcoat_roughness_texture.present())
        add(m.clearcoat_roughness_texture, texel_encoding::linear, lt.clearcoat_roughness);
      if (with_normal && m.clearcoat_normal_texture.present())
        add(m.clearcoat_normal_texture, texel_encoding::linear, lt.clearcoat_normal);
    }
    if (m.sheen_color_factor != vec3(0.0f)) {
      if (m.sheen_color_texture.present()) add(m.sheen_color_texture, texel_encoding::srgb, lt.sheen_color);
      if (m.sheen_roughness_texture.present())
        add(m.sheen_roughness_texture, texel_encoding::linear, lt.sheen_roughness);
    }
    if (m.iridescence_factor > 0.0f) {
      if (m.iridescence_texture.present()) add(m.iridescence_texture, texel_encoding::linear, lt.iridescence);
      if (m.iridescence_thickness_texture.present())
        add(m.iridescence_thickness_texture, texel_encoding::linear, lt.iridescence_thickness);
    }
    if (m.diffuse_transmission_factor > 0.0f) {
      if (m.diffuse_transmission_texture.present())
        add(m.diffuse_transmission_texture, texel_encoding::linear, lt.diffuse_transmission);
      if (m.diffuse_transmission_color_texture.present())
        add(m.diffuse_transmission_color_texture, texel_encoding::srgb, lt.diffuse_transmission_color);
    }
    if (m.anisotropy_strength > 0.0f && m.anisotropy_texture.present())
      add(m.anisotropy_texture, texel_encoding::linear, lt.anisotropy);
  }
  if (with_normal && m.normal_texture.present()) add(m.normal_texture, texel_encoding::linear, t.normal);
  // Slots on the same UV set and transform (the usual case) share the transformed uv and
  // footprint: the same arithmetic on the same inputs. They are carried in locals and stored
  // field by field: copying them back from a lookup (or a whole lookup) just stored field by field,
  // as one wide copy, stalled on store forwarding.
  vec2 uv(0.0f);
  uv_footprint footprint;
  for (int i = 0; i < count; ++i) {
    const texture_ref& ref = *refs[i];
    if (i == 0 || !same_uv_mapping(*refs[i - 1], ref)) map_uv(ref, in, uv, footprint);
    texture_lookup& l = lookups[i];
    l.texture = uint32_t(ref.texture);
    l.encoding = encodings[i];
    l.uv = uv;
    l.footprint = footprint;
  }
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
  // KHR_materials_specular: the factors times their textures (specularTexture's alpha,
  // specularColorTexture's RGB); F0 from the ior, tinted, and kept at most 1.
  mp.specular_weight = m.specular_factor;
  if (m.specular_texture.present()) mp.specular_weight *= t.specular.a;
  vec3 specular_color = m.specular_color_factor;
  if (m.specular_color_texture.present()) specular_color *= vec3(t.specular_color);
  float r = (m.ior - 1.0f) / (m.ior + 1.0f);
  mp.dielectric_f0 = glm::min(vec3(r * r) * specular_color, vec3(1.0f));
  mp.transmission = m.transmission_factor;
  if (m.transmission_texture.present() && mp.transmission > 0.0f) mp.transmission *= t.transmission.r;
  mp.transmission = std::clamp(mp.transmission, 0.0f, 1.0f);
  mp.unlit = m.unlit;
  evaluate_lobe_extensions(m, t, mp);
  return mp;
}

vec3 specular_f0(const material_point& mp) {
  return glm::mix(mp.dielectric_f0 * mp.specular_weight, mp.base_color, mp.metallic);
}

highlight_footprint highlight_footprint_of(float spread, float width, float light_distance,
                                           const surface_curvature& curvature) {
  const float light_angle =
      std::isinf(light_distance) || !(light_distance > 0.0f) ? 0.0f : width / light_distance;
  const float every_way = 0.25f * spread + 0.25f * light_angle;
  return {curvature.axis, every_way + 0.5f * curvature.major * width,
          every_way + 0.5f * curvature.minor * width};
}

vec3 iridescent_fresnel(const material_point& mp, const vec3& f0, float cos_theta) {
  const material_layers& L = layers_of(mp);
  // Under a clearcoat the film lies below the coat's ior 1.5, not air (the extension's layering).
  const float outside_ior = L.clearcoat > 0.0f ? 1.5f : 1.0f;
  const vec3 film =
      iridescence_fresnel(outside_ior, L.iridescence_ior, cos_theta, L.iridescence_thickness, f0);
  return glm::mix(fresnel_schlick(f0, cos_theta), film, L.iridescence);
}

namespace {

float max3(const vec3& v) { return std::max({v.x, v.y, v.z}); }

// The footprint's axis across the normal n as a unit tangent; zero when it has none (or it lies
// along n).
vec3 footprint_tangent(const highlight_footprint& f, const vec3& n) {
  if (f.axis == vec3(0.0f) || f.along == f.across) return vec3(0.0f);
  const vec3 t = f.axis - n * glm::dot(n, f.axis);
  const float length = glm::length(t);
  return length > 1e-4f ? t / length : vec3(0.0f);
}

// GGX D · V (glTF appendix B: height-correlated Smith) for perceptual roughness r around the unit
// normal n, widened by the footprint f (see highlight_footprint_of).
[[gnu::always_inline]] inline float ggx_lobe(float roughness, const vec3& n, const vec3& h, const vec3& v,
                                             const vec3& l, float n_dot_h, float n_dot_v, float n_dot_l,
                                             const highlight_footprint& f) {
  const float material_alpha = std::max(roughness * roughness, 1e-3f);
  float alpha_t = material_alpha, alpha_b = material_alpha;
  if (f.along > 0.0f) {
    alpha_t = std::min(std::sqrt(material_alpha * material_alpha + f.along * f.along), 1.0f);
    alpha_b = std::min(std::sqrt(material_alpha * material_alpha + f.across * f.across), 1.0f);
  }
  const vec3 t = footprint_tangent(f, n);
  if (t == vec3(0.0f)) alpha_b = alpha_t;  // every way alike
  float distribution, visibility;
  const float cos2 = n_dot_h * n_dot_h;
  float slope2;  // the half vector's squared slopes over the lobe's: tan²θ_h / α² when round
  if (alpha_t == alpha_b) {
    const float a2 = alpha_t * alpha_t;
    const float d_denominator = cos2 * (a2 - 1.0f) + 1.0f;
    distribution = a2 / (pi * d_denominator * d_denominator);
    const float visibility_l = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0f - a2) + a2);
    const float visibility_v = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0f - a2) + a2);
    visibility = 0.5f / std::max(visibility_l + visibility_v, 1e-8f);
    slope2 = std::max(1.0f - cos2, 0.0f) / (std::max(cos2, 1e-12f) * a2);
  } else {
    const vec3 b = glm::cross(n, t);
    const float t_dot_h = glm::dot(t, h), b_dot_h = glm::dot(b, h);
    distribution = ggx_anisotropic_distribution(n_dot_h, t_dot_h, b_dot_h, alpha_t, alpha_b);
    visibility = ggx_anisotropic_visibility(n_dot_l, n_dot_v, glm::dot(t, v), glm::dot(b, v), glm::dot(t, l),
                                            glm::dot(b, l), alpha_t, alpha_b);
    slope2 = (t_dot_h * t_dot_h / (alpha_t * alpha_t) + b_dot_h * b_dot_h / (alpha_b * alpha_b)) /
             std::max(cos2, 1e-12f);
  }
  const float narrower = std::min(alpha_t, alpha_b);
  if (narrower > material_alpha) {
    // The widening is a filter over the footprint, not roughness: its share of the lobe's variance
    // gets Beckmann's Gaussian slopes, whose tail ends within a few α, instead of GGX's long tail
    // (a chrome sphere under the sun would otherwise glow far beyond the footprint). Both are
    // normalised. The share is the narrower direction's: where the footprint does not widen the
    // lobe, the material's own tail stays (Beckmann's short one kept light on a cylinder that GGX's
    // spreads past its ends).
    const float filter_share = 1.0f - material_alpha * material_alpha / (narrower * narrower);
    const float beckmann = std::exp(-slope2) / (pi * alpha_t * alpha_b * std::max(cos2 * cos2, 1e-24f));
    distribution += filter_share * (beckmann - distribution);
  }
  return distribution * visibility;
}

// KHR_materials_anisotropy's lobe: roughness α along the bitangent, mix(α, 1, strength²) along the
// direction of anisotropy, both widened in quadrature by the footprint's width in their direction.
float anisotropic_lobe(const material_point& mp, const vec3& n, const vec3& v, const vec3& l, const vec3& h,
                       const highlight_footprint& footprint) {
  const material_layers& L = layers_of(mp);
  vec3 t = L.anisotropy_direction - n * glm::dot(n, L.anisotropy_direction);
  const float t_length = glm::length(t);
  const float n_dot_h = std::max(glm::dot(n, h), 0.0f);
  const float n_dot_v = glm::dot(n, v), n_dot_l = glm::dot(n, l);
  if (!(t_length > 1e-6f)) return ggx_lobe(mp.roughness, n, h, v, l, n_dot_h, n_dot_v, n_dot_l, footprint);
  t /= t_length;
  const vec3 b = glm::cross(n, t);
  const float alpha = std::max(mp.roughness * mp.roughness, 1e-3f);
  float at = glm::mix(alpha, 1.0f, L.anisotropy * L.anisotropy), ab = alpha;
  // The footprint's widths in the material's frame: its variance along t and along b.
  const vec3 axis = footprint_tangent(footprint, n);
  const float along2 = footprint.along * footprint.along, across2 = footprint.across * footprint.across;
  const float share_t = axis == vec3(0.0f) ? 1.0f : glm::dot(axis, t) * glm::dot(axis, t);
  const float widen_t = axis == vec3(0.0f) ? along2 : along2 * share_t + across2 * (1.0f - share_t);
  const float widen_b = axis == vec3(0.0f) ? along2 : along2 * (1.0f - share_t) + across2 * share_t;
  at = std::min(std::sqrt(at * at + widen_t), 1.0f);
  ab = std::min(std::sqrt(ab * ab + widen_b), 1.0f);
  return ggx_anisotropic_distribution(n_dot_h, glm::dot(t, h), glm::dot(b, h), at, ab) *
         ggx_anisotropic_visibility(n_dot_l, n_dot_v, glm::dot(t, v), glm::dot(b, v), glm::dot(t, l),
                                    glm::dot(b, l), at, ab);
}

// KHR_materials_sheen's albedo scaling of what lies beneath the sheen, for the view and light
// cosines (the specification's min over both).
// sheen_scaling with the view's albedo E(n·v) already found.
float sheen_scaling_from(const material_point& mp, float albedo_v, float n_dot_l) {
  const material_layers& L = layers_of(mp);
  if (L.sheen_color == vec3(0.0f)) return 1.0f;
  const float strength = max3(L.sheen_color);
  // The spec's fitted visibility lets E pass 1 at grazing views on smooth sheen: keep the base's
  // weight from turning negative there.
  return std::max(std::min(1.0f - strength * albedo_v,
                           1.0f - strength * sheen_directional_albedo(n_dot_l, L.sheen_roughness)),
                  0.0f);
}

float sheen_scaling(const material_point& mp, float n_dot_v, float n_dot_l) {
  return sheen_scaling_from(mp, sheen_directional_albedo(n_dot_v, layers_of(mp).sheen_roughness), n_dot_l);
}

brdf_lobes brdf_terms_at(const brdf_view& view, const material_point& mp, const vec3& n, const vec3& v,
                         const vec3& l, const highlight_footprint& footprint, bool& zero,
                         const glossy_weights* weights = nullptr) {
  const material_layers& L = layers_of(mp);
  brdf_lobes out;
  zero = true;
  const float n_dot_l = glm::dot(n, l);
  const float n_dot_v = view.n_dot_v;
  const bool coated = L.clearcoat > 0.0f;
  if (!(n_dot_l > 0.0f && n_dot_v > 0.0f) && !coated) return out;
  const vec3 h = glm::normalize(v + l);
  if (n_dot_l > 0.0f && n_dot_v > 0.0f) {
    zero = false;
    const float n_dot_h = std::max(glm::dot(n, h), 0.0f);
    const float v_dot_h = std::max(glm::dot(v, h), 0.0f);
    const float specular = L.anisotropy > 0.0f && L.anisotropy_direction != vec3(0.0f)
                               ? anisotropic_lobe(mp, n, v, l, h, footprint)
                               : ggx_lobe(mp.roughness, n, h, v, l, n_dot_h, n_dot_v, n_dot_l, footprint);
    // Dielectric: KHR_materials_specular's fresnel_mix (the layer takes weight · F, the base what
    // the strongest channel leaves); metal: specular only, tinted by base colour. Transmitted light
    // (specular and diffuse) is traced or lit from the far side, so it leaves the diffuse lobe.
    const vec3 fresnel = mp.specular_weight * dielectric_fresnel(mp, v_dot_h);
    const vec3 diffuse = mp.base_color * ((1.0f - mp.transmission) * (1.0f - L.diffuse_transmission) / pi);
    out.diffuse = ((1.0f - max3(fresnel)) * diffuse) * (1.0f - mp.metallic);
    out.specular = weights ? (fresnel * specular) * ((1.0f - mp.metallic) * weights->dielectric) +
                                 (metal_fresnel(mp, v_dot_h) * specular) * (mp.metallic * weights->metal)
                           : (fresnel * specular) * (1.0f - mp.metallic) +
                                 (metal_fresnel(mp, v_dot_h) * specular) * mp.metallic;
    if (L.sheen_color != vec3(0.0f)) {
      const float scaling = sheen_scaling_from(mp, view.sheen_albedo_v, n_dot_l);
      out.diffuse *= scaling;
      out.specular =
          out.specular * scaling +
          L.sheen_color * (charlie_distribution(L.sheen_roughness, n_dot_h) *
                           charlie_visibility_from(L.sheen_roughness, view.sheen_lambda_v, n_dot_v, n_dot_l));
    }
  }
  if (coated) {
    // fresnel_coat: the coat's GGX layer (no Fresnel of its own) weighted by clearcoat · F(nc · v),
    // over everything beneath weighted by one minus that.
    const vec3& nc = view.coat_normal;
    const float coat_v = view.coat_v, coat_l = glm::dot(nc, l);
    const float weight = view.coat_weight;
    out.diffuse *= 1.0f - weight;
    out.specular *= 1.0f - weight;
    if (coat_v > 0.0f && coat_l > 0.0f) {
      zero = false;
      out.specular += vec3(weight * (weights ? weights->coat : 1.0f) *
                           ggx_lobe(L.clearcoat_roughness, nc, h, v, l, std::max(glm::dot(nc, h), 0.0f),
                                    coat_v, coat_l, footprint));
    }
  }
  return out;
}

}  // namespace

brdf_view brdf_view_of(const material_point& mp, const vec3& n, const vec3& v) {
  const material_layers& L = layers_of(mp);
  brdf_view view;
  view.n_dot_v = glm::dot(n, v);
  if (L.sheen_color != vec3(0.0f)) {
    view.sheen_albedo_v = sheen_directional_albedo(view.n_dot_v, L.sheen_roughness);
    view.sheen_lambda_v = charlie_lambda_at(L.sheen_roughness, view.n_dot_v);
  }
  view.coat_normal = coat_normal_or(mp, n);
  if (L.clearcoat > 0.0f) {
    view.coat_v = glm::dot(view.coat_normal, v);
    view.coat_weight = clearcoat_weight(mp, view.coat_v);
  }
  return view;
}

vec3 evaluate_brdf(const brdf_view& view, const material_point& mp, const vec3& n, const vec3& v,
                   const vec3& l, const highlight_footprint& footprint) {
  bool zero = true;
  const brdf_lobes t = brdf_terms_at(view, mp, n, v, l, footprint, zero);
  if (zero) return vec3(0.0f);
  return t.diffuse + t.specular;
}

brdf_lobes evaluate_brdf_lobes(const brdf_view& view, const material_point& mp, const vec3& n, const vec3& v,
                               const vec3& l, const highlight_footprint& footprint) {
  bool zero = true;
  const brdf_lobes t = brdf_terms_at(view, mp, n, v, l, footprint, zero);
  if (zero) return {};
  return t;
}

brdf_lobes evaluate_brdf_lobes(const brdf_view& view, const material_point& mp, const vec3& n, const vec3& v,
                               const vec3& l, const glossy_weights& weights) {
  bool zero = true;
  const brdf_lobes t = brdf_terms_at(view, mp, n, v, l, highlight_footprint{}, zero, &weights);
  if (zero) return {};
  return t;
}

vec3 evaluate_brdf(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                   const highlight_footprint& footprint) {
  return evaluate_brdf(brdf_view_of(mp, n, v), mp, n, v, l, footprint);
}

brdf_lobes evaluate_brdf_lobes(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                               const highlight_footprint& footprint) {
  return evaluate_brdf_lobes(brdf_view_of(mp, n, v), mp, n, v, l, footprint);
}

brdf_lobes evaluate_brdf_lobes(const material_point& mp, const vec3& n, const vec3& v, const vec3& l,
                               const glossy_weights& weights) {
  return evaluate_brdf_lobes(brdf_view_of(mp, n, v), mp, n, v, l, weights);
}

vec3 evaluate_diffuse_btdf(const material_point& mp, const vec3& n, const vec3& v, const vec3& l) {
  const material_layers& L = layers_of(mp);
  const float through = diffuse_see_through_weight(mp);
  const float n_dot_v = glm::dot(n, v), n_dot_l = glm::dot(n, l);
  if (!(through > 0.0f) || !(n_dot_v > 0.0f) || !(n_dot_l < 0.0f)) return vec3(0.0f);
  // No half vector joins the two sides; the base's Fresnel is taken at the view's angle.
  const vec3 fresnel = mp.specular_weight * dielectric_fresnel(mp, n_dot_v);
  vec3 f = L.diffuse_transmission_color * ((1.0f - max3(fresnel)) * through / pi);
  f *= sheen_scaling(mp, n_dot_v, -n_dot_l);
  return f * (1.0f - clearcoat_weight(mp, glm::dot(coat_normal_or(mp, n), v)));
}

vec3 denoising_albedo(const material_point& mp) {
  if (mp.unlit) return glm::clamp(mp.base_color, 0.0f, 1.0f);
  const float see_through = see_through_weight(mp);
  return glm::clamp(mp.base_color * (1.0f - see_through) + vec3(see_through), 0.0f, 1.0f);
}

}  // namespace kiln
