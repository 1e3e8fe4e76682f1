// Per-vertex tangent frames for normal mapping, generated from positions, normals and one UV set
// when a file supplies no TANGENT (used by the glTF loader). Depends on scene (mesh data) only.
//
// Not a full MikkTSpace implementation: each triangle's UV derivative dP/du (and dP/dv for the
// handedness) is accumulated, area-weighted, at its vertices, then made orthogonal to the vertex
// normal (Gram-Schmidt). It follows MikkTSpace's conventions (tangent = +u, bitangent =
// cross(normal, tangent) · w pointing to +v of an upward-v texture, i.e. to decreasing glTF v),
// so it agrees with MikkTSpace on smooth, consistently mapped surfaces and differs at UV seams.
#pragma once

#include <vector>

#include "scene/scene.h"

namespace kiln {

// One tangent per vertex: xyz unit, w = ±1 handedness. uv has one entry per vertex. Vertices no
// triangle gives a usable UV derivative get a tangent perpendicular to their normal. A mesh
// without normals (flat shading) uses the mean face normal around each vertex instead.
std::vector<vec4> generate_tangents(const mesh& m, const std::vector<vec2>& uv);

}  // namespace kiln
