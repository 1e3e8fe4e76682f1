// What rays that leave the scene see: the constant environment colour, or an equirectangular map
// (scaled by its intensity, turned about +Y by its rotation). Depends on scene and texture
// sampling only.
#pragma once

#include "scene/scene.h"

namespace kiln {

// Equirectangular coordinates of a world direction (glTF's +Y up): v = 0 straight up, v = 1 straight
// down; u = 0.5 along -Z, 0.75 along +X, 0 and 1 along +Z. A positive rotation turns the map
// counter-clockwise seen from above (+Y).
vec2 environment_uv(const vec3& direction, float rotation_radians);

// Radiance arriving from direction (any length).
vec3 environment_radiance(const scene& s, const vec3& direction);

// The same at the map's equirectangular coordinates uv (environment_uv of the direction), for a
// caller that has them already (a direction drawn from the map); the constant colour without a map.
vec3 environment_radiance_at(const scene& s, const vec2& uv);

// Asks the cache for the map's texels environment_radiance_at(s, uv) will read (the texel at uv and
// its neighbours above and below), so that a shading point's directions, found first, wait on
// their reads together rather than one after another. Changes no result.
void prefetch_environment_radiance(const scene& s, const vec2& uv);

}  // namespace kiln
