// Moves a loaded scene's colours from glTF's linear Rec.709 into a render's working space by one
// 3x3 matrix, once, before anything is rendered: factors, vertex colours, lights, the background
// and environment map, and the colour (sRGB-slot) textures. Data textures (normals,
// metallic-roughness, occlusion, transmission) are never converted. Depends on scene only.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace kiln {

// rgb_working = working_from_rec709 · rgb_rec709 (GLM's column-vector convention).
// A colour texture's image is converted texel by texel after its sRGB decode and stored as float,
// sRGB-encoded again (the exact inverse of texture_eval's srgb_to_linear, extended to negative
// values and values above 1) so that every slot still reads it through its sRGB decode and mip
// levels average the converted linear values. An image that a data slot or the environment also
// reads is copied first, so the data use keeps the file's texels. Returns the bytes the scene's
// images grew by (8-bit colour textures become float: 16 bytes a texel instead of 4).
uint64_t convert_scene_colours(scene& s, const mat3& working_from_rec709);

// The sRGB encoding srgb_to_linear inverts: 12.92·v up to 0.0031308 (negative values included),
// 1.055·v^(1/2.4) − 0.055 above.
float linear_to_srgb(float v);

}  // namespace kiln
