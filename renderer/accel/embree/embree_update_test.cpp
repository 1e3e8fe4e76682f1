// embree_accelerator::update against a backend built afresh over the same scene: after instances
// move and a mesh deforms in place, every ray of a fan must hit the same instance and triangle at
// the same distance, whether the mesh BVH was rebuilt for refitting (its first move), refitted
// (later moves) or rebuilt because its triangles changed.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "accel/embree/embree_accelerator.h"

namespace kiln {
namespace {

// An n x n grid of quads over [-1, 1]^2 at z = 0, its heights a wave of the given phase.
mesh wavy_grid(int n, double phase) {
  mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -1.0 + 2.0 * i / n, y = -1.0 + 2.0 * j / n;
      m.positions.emplace_back(x, y, 0.3 * std::sin(3.0 * x + phase) * std::cos(2.0 * y - phase));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  return m;
}

void place(instance& inst, const dmat4& world) {
  inst.world_from_object = world;
  finish_instance_transform(inst);
}

// Two instances of the wave (mesh 0) and one of a rigid grid (mesh 1).
scene frame_scene(double phase, double shift) {
  scene s;
  s.meshes = {wavy_grid(24, phase), wavy_grid(8, 0.0)};
  s.materials.emplace_back();
  instance a, b, c;
  place(a, glm::translate(dmat4(1.0), dvec3(shift, 0, -4)));
  place(b,
        glm::rotate(glm::translate(dmat4(1.0), dvec3(-1.5, 0.5, -6 + shift)), 0.4 + shift, dvec3(0, 1, 0)));
  c.shape = 1;
  place(c, glm::translate(dmat4(1.0), dvec3(1.2, -shift, -5)));
  a.shape = b.shape = 0;
  s.instances = {a, b, c};
  return s;
}

// The fan of rays from the origin over the view, their hits by both backends.
void expect_same_hits(const accelerator& updated, const accelerator& fresh) {
  int hits = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      ray r;
      r.origin = vec3(0.0f);
      r.direction = glm::normalize(vec3(-0.8f + 1.6f * x / 39, -0.6f + 1.2f * y / 39, -1.0f));
      const auto u = updated.intersect(r), f = fresh.intersect(r);
      ASSERT_EQ(bool(u), bool(f)) << x << "," << y;
      EXPECT_EQ(updated.occluded(r), fresh.occluded(r));
      if (!u) continue;
      ++hits;
      EXPECT_EQ(u->instance_id, f->instance_id) << x << "," << y;
      EXPECT_EQ(u->primitive_id, f->primitive_id) << x << "," << y;
      EXPECT_EQ(u->t, f->t) << x << "," << y;  // the same triangle test on the same vertices
    }
  EXPECT_GT(hits, 250);  // the fan sees the grids (about a fifth of it), not only the background
}

TEST(embree_update, moved_instances_and_a_refitted_mesh_hit_like_a_fresh_build) {
  scene s = frame_scene(0.0, 0.0);
  embree_accelerator accel(s);
  for (int frame = 1; frame <= 3; ++frame) {
    SCOPED_TRACE(frame);
    scene next = frame_scene(0.7 * frame, 0.1 * frame);
    next.meshes[1] = std::move(s.meshes[1]);  // the rigid mesh is handed over, as the loader does
    s = std::move(next);
    ASSERT_TRUE(accel.update({0}));
    embree_accelerator fresh(s);
    expect_same_hits(accel, fresh);
  }
}

TEST(embree_update, a_deformed_mesh_with_other_triangles_is_rebuilt) {
  scene s = frame_scene(0.0, 0.0);
  embree_accelerator accel(s);
  ASSERT_TRUE(accel.update({0}));  // now refittable
  scene next = frame_scene(1.0, 0.2);
  next.meshes[0] = wavy_grid(12, 1.0);  // fewer triangles: a refit cannot take it
  s = std::move(next);
  ASSERT_TRUE(accel.update({0}));
  embree_accelerator fresh(s);
  expect_same_hits(accel, fresh);
}

TEST(embree_update, instances_that_place_other_shapes_need_a_new_build) {
  scene s = frame_scene(0.0, 0.0);
  embree_accelerator accel(s);
  s.instances[2].shape = 0;
  EXPECT_FALSE(accel.update({}));
  s = frame_scene(0.0, 0.0);
  s.instances.pop_back();
  EXPECT_FALSE(accel.update({}));
}

}  // namespace
}  // namespace kiln
