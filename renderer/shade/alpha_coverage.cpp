#include "shade/alpha_coverage.h"

#include "shade/surface.h"
#include "shade/texture_sampling.h"

namespace kiln {

float alpha_at(const scene& s, uint32_t instance_id, uint32_t primitive_id, float u, float v) {
  const instance& inst = s.instances[instance_id];
  const material& m = s.materials[inst.material];
  float alpha = m.base_color_factor.a;
  const mesh& shape = s.meshes[inst.shape];
  if (m.base_color_texture.present() && !shape.texcoords0.empty()) {
    const uint32_t* idx = &shape.indices[size_t(primitive_id) * 3];
    vec2 uv = interpolate(shape.texcoords0[idx[0]], shape.texcoords0[idx[1]], shape.texcoords0[idx[2]], u, v);
    alpha *=
        sample_texture(s, s.textures[size_t(m.base_color_texture.texture)], uv, texel_encoding::linear).a;
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
