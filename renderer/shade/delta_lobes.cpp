#include "shade/delta_lobes.h"

#include <algorithm>

#include "shade/material_lobes.h"

namespace kiln {

namespace {

// Weight of the perfect-mirror term for the opaque part of a surface: the BRDF's Fresnel at the
// view (linear in F0, so metal and dielectric mix; iridescent where the material is), faded out
// with roughness, seen through the sheen and the coat (by the caller). The transmissive part
// reflects by exact Fresnel instead (add_refraction); the coat's own mirror is coat_mirror_weight.
vec3 mirror_weight(float roughness_limit, const material_point& mp, float cos_theta) {
  if (mp.roughness >= roughness_limit) return vec3(0.0f);
  float fade = 1.0f - mp.roughness / roughness_limit;
  vec3 metal = metal_fresnel(mp, cos_theta) * mp.metallic;
  vec3 dielectric = mp.specular_weight * dielectric_fresnel(mp, cos_theta) *
                    ((1.0f - mp.metallic) * (1.0f - mp.transmission));
  return (metal + dielectric) * fade;
}

// The clearcoat's mirror: its Fresnel weight, faded out with the coat's roughness like the base's.
float coat_mirror_weight(float roughness_limit, const material_point& mp, float coat_cos_theta) {
  const material_layers& L = layers_of(mp);
  if (!(L.clearcoat > 0.0f) || L.clearcoat_roughness >= roughness_limit) return 0.0f;
  return clearcoat_weight(mp, coat_cos_theta) * (1.0f - L.clearcoat_roughness / roughness_limit);
}

// The refraction event at a transmissive surface: the ior pair, the media on the far side, and
// whether the ray bends (a thin-walled surface has no volume: rays pass straight through).
struct interface_crossing {
  float eta = 1.0f;  // n_incident / n_transmitted
  medium_stack beyond;
  bool bends = true;
};

// Entering or leaving is decided by the geometric normal's side (sp.front_face), never by the
// shading normal. A back-face hit on a volume not in the stack (a camera inside glass, an open mesh)
// still counts as leaving that material.
interface_crossing cross_interface(const scene& s, const surface_point& sp, const medium_stack& media,
                                   int channel) {
  interface_crossing c;
  const material& m = s.materials[sp.material];
  // A ray of one colour channel refracts by that channel's ior (KHR_materials_dispersion); the
  // media around the surface keep their single ior.
  const float ior = channel >= 0 ? dispersed_ior(material_ior(m), m.dispersion)[channel] : material_ior(m);
  if (!m.has_volume()) {
    c.eta = media.ior(s) / ior;
    c.beyond = media;
    c.bends = false;
    return c;
  }
  if (sp.front_face) {
    c.eta = media.ior(s) / ior;
    c.beyond = media.with(sp.material);
  } else {
    c.beyond = media.without(sp.material);
    c.eta = ior / c.beyond.ior(s);
  }
  return c;
}

// The direction a refracted ray leaves in (empty: total internal reflection). Thin walls pass light
// on unbent; volumes bend it by Snell's law about the shading normal, falling back to the geometric
// normal when that would not cross the surface.
std::optional<vec3> refraction_direction(const surface_point& sp, const vec3& incident,
                                         const interface_crossing& crossing) {
  if (!crossing.bends) return incident;
  std::optional<vec3> direction = refract_direction(incident, sp.shading_normal, crossing.eta);
  if (direction && glm::dot(*direction, sp.geometric_normal) >= 0.0f)
    direction = refract_direction(incident, sp.geometric_normal, crossing.eta);
  return direction;
}

// The refracted part of a transmissive surface for one crossing (channel -1: all three colours,
// else that channel alone): exact Fresnel splits it into the refraction listed in out and a
// reflected part added to reflect_weight (all of it under total internal reflection). layers: the
// share seen through the sheen and the coat.
void add_refraction(const scene& s, const surface_point& sp, const material_point& mp, const vec3& incident,
                    float cos_theta, float layers, const medium_stack& media, int channel,
                    vec3& reflect_weight, delta_lobes& out) {
  const float see_through = see_through_weight(mp) * layers;
  const vec3 mask = channel < 0 ? vec3(1.0f) : vec3(channel == 0, channel == 1, channel == 2);
  const interface_crossing crossing = cross_interface(s, sp, media, channel);
  const float fresnel = fresnel_dielectric(cos_theta, crossing.eta);
  reflect_weight += mask * (see_through * mp.specular_weight * fresnel);
  const std::optional<vec3> direction = refraction_direction(sp, incident, crossing);
  if (!direction) {
    reflect_weight += mask * (see_through * (1.0f - mp.specular_weight * fresnel));
    return;
  }
  delta_lobe& lobe = out.lobes[out.count++];
  lobe.kind = delta_kind::refraction;
  lobe.direction = *direction;
  lobe.weight = mask * mp.base_color * (see_through * (1.0f - fresnel));
  lobe.channel = channel;
  lobe.media = crossing.beyond;
  lobe.eta = crossing.eta;
  lobe.bends = crossing.bends;
}

// The mirror about normal, in the medium the ray came from. An interpolated normal can send it
// below the surface; the true plane reflects it then.
void add_mirror(const surface_point& sp, const vec3& normal, const vec3& incident, const vec3& weight,
                delta_kind kind, const medium_stack& media, int channel, delta_lobes& out) {
  vec3 direction = glm::reflect(incident, normal);
  if (glm::dot(direction, sp.geometric_normal) <= 0.0f)
    direction = glm::reflect(incident, sp.geometric_normal);
  delta_lobe& lobe = out.lobes[out.count++];
  lobe.kind = kind;
  lobe.direction = glm::normalize(direction);
  lobe.weight = weight;
  lobe.channel = channel;
  lobe.media = media;
}

}  // namespace

float through_layers(const material_point& mp, float cos_theta, float coat_cos_theta) {
  if (!mp.layers) return 1.0f;
  const material_layers& L = *mp.layers;
  float share = 1.0f - clearcoat_weight(mp, coat_cos_theta);
  if (L.sheen_color != vec3(0.0f))
    share *= std::max(1.0f - std::max({L.sheen_color.x, L.sheen_color.y, L.sheen_color.z}) *
                                 sheen_directional_albedo(cos_theta, L.sheen_roughness),
                      0.0f);
  return share;
}

delta_lobes delta_lobes_at(const scene& s, float mirror_roughness_limit, const surface_point& sp,
                           const material_point& mp, const vec3& incident, const medium_stack& media,
                           int channel) {
  delta_lobes out;
  const vec3 to_viewer = -incident;
  const float cos_theta = std::max(glm::dot(sp.shading_normal, to_viewer), 0.0f);
  const vec3 coat_normal = coat_normal_or(mp, sp.shading_normal);
  const float coat_cos_theta = std::max(glm::dot(coat_normal, to_viewer), 0.0f);
  const float layers = through_layers(mp, cos_theta, coat_cos_theta);
  vec3 reflect_weight = mirror_weight(mirror_roughness_limit, mp, cos_theta) * layers;
  // The transmissive share: a smooth dielectric whatever its roughness (Whitted has no blurred
  // refraction). A dispersive volume entered by a ray of all colours splits it into one refracted
  // ray per channel, each bent by its own ior.
  if (see_through_weight(mp) > 0.0f) {
    const material& m = s.materials[sp.material];
    if (channel >= 0 || !(m.dispersion > 0.0f) || !m.has_volume())
      add_refraction(s, sp, mp, incident, cos_theta, layers, media, channel, reflect_weight, out);
    else
      for (int c = 0; c < 3; ++c)
        add_refraction(s, sp, mp, incident, cos_theta, layers, media, c, reflect_weight, out);
  }
  // The coat's mirror joins the base's when both reflect about the same normal.
  const float coat_mirror = coat_mirror_weight(mirror_roughness_limit, mp, coat_cos_theta);
  const bool separate_coat = coat_mirror > 0.0f && coat_normal != sp.shading_normal;
  if (!separate_coat) reflect_weight += vec3(coat_mirror);
  add_mirror(sp, sp.shading_normal, incident, reflect_weight, delta_kind::mirror, media, channel, out);
  if (separate_coat)
    add_mirror(sp, coat_normal, incident, vec3(coat_mirror), delta_kind::coat_mirror, media, channel, out);
  return out;
}

}  // namespace kiln
