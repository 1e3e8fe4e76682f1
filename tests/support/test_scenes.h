// Small scenes built directly as kiln::scene data (no glTF file) for shading tests: boxes and quads
// placed by identity instances, and unit rays. Header-only; depends on scene only.
#pragma once

#include "core/ray.h"
#include "scene/scene.h"

namespace kiln::testing {

// Adds a mesh and one identity instance of it with the given material.
inline void add_mesh_instance(scene& s, mesh m, uint32_t material) {
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  s.meshes.push_back(std::move(m));
  instance inst;
  inst.shape = uint32_t(s.meshes.size() - 1);
  inst.material = material;
  finish_instance_transform(inst);
  s.instances.push_back(inst);
}

// An axis-aligned box with outward-facing counter-clockwise triangles (a closed volume).
inline void add_box(scene& s, const vec3& lo, const vec3& hi, uint32_t material) {
  mesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  // Faces as quads (a, b, c, d), counter-clockwise seen from outside.
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  add_mesh_instance(s, std::move(m), material);
}

// A quad [x0, x1] × [y0, y1] at height z facing +z, with UVs (0,0) at (x0, y1) and (1,1) at (x1, y0)
// (glTF's top-left UV origin seen from above).
inline void add_quad(scene& s, float x0, float y0, float x1, float y1, float z, uint32_t material) {
  mesh m;
  m.positions = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  m.texcoords0 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  add_mesh_instance(s, std::move(m), material);
}

// A material that only emits: black base, no specular, the given radiance.
inline material emitter(float radiance) {
  material m;
  m.base_color_factor = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  m.metallic_factor = 0.0f;
  m.specular_factor = 0.0f;
  m.emissive_factor = vec3(radiance);
  return m;
}

inline ray make_ray(const vec3& origin, const vec3& direction) {
  ray r;
  r.origin = origin;
  r.direction = glm::normalize(direction);
  return r;
}

}  // namespace kiln::testing
