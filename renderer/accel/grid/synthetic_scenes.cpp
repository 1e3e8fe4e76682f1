#include "accel/grid/synthetic_scenes.h"

#include <glm/gtc/matrix_transform.hpp>
#include <random>

namespace kiln {

namespace {

void finish_bounds(mesh& m) {
  m.bounds = bounds3{};
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
}

}  // namespace

mesh make_sphere_mesh(int rings, int segments, float radius) {
  mesh m;
  m.name = "sphere";
  // Vertex rows 1 .. rings-1 plus the two poles; every row shares the seam vertex of its start.
  m.positions.push_back({0.0f, radius, 0.0f});
  for (int r = 1; r < rings; ++r) {
    float theta = pi * float(r) / float(rings);
    for (int s = 0; s < segments; ++s) {
      float phi = 2.0f * pi * float(s) / float(segments);
      m.positions.push_back(
          radius * vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  }
  const uint32_t south = uint32_t(m.positions.size());
  m.positions.push_back({0.0f, -radius, 0.0f});
  auto at = [segments](int row, int s) { return uint32_t(1 + (row - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    // Counter-clockwise seen from outside.
    m.indices.insert(m.indices.end(), {0u, at(1, s + 1), at(1, s)});
    m.indices.insert(m.indices.end(), {south, at(rings - 1, s), at(rings - 1, s + 1)});
  }
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.indices.insert(m.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1)});
      m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s + 1), at(r + 1, s)});
    }
  finish_bounds(m);
  return m;
}

mesh make_triangle_soup(uint32_t count, uint32_t seed, float extent, float size) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> where(-extent, extent), offset(-size, size);
  mesh m;
  m.name = "soup";
  for (uint32_t i = 0; i < count; ++i) {
    vec3 c(where(rng), where(rng), where(rng));
    for (int k = 0; k < 3; ++k) {
      m.indices.push_back(uint32_t(m.positions.size()));
      m.positions.push_back(c + vec3(offset(rng), offset(rng), offset(rng)));
    }
  }
  finish_bounds(m);
  return m;
}

scene scene_from_mesh(mesh m) {
  scene s;
  s.meshes.push_back(std::move(m));
  s.materials.emplace_back();
  instance inst;
  finish_instance_transform(inst);
  s.instances.push_back(inst);
  return s;
}

scene make_instanced_scene(mesh m, int n, uint32_t seed) {
  scene s = scene_from_mesh(std::move(m));
  s.instances.clear();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double spacing = 2.5 * glm::length(s.meshes[0].bounds.diagonal());
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        instance inst;
        dvec3 axis = glm::normalize(dvec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5) + dvec3(1e-3));
        dmat4 m4 = glm::translate(dmat4(1.0), spacing * dvec3(x, y, z));
        m4 = glm::rotate(m4, 2.0 * double(pi) * unit(rng), axis);
        double scale = 0.5 + unit(rng);
        m4 = glm::scale(m4, dvec3(scale, scale * (0.5 + unit(rng)), (x + y + z) % 3 == 0 ? -scale : scale));
        inst.world_from_object = m4;
        finish_instance_transform(inst);
        s.instances.push_back(inst);
      }
  return s;
}

}  // namespace kiln
