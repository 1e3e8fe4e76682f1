// Tangent-space normal mapping (glTF normalTexture): perturbs a shading point's shading normal by
// the texture, in the frame (tangent, cross(normal, tangent)·w, normal). Depends on scene and
// material evaluation only.
#pragma once

#include "scene/scene.h"
#include "shade/material_eval.h"
#include "shade/surface.h"

namespace kiln {

// Replaces sp.shading_normal with the mapped normal when the material has a normal texture and the
// mesh a tangent frame; the result stays on the incoming ray's side of the geometric surface.
void apply_normal_map(const scene& s, const material& m, const material_inputs& in, surface_point& sp);

// Whether apply_normal_map reads m's normal texture at sp (m has one and sp a tangent frame).
bool reads_normal_map(const material& m, const surface_point& sp);

// apply_normal_map with the normal texture's texel at sp already read (by
// sample_material_textures); sp must be a point where reads_normal_map holds.
void apply_normal_map(const material& m, const vec4& normal_texel, surface_point& sp);

// The same for any normal texture (the clearcoat's: KHR_materials_clearcoat) and its texel.
void apply_normal_map(const texture_ref& normal_texture, const vec4& normal_texel, surface_point& sp);

// Whether shading at sp reads m's clearcoat normal map (a coat, the texture and a tangent frame).
bool reads_clearcoat_normal_map(const material& m, const surface_point& sp);

}  // namespace kiln
