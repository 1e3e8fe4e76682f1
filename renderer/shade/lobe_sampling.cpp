#include "shade/lobe_sampling.h"

#include <cmath>

namespace kiln {

namespace {

// An orthonormal frame (t, b, n) about the unit n (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited").
struct frame {
  vec3 t, b, n;
};
frame frame_about(const vec3& n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  return {vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), vec3(b, sign + n.y * n.y * a, -n.y), n};
}
vec3 to_local(const frame& f, const vec3& d) {
  return {glm::dot(d, f.t), glm::dot(d, f.b), glm::dot(d, f.n)};
}
vec3 to_world(const frame& f, const vec3& d) { return d.x * f.t + d.y * f.b + d.z * f.n; }

// A cosine-weighted direction about +z (Malley's method).
vec3 cosine_direction(const vec2& u) {
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * pi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0f - u.x, 0.0f))};
}

float ggx_alpha(float roughness) { return std::max(roughness * roughness, 1e-3f); }

// The reflection of v about the GGX normal drawn for it about n; empty below the surface.
std::optional<vec3> sample_ggx(const vec3& n, float alpha, const vec3& v, const vec2& u) {
  const frame f = frame_about(n);
  const vec3 v_local = to_local(f, v);
  if (!(v_local.z > 0.0f)) return std::nullopt;
  const vec3 h = to_world(f, sample_ggx_visible_normal(v_local, alpha, u));
  const vec3 l = glm::reflect(-v, h);
  if (!(glm::dot(l, n) > 0.0f)) return std::nullopt;
  return glm::normalize(l);
}

// The density of l under sample_ggx about n.
float ggx_pdf(const vec3& n, float alpha, const vec3& v, const vec3& l) {
  const float n_dot_v = glm::dot(n, v), n_dot_l = glm::dot(n, l);
  if (!(n_dot_v > 0.0f && n_dot_l > 0.0f)) return 0.0f;
  const vec3 h = glm::normalize(v + l);
  return ggx_reflection_pdf(alpha, n_dot_v, glm::dot(n, h));
}

float max3(const vec3& c) { return std::max({c.x, c.y, c.z}); }

}  // namespace

vec3 sample_ggx_visible_normal(const vec3& v_local, float alpha, const vec2& u) {
  // The view in the hemisphere configuration, where visible normals are a disk's projection.
  const vec3 vh = glm::normalize(vec3(alpha * v_local.x, alpha * v_local.y, v_local.z));
  const float length2 = vh.x * vh.x + vh.y * vh.y;
  const vec3 t1 = length2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / std::sqrt(length2) : vec3(1.0f, 0.0f, 0.0f);
  const vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * pi * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(1.0f - p1 * p1, 0.0f)) + s * r * std::sin(phi);
  const vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(1.0f - p1 * p1 - p2 * p2, 0.0f)) * vh;
  return glm::normalize(vec3(alpha * nh.x, alpha * nh.y, std::max(nh.z, 0.0f)));
}

float ggx_reflection_pdf(float alpha, float n_dot_v, float n_dot_h) {
  // G1(v) · D(h) · (v·h) / (n·v) visible normals, times 1 / (4 v·h) for the reflection: the v·h cancel.
  const float a2 = alpha * alpha;
  const float d_denominator = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  const float d = a2 / (pi * d_denominator * d_denominator);
  return d / (2.0f * (n_dot_v + std::sqrt(a2 + (1.0f - a2) * n_dot_v * n_dot_v)));
}

lobe_sampler make_lobe_sampler(const material_point& mp, const vec3& n, const vec3& v,
                               const glossy_weights& weights) {
  lobe_sampler s;
  const material_layers& L = layers_of(mp);
  s.normal = n;
  s.coat_normal = coat_normal_or(mp, n);
  s.alpha = ggx_alpha(mp.roughness);
  if (L.anisotropy > 0.0f)
    s.alpha = std::sqrt(s.alpha * glm::mix(s.alpha, 1.0f, L.anisotropy * L.anisotropy));
  s.coat_alpha = ggx_alpha(L.clearcoat_roughness);
  const float n_dot_v = std::max(glm::dot(n, v), 0.0f);
  // Each lobe's estimated albedo at this view: what it reflects at most.
  const float dielectric = (1.0f - mp.metallic) * mp.specular_weight;
  const float base_specular =
      dielectric * weights.dielectric * max3(fresnel_schlick(mp.dielectric_f0, n_dot_v)) +
      mp.metallic * weights.metal * max3(fresnel_schlick(mp.base_color, n_dot_v));
  const float coat = clearcoat_weight(mp, glm::dot(s.coat_normal, v)) * weights.coat;
  const float diffuse = (1.0f - mp.metallic) * (1.0f - mp.transmission) * (1.0f - L.diffuse_transmission) *
                            max3(mp.base_color) +
                        max3(L.sheen_color);
  const float back = diffuse_see_through_weight(mp) * max3(L.diffuse_transmission_color);
  const float total = diffuse + base_specular + coat + back;
  if (!(total > 0.0f) || !std::isfinite(total)) return s;
  s.diffuse = diffuse / total;
  s.specular = base_specular / total;
  s.coat = coat / total;
  s.back = back / total;
  return s;
}

std::optional<vec3> sample_lobes(const lobe_sampler& s, const vec3& v, const vec3& u) {
  float pick = u.x;
  const vec2 uv(u.y, u.z);
  if (pick < s.diffuse) return to_world(frame_about(s.normal), cosine_direction(uv));
  pick -= s.diffuse;
  if (pick < s.specular) return sample_ggx(s.normal, s.alpha, v, uv);
  pick -= s.specular;
  if (pick < s.coat) return sample_ggx(s.coat_normal, s.coat_alpha, v, uv);
  pick -= s.coat;
  if (pick < s.back) return to_world(frame_about(-s.normal), cosine_direction(uv));
  return std::nullopt;
}

float lobe_pdf(const lobe_sampler& s, const vec3& v, const vec3& l) {
  const float n_dot_l = glm::dot(s.normal, l);
  float pdf = 0.0f;
  if (s.diffuse > 0.0f && n_dot_l > 0.0f) pdf += s.diffuse * n_dot_l / pi;
  if (s.back > 0.0f && n_dot_l < 0.0f) pdf += s.back * -n_dot_l / pi;
  if (s.specular > 0.0f) pdf += s.specular * ggx_pdf(s.normal, s.alpha, v, l);
  if (s.coat > 0.0f) pdf += s.coat * ggx_pdf(s.coat_normal, s.coat_alpha, v, l);
  return pdf;
}

}  // namespace kiln
