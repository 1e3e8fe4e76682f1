// Generated scenes for accelerator tests and benchmarks: closed tessellated spheres of any size,
// triangle soups, and many transformed instances of one mesh. Not part of the renderer proper.
// Depends on scene only.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace kiln {

// A closed UV sphere with 2·segments·(rings-1) triangles (the pole rows are fans).
mesh make_sphere_mesh(int rings, int segments, float radius);

// count random triangles with vertices uniform in [-extent, extent]³ around random centres,
// edge lengths up to `size`: overlapping, intersecting, unevenly spread.
mesh make_triangle_soup(uint32_t count, uint32_t seed, float extent, float size);

// A scene with one identity instance of m and one default material.
scene scene_from_mesh(mesh m);

// n³ instances of m on a lattice, each rotated, scaled (some mirrored) differently: one mesh,
// many placements.
scene make_instanced_scene(mesh m, int n, uint32_t seed);

}  // namespace kiln
