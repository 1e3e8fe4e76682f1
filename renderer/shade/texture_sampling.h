// Texture lookups for shading: glTF samplers (wrap modes, nearest or bilinear), sRGB decoding for
// colour textures. Depends on scene only; images were decoded by the loader.
#pragma once

#include "scene/scene.h"

namespace kiln {

// How a texture's texels are to be read.
enum class texel_encoding { linear, srgb };

// Filtered RGBA at uv (glTF convention: (0,0) is the top-left corner of the image).
// sRGB decoding applies to RGB, never to alpha, and happens before filtering.
vec4 sample_texture(const scene& s, const texture& tex, vec2 uv, texel_encoding encoding);

// Applies a texture reference's KHR_texture_transform to uv (identity by default).
vec2 transform_uv(const texture_ref& ref, vec2 uv);

// Maps an integer texel coordinate into [0, size) by a glTF wrap mode.
int wrap_texel(int i, int size, wrap_mode mode);

// IEC 61966-2-1 sRGB transfer function, decoded to linear.
float srgb_to_linear(float c);

}  // namespace kiln
