#include "shade/material_lobes.h"

#include <algorithm>
#include <cmath>

namespace kiln {

namespace {

// Sheen roughness below this makes the Charlie lobe a grazing spike narrower than the albedo
// table (and float) resolves; both the lobe and the table clamp to it.
constexpr float min_sheen_roughness = 0.07f;

float sheen_alpha(float sheen_roughness) {
  const float r = std::clamp(sheen_roughness, min_sheen_roughness, 1.0f);
  return r * r;
}

// The exponent fit of the Charlie visibility's Λ (the specification's l(x, α)).
float charlie_l(float x, float alpha) {
  const float t = (1.0f - alpha) * (1.0f - alpha);
  const float a = 21.5473f + (25.3245f - 21.5473f) * t;
  const float b = 3.82987f + (3.32435f - 3.82987f) * t;
  const float c = 0.19823f + (0.16801f - 0.19823f) * t;
  const float d = -1.97760f + (-1.27393f + 1.97760f) * t;
  const float e = -4.32054f + (-4.85967f + 4.32054f) * t;
  return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

float charlie_lambda(float cos_theta, float alpha) {
  const float c = std::abs(cos_theta);
  return c < 0.5f ? std::exp(charlie_l(c, alpha))
                  : std::exp(2.0f * charlie_l(0.5f, alpha) - charlie_l(1.0f - c, alpha));
}

// The colour matching functions' Gaussian fit in Fourier space (the specification's
// evalSensitivity), as Rec.709 RGB.
vec3 film_sensitivity(float opd, const vec3& shift) {
  const float phase = 2.0f * pi * opd * 1.0e-9f;
  const vec3 val(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
  const vec3 pos(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
  const vec3 var(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
  vec3 xyz;
  for (int c = 0; c < 3; ++c)
    xyz[c] = val[c] * std::sqrt(2.0f * pi * var[c]) * std::cos(pos[c] * phase + shift[c]) *
             std::exp(-phase * phase * var[c]);
  xyz.x += 9.7470e-14f * std::sqrt(2.0f * pi * 4.5282e+09f) * std::cos(2.2399e+06f * phase + shift[0]) *
           std::exp(-4.5282e+09f * phase * phase);
  xyz /= 1.0685e-7f;
  return {3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
          -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
          0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z};
}

float schlick(float f0, float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (1.0f - f0) * (m2 * m2 * m);
}

float ior_to_f0(float transmitted, float incident) {
  const float r = (transmitted - incident) / (transmitted + incident);
  return r * r;
}

}  // namespace

float charlie_distribution(float sheen_roughness, float n_dot_h) {
  const float inv_alpha = 1.0f / sheen_alpha(sheen_roughness);
  const float sin2 = std::max(1.0f - n_dot_h * n_dot_h, 0.0f);
  return (2.0f + inv_alpha) * std::pow(sin2, 0.5f * inv_alpha) / (2.0f * pi);
}

float charlie_lambda_at(float sheen_roughness, float cos_theta) {
  return charlie_lambda(cos_theta, sheen_alpha(sheen_roughness));
}

float charlie_visibility_from(float sheen_roughness, float lambda_v, float n_dot_v, float n_dot_l) {
  const float alpha = sheen_alpha(sheen_roughness);
  const float denominator = (1.0f + lambda_v + charlie_lambda(n_dot_l, alpha)) * (4.0f * n_dot_v * n_dot_l);
  return denominator > 0.0f ? 1.0f / denominator : 0.0f;
}

float charlie_visibility(float sheen_roughness, float n_dot_v, float n_dot_l) {
  return charlie_visibility_from(sheen_roughness, charlie_lambda_at(sheen_roughness, n_dot_v), n_dot_v,
                                 n_dot_l);
}

vec3 iridescence_fresnel(float outside_ior, float film_ior, float cos_theta, float thickness_nm,
                         const vec3& base_f0) {
  // A film thinning to nothing fades into the medium above it, so thickness 0 is no film.
  const float t = std::clamp(thickness_nm / 0.03f, 0.0f, 1.0f);
  const float ior = outside_ior + (film_ior - outside_ior) * (t * t * (3.0f - 2.0f * t));
  const float ratio = outside_ior / ior;
  const float sin2_film = ratio * ratio * (1.0f - cos_theta * cos_theta);
  const float cos2_film = 1.0f - sin2_film;
  if (cos2_film < 0.0f) return vec3(1.0f);  // total internal reflection inside the film
  const float cos_film = std::sqrt(cos2_film);

  // First interface (outside to film) and second (film to base), by Schlick's approximation.
  const float r12 = schlick(ior_to_f0(ior, outside_ior), cos_theta);
  const float t121 = 1.0f - r12;
  const float phi12 = ior < outside_ior ? pi : 0.0f;
  const float phi21 = pi - phi12;
  vec3 r23, phi23;
  for (int c = 0; c < 3; ++c) {
    const float root = std::sqrt(std::clamp(base_f0[c], 0.0f, 0.9999f));
    const float base_ior = (1.0f + root) / (1.0f - root);
    r23[c] = schlick(ior_to_f0(base_ior, ior), cos_film);
    phi23[c] = base_ior < ior ? pi : 0.0f;
  }
  // The optical path difference inside the film, and the series of its inter-reflections.
  const float opd = 2.0f * ior * thickness_nm * cos_film;
  const vec3 phi = vec3(phi21) + phi23;
  const vec3 r123 = glm::clamp(r12 * r23, vec3(1e-5f), vec3(0.9999f));
  const vec3 sqrt_r123 = glm::sqrt(r123);
  const vec3 rs = (t121 * t121) * r23 / (vec3(1.0f) - r123);
  vec3 result = r12 + rs;
  vec3 cm = rs - t121;
  for (int m = 1; m <= 2; ++m) {
    cm *= sqrt_r123;
    result += cm * (2.0f * film_sensitivity(float(m) * opd, float(m) * phi));
  }
  return glm::max(result, vec3(0.0f));
}

float ggx_anisotropic_distribution(float n_dot_h, float t_dot_h, float b_dot_h, float at, float ab) {
  const float a2 = at * ab;
  const vec3 f(ab * t_dot_h, at * b_dot_h, a2 * n_dot_h);
  const float w2 = a2 / std::max(glm::dot(f, f), 1e-30f);
  return a2 * w2 * w2 / pi;
}

float ggx_anisotropic_visibility(float n_dot_l, float n_dot_v, float t_dot_v, float b_dot_v, float t_dot_l,
                                 float b_dot_l, float at, float ab) {
  const float ggx_v = n_dot_l * glm::length(vec3(at * t_dot_v, ab * b_dot_v, n_dot_v));
  const float ggx_l = n_dot_v * glm::length(vec3(at * t_dot_l, ab * b_dot_l, n_dot_l));
  return 0.5f / std::max(ggx_v + ggx_l, 1e-8f);
}

vec3 dispersed_ior(float ior, float dispersion) {
  if (!(dispersion > 0.0f) || ior <= 1.0f) return vec3(ior);
  const float abbe = 20.0f / dispersion;
  const vec3 lambda(656.3f, 587.6f, 486.1f);
  vec3 out;
  for (int c = 0; c < 3; ++c)
    out[c] = std::max(ior + (ior - 1.0f) / abbe * (523655.0f / (lambda[c] * lambda[c]) - 1.5168f), 1.0f);
  return out;
}

}  // namespace kiln
