#include "shade/sheen_albedo.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "shade/material_lobes.h"

namespace kiln {

namespace {

// E(μ, r) on a grid of μ = cos θ in [0, 1] and r in [0, 1], integrated over the half vector: the
// lobe concentrates where h turns away from n, which a grid over h resolves at every roughness
// the lobe allows. l = reflect(−v, h), dω_l = 4 (v·h) dω_h.
constexpr int albedo_size = sheen_albedo_size;

constexpr float stored_table[albedo_size * albedo_size] = {
#include "shade/sheen_albedo_table.inc"
};

float integrate_sheen_albedo(float cos_v, float roughness) {
  constexpr int theta_steps = 96, phi_steps = 48;  // φ over [0, π], doubled by symmetry
  const float sin_v = std::sqrt(std::max(1.0f - cos_v * cos_v, 0.0f));
  const vec3 v(sin_v, 0.0f, cos_v);
  double sum = 0.0;
  for (int i = 0; i < theta_steps; ++i) {
    const float theta = (i + 0.5f) * (0.5f * pi) / theta_steps;
    const float st = std::sin(theta), ct = std::cos(theta);
    for (int j = 0; j < phi_steps; ++j) {
      const float phi = (j + 0.5f) * pi / phi_steps;
      const vec3 h(st * std::cos(phi), st * std::sin(phi), ct);
      const float v_dot_h = glm::dot(v, h);
      if (v_dot_h <= 0.0f) continue;
      const float n_dot_l = 2.0f * v_dot_h * h.z - v.z;
      if (n_dot_l <= 0.0f) continue;
      const float f = charlie_distribution(roughness, ct) * charlie_visibility(roughness, cos_v, n_dot_l);
      sum += double(f * n_dot_l * 4.0f * v_dot_h * st);
    }
  }
  return float(sum * 2.0 * (0.5 * pi / theta_steps) * (pi / phi_steps));
}

}  // namespace

float sheen_directional_albedo(float cos_theta, float sheen_roughness) {
  const float x = std::sqrt(std::clamp(cos_theta, 0.0f, 1.0f)) * (albedo_size - 1);
  const float y = std::clamp(sheen_roughness, 0.0f, 1.0f) * (albedo_size - 1);
  const int x0 = std::min(int(x), albedo_size - 2), y0 = std::min(int(y), albedo_size - 2);
  const float fx = x - float(x0), fy = y - float(y0);
  const auto at = [&](int r, int m) { return stored_table[r * albedo_size + m]; };
  const float low = at(y0, x0) + (at(y0, x0 + 1) - at(y0, x0)) * fx;
  const float high = at(y0 + 1, x0) + (at(y0 + 1, x0 + 1) - at(y0 + 1, x0)) * fx;
  return low + (high - low) * fy;
}

float stored_sheen_albedo(int r, int m) { return stored_table[r * albedo_size + m]; }

float integrate_sheen_albedo_entry(int r, int m) {
  const float x = float(m) / (albedo_size - 1);
  return integrate_sheen_albedo(std::max(x * x, 1e-3f), float(r) / (albedo_size - 1));
}

}  // namespace kiln
