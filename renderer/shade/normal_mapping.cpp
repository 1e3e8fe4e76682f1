#include "shade/normal_mapping.h"

#include <cmath>

namespace kiln {

bool reads_normal_map(const material& m, const surface_point& sp) {
  return m.normal_texture.present() && sp.tangent != vec4(0.0f);
}

void apply_normal_map(const scene& s, const material& m, const material_inputs& in, surface_point& sp) {
  if (!reads_normal_map(m, sp)) return;
  apply_normal_map(m, sample_texture_ref(s, m.normal_texture, in, texel_encoding::linear), sp);
}

bool reads_clearcoat_normal_map(const material& m, const surface_point& sp) {
  return m.clearcoat_factor > 0.0f && m.clearcoat_normal_texture.present() && sp.tangent != vec4(0.0f);
}

void apply_normal_map(const material& m, const vec4& normal_texel, surface_point& sp) {
  apply_normal_map(m.normal_texture, normal_texel, sp);
}

void apply_normal_map(const texture_ref& normal_texture, const vec4& normal_texel, surface_point& sp) {
  // Work with glTF's front-side normal; make_surface_point flipped it toward back-face rays.
  const vec3 n = sp.front_face ? sp.shading_normal : -sp.shading_normal;
  vec3 t = vec3(sp.tangent);
  t -= n * glm::dot(n, t);
  const float t_length = glm::length(t);
  if (!(t_length > 0.0f) || !std::isfinite(t_length)) return;
  t /= t_length;
  const vec3 b = glm::cross(n, t) * sp.tangent.w;
  vec3 c = vec3(normal_texel) * 2.0f - 1.0f;
  c.x *= normal_texture.scale;  // glTF: scale applies to X and Y only
  c.y *= normal_texture.scale;
  vec3 mapped = t * c.x + b * c.y + n * c.z;
  const float length = glm::length(mapped);
  if (!(length > 0.0f) || !std::isfinite(length)) return;
  mapped /= length;
  if (!sp.front_face) mapped = -mapped;
  // Same rule as make_surface_point: never point into the surface the geometric normal defines.
  const vec3& ng = sp.geometric_normal;
  if (glm::dot(mapped, ng) < 0.0f) mapped = glm::normalize(mapped - 2.0f * glm::dot(mapped, ng) * ng);
  sp.shading_normal = mapped;
}

}  // namespace kiln
