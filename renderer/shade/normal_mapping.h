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

}  // namespace kiln
