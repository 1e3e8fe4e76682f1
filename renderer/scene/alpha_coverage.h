// glTF alpha rules as plain functions of (scene, instance, triangle, barycentrics), so that every
// accelerator applies them identically: the Embree backend calls alpha_masked_out() from its
// intersection and occlusion filter functions, the grid backend calls it in its triangle loop.
// Depends on scene only; never on a backend or on shading.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace kiln {

// Coverage at a triangle hit: base colour factor alpha times base colour texture alpha (the
// texture read with the material's texCoord set). 1 for materials without alpha information.
float alpha_at(const scene& s, uint32_t instance_id, uint32_t primitive_id, float u, float v);

// True when a hit on an alphaMode MASK material falls where alpha < alphaCutoff: the surface is
// not there at all (no hit, no shadow). Always false for OPAQUE and BLEND materials.
bool alpha_masked_out(const scene& s, uint32_t instance_id, uint32_t primitive_id, float u, float v);

// Per mesh: whether some instance of it uses an alphaMode MASK material (only those meshes need a
// filter; one pass over the instances).
std::vector<bool> meshes_needing_alpha_filter(const scene& s);

}  // namespace kiln
