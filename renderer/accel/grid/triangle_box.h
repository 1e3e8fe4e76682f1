// Triangle / axis-aligned box overlap by the separating axis theorem (Akenine-Möller, "Fast 3D
// Triangle-Box Overlap Testing", 2001): the box's three face normals, the triangle's normal and
// the nine edge cross products. Used when inserting triangles into grid cells, so a triangle lands
// only in the cells it touches rather than every cell its bounds cover. Depends on core only.
#pragma once

#include "core/math.h"

namespace kiln {

// True when the triangle (p0, p1, p2) and the closed box b share a point. Computed in double;
// touching counts as overlap, so callers that pad the box get a conservative answer.
bool triangle_box_overlap(const dvec3& p0, const dvec3& p1, const dvec3& p2, const bounds3& b);

}  // namespace kiln
