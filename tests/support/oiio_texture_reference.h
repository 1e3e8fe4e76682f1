// The filtered lookups kiln's texture_filter is measured against: OpenImageIO's TextureSystem
// (trilinear-anisotropic, MipModeAniso) over the same in-memory linear float pyramids, each level
// the 2x2 box average of the level above. Tests only: the renderer does not link OpenImageIO's
// texture system.
#pragma once

#include <memory>

#include "scene/scene.h"
#include "shade/texture_sampling.h"

namespace kiln::testing {

class oiio_texture_reference {
 public:
  explicit oiio_texture_reference(const scene& s, float cache_mb = 256.0f);
  ~oiio_texture_reference();
  oiio_texture_reference(const oiio_texture_reference&) = delete;
  oiio_texture_reference& operator=(const oiio_texture_reference&) = delete;

  vec4 minified(uint32_t texture_index, texel_encoding encoding, vec2 uv,
                const uv_footprint& footprint) const;

 private:
  struct impl;
  std::unique_ptr<impl> impl_;
};

}  // namespace kiln::testing
