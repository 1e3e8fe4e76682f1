#include "accel/grid/grid_accelerator.h"

#include <gtest/gtest.h>

#include "accel/grid/synthetic_scenes.h"

namespace kiln {
namespace {

// Nested grids: one grid per unique mesh, so a thousand placements cost a thousand transforms and
// a top-level grid over instance bounds, never a thousand copies of the mesh's grid.
TEST(grid_accelerator, memory_grows_with_unique_geometry_not_instances) {
  const mesh sphere = make_sphere_mesh(40, 80, 1.0f);
  const scene one = make_instanced_scene(sphere, 1, 5);
  const scene many = make_instanced_scene(sphere, 10, 5);
  ASSERT_EQ(many.instances.size(), 1000u);
  const grid_statistics a = grid_accelerator(one, uniform_grid_options()).statistics();
  const grid_statistics b = grid_accelerator(many, uniform_grid_options()).statistics();
  const size_t mesh_triangles = sphere.triangle_count();
  // The 1000-instance scene places 1000x the triangles but needs well under 10x the memory.
  EXPECT_LT(b.memory_bytes, 10 * a.memory_bytes);
  EXPECT_GT(b.item_references, 0u);
  EXPECT_LT(b.item_references, a.item_references + 1000 * 27);  // + instance references of the top grid
  EXPECT_GT(a.item_references, mesh_triangles);  // triangles straddling cells are referenced more than once
}

TEST(grid_accelerator, mirrored_instance_hit_matches_object_space_answer) {
  scene s = make_instanced_scene(make_sphere_mesh(16, 32, 1.0f), 3, 8);
  grid_accelerator g(s, adaptive_grid_options());
  for (uint32_t i = 0; i < s.instances.size(); ++i) {
    // Aim at each instance's centre from outside along -Z: the hit point, moved into the hit
    // instance's object space, lies on its unit sphere (facets reach in to cos(pi/16) ≈ 0.98),
    // and the normal faces the ray (the sphere's outside, through the normal matrix).
    dvec3 centre = transform_point(s.instances[i].world_from_object, dvec3(0.0));
    ray r;
    r.origin = vec3(centre + dvec3(0.0, 0.0, 1000.0));
    r.direction = {0.0f, 0.0f, -1.0f};
    auto h = g.intersect(r);
    ASSERT_TRUE(h);
    const vec3 p = r.origin + h->t * r.direction;
    EXPECT_LT(glm::dot(h->geometric_normal, r.direction), 0.0f) << "outward normal through the normal matrix";
    const double radius =
        glm::length(transform_point(s.instances[h->instance_id].object_from_world, dvec3(p)));
    EXPECT_GT(radius, 0.97);
    EXPECT_LT(radius, 1.0001);
  }
  ray invalid;
  invalid.direction = {0.0f, 0.0f, 0.0f};
  EXPECT_FALSE(g.intersect(invalid));
  EXPECT_FALSE(g.occluded(invalid));
}

TEST(grid_accelerator, empty_scene_never_hits) {
  scene s;
  grid_accelerator g(s, uniform_grid_options());
  ray r;
  EXPECT_FALSE(g.intersect(r));
  EXPECT_FALSE(g.occluded(r));
}

}  // namespace
}  // namespace kiln
