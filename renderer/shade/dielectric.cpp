#include "shade/dielectric.h"

#include <algorithm>
#include <cmath>

namespace kiln {

float fresnel_dielectric(float cos_i, float eta) {
  if (eta == 1.0f)
    return 0.0f;  // index-matched: no interface, exactly (not a rounding
                  // residue)
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = std::sqrt(1.0f - sin2_t);
  // Both amplitude ratios divided through by n_transmitted, so only eta
  // appears.
  float r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_s * r_s + r_p * r_p);
}

std::optional<vec3> refract_direction(const vec3& d, const vec3& n, float eta) {
  float cos_i = std::clamp(-glm::dot(d, n), 0.0f, 1.0f);
  float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return std::nullopt;
  float cos_t = std::sqrt(1.0f - sin2_t);
  // Tangential part scales by eta (Snell), normal part is -cos_t·n.
  return glm::normalize(eta * d + (eta * cos_i - cos_t) * n);
}

vec3 beer_transmittance(const vec3& attenuation_color, float attenuation_distance, float distance) {
  if (!(attenuation_distance < inf) || attenuation_distance <= 0.0f || distance <= 0.0f) return vec3(1.0f);
  vec3 result;
  for (int c = 0; c < 3; ++c)
    result[c] = attenuation_color[c] >= 1.0f
                    ? 1.0f
                    : std::pow(std::max(attenuation_color[c], 0.0f), distance / attenuation_distance);
  return result;
}

float material_ior(const material& m) { return m.ior >= 1.0f ? m.ior : 1.5f; }

bool medium_stack::contains(uint32_t m) const {
  for (int i = 0; i < size; ++i)
    if (materials[size_t(i)] == m) return true;
  return false;
}

medium_stack medium_stack::with(uint32_t m) const {
  medium_stack out = *this;
  if (out.size < capacity) out.materials[size_t(out.size++)] = m;
  return out;
}

medium_stack medium_stack::without(uint32_t m) const {
  medium_stack out = *this;
  for (int i = out.size - 1; i >= 0; --i) {
    if (out.materials[size_t(i)] != m) continue;
    for (int j = i; j + 1 < out.size; ++j) out.materials[size_t(j)] = out.materials[size_t(j + 1)];
    --out.size;
    break;
  }
  return out;
}

float medium_stack::ior(const scene& s) const {
  return empty() ? 1.0f : material_ior(s.materials[innermost()]);
}

}  // namespace kiln
