#include "shade/texture_sampling.h"

#include <algorithm>
#include <cmath>

#include "shade/texture_filter.h"

namespace kiln {

vec4 sample_texture(const scene& s, const texture_filter* filter, uint32_t texture_index, vec2 uv,
                    const uv_footprint& footprint, texel_encoding encoding) {
  const texture& tex = s.textures[texture_index];
  const image& img = s.images[tex.image];
  if (!sampleable(img, uv)) return vec4(1.0f);
  // OpenGL's rule: the scale factor ρ is the footprint's longest axis in texels; ρ ≤ 1 magnifies.
  const vec2 texels(img.width, img.height);
  const float rho = std::max(glm::length(footprint.dx * texels), glm::length(footprint.dy * texels));
  if (!(rho > 1.0f) || !std::isfinite(rho))
    return sample_level0(img, tex.sampling, tex.sampling.filter, uv, encoding);
  if (tex.sampling.mipmap == mip_mode::none || !filter)
    return sample_level0(img, tex.sampling, tex.sampling.min_filter, uv, encoding);
  return filter->minified(texture_index, encoding, uv, footprint);
}

}  // namespace kiln
