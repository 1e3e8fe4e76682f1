// Moves a loaded scene's colours from glTF's linear Rec.709 into a render's working space by one
// 3x3 matrix, once, before anything is rendered: factors, vertex colours, lights, the background
// and environment map, and the colour (sRGB-slot) textures. Data textures (normals,
// metallic-roughness, occlusion, transmission) are never converted. Depends on scene only.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace kiln {

// What of a scene to convert. A sequence's later frames (job/render_sequence) carry the last
// frame's materials, textures, images, environment map and undeformed meshes over, converted
// already; each pose builds its lights, the background colour and the deformed meshes again.
struct colour_conversion_scope {
  bool carried_over = false;                            // convert only what the pose built again
  const std::vector<uint32_t>* posed_meshes = nullptr;  // with carried_over: the meshes it built
  // A pose keeps only the loader's own images, so in a sequence an image read both as colour and as
  // data cannot be split into a converted copy: false refuses such a scene (kiln::error, input).
  bool allow_image_copies = true;
};

// rgb_working = working_from_rec709 · rgb_rec709 (GLM's column-vector convention).
// A colour texture's image is converted texel by texel after its sRGB decode and stored as float,
// sRGB-encoded again (the exact inverse of texture_eval's srgb_to_linear, extended to negative
// values and values above 1) so that every slot still reads it through its sRGB decode and mip
// levels average the converted linear values. An image that a data slot or the environment also
// reads is copied first, so the data use keeps the file's texels. Returns the bytes the scene's
// images grew by (8-bit colour textures become float: 16 bytes a texel instead of 4).
uint64_t convert_scene_colours(scene& s, const mat3& working_from_rec709,
                               const colour_conversion_scope& scope = {});

// The sRGB encoding srgb_to_linear inverts: 12.92·v up to 0.0031308 (negative values included),
// 1.055·v^(1/2.4) − 0.055 above.
float linear_to_srgb(float v);

}  // namespace kiln
