#include "scene/alpha_coverage.h"

#include "scene/texture_eval.h"

namespace kiln {

float alpha_at(const scene& s, uint32_t instance_id, uint32_t primitive_id, float u, float v) {
  const instance& inst = s.instances[instance_id];
  const material& m = s.materials[inst.material];
  float alpha = m.base_color_factor.a;
  const mesh& shape = s.meshes[inst.shape];
  const uint32_t* idx = &shape.indices[size_t(primitive_id) * 3];
  if (!shape.colors0.empty())
    alpha *= interpolate(shape.colors0[idx[0]].a, shape.colors0[idx[1]].a, shape.colors0[idx[2]].a, u, v);
  const texture_ref& ref = m.base_color_texture;
  const std::vector<vec2>& set =
      ref.texcoord == 1 && !shape.texcoords1.empty() ? shape.texcoords1 : shape.texcoords0;
  if (ref.present() && !set.empty()) {
    vec2 uv = transform_uv(ref, interpolate(set[idx[0]], set[idx[1]], set[idx[2]], u, v));
    alpha *= sample_texture(s, s.textures[size_t(ref.texture)], uv, texel_encoding::linear).a;
  }
  return alpha;
}

bool alpha_masked_out(const scene& s, uint32_t instance_id, uint32_t primitive_id, float u, float v) {
  const material& m = s.materials[s.instances[instance_id].material];
  if (m.alpha != alpha_mode::mask) return false;
  return alpha_at(s, instance_id, primitive_id, u, v) < m.alpha_cutoff;
}

std::vector<bool> meshes_needing_alpha_filter(const scene& s) {
  std::vector<bool> needed(s.meshes.size(), false);
  for (const instance& inst : s.instances)
    if (inst.kind == shape_kind::mesh && s.materials[inst.material].alpha == alpha_mode::mask)
      needed[inst.shape] = true;
  return needed;
}

}  // namespace kiln
