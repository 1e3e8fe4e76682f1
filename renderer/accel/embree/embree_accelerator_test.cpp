#include "accel/embree/embree_accelerator.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "accel/embree/embree_device.h"
#include "core/error.h"
#include "geometry/triangle.h"

namespace kiln {
namespace {

// A unit square in the z = 0 plane, front face +Z, two triangles.
mesh unit_square() {
  mesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  return m;
}

scene two_instances() {
  scene s;
  s.meshes.push_back(unit_square());
  s.materials.emplace_back();
  instance a;
  a.world_from_object = glm::translate(dmat4(1.0), dvec3(0, 0, -5));
  finish_instance_transform(a);
  instance b;  // mirrored in z and moved further away: its front face must point toward +Z still
  b.world_from_object = glm::scale(glm::translate(dmat4(1.0), dvec3(10, 0, -8)), dvec3(1, 1, -1));
  finish_instance_transform(b);
  s.instances = {a, b};
  return s;
}

TEST(embree_accelerator, closest_hit_reports_instance_t_and_barycentrics) {
  scene s = two_instances();
  embree_accelerator accel(s);
  ray r;
  r.origin = {0.5f, -0.25f, 0.0f};
  r.direction = {0, 0, -1};
  auto h = accel.intersect(r);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->instance_id, 0u);
  EXPECT_NEAR(h->t, 5.0f, 1e-5f);
  // Reconstruct the hit from (u, v) with Embree's convention and compare with o + t·d.
  auto p = triangle_vertices(s.meshes[0], h->primitive_id);
  vec3 q = (1 - h->u - h->v) * p[0] + h->u * p[1] + h->v * p[2];
  EXPECT_NEAR(q.x, 0.5f, 1e-5f);
  EXPECT_NEAR(q.y, -0.25f, 1e-5f);
  EXPECT_NEAR(h->geometric_normal.z, 1.0f, 1e-6f);
}

TEST(embree_accelerator, mirrored_instance_keeps_front_face_through_normal_matrix) {
  scene s = two_instances();
  embree_accelerator accel(s);
  ray r;
  r.origin = {10.0f, 0.3f, 0.0f};
  r.direction = {0, 0, -1};
  auto h = accel.intersect(r);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->instance_id, 1u);
  EXPECT_NEAR(h->t, 8.0f, 1e-5f);
  // Scale z by -1 maps the object +Z normal to world -Z: the normal matrix says the front face
  // (counter-clockwise in object space) now faces -Z, as glTF's determinant rule demands.
  EXPECT_NEAR(h->geometric_normal.z, -1.0f, 1e-6f);
}

// The hit's world normal comes from Embree's object-space Ng: it must be the normal of the
// triangle's vertices carried through the normal matrix, for rotated, sheared, non-uniformly
// scaled and mirrored instances and for slivers, in both traversal paths.
TEST(embree_accelerator, world_normal_matches_the_vertices_under_any_instance_transform) {
  scene s;
  mesh m;
  uint32_t seed = 12345;
  auto uniform = [&seed](float lo, float hi) {
    seed = seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * float(seed >> 8) / float(1u << 24);
  };
  for (int t = 0; t < 64; ++t) {
    const vec3 c(uniform(-3, 3), uniform(-3, 3), 0.0f);
    const float sliver = t % 8 == 0 ? 1e-3f : 1.0f;  // some nearly degenerate triangles
    const uint32_t base = uint32_t(m.positions.size());
    m.positions.push_back(c + vec3(uniform(-0.4f, 0.4f), uniform(-0.4f, 0.4f), uniform(-0.3f, 0.3f)));
    m.positions.push_back(c + vec3(0.5f, sliver * uniform(-0.2f, 0.2f), uniform(-0.3f, 0.3f)));
    m.positions.push_back(c + vec3(uniform(-0.2f, 0.2f), 0.5f * sliver, uniform(-0.3f, 0.3f)));
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  }
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  s.meshes.push_back(m);
  s.materials.emplace_back();
  const dmat4 transforms[] = {
      dmat4(1.0),
      glm::rotate(glm::translate(dmat4(1.0), dvec3(20, 0, 0)), 0.7, glm::normalize(dvec3(1, 2, 3))),
      glm::scale(glm::translate(dmat4(1.0), dvec3(40, 0, 0)), dvec3(3.0, 0.2, -1.5)),  // mirrored
      glm::translate(dmat4(1.0), dvec3(60, 0, 0)) * dmat4(1, 0.5, 0, 0, 0, 1, 0, 0, 0.3, 0, 1, 0, 0, 0, 0, 1),
  };
  for (const dmat4& t : transforms) {
    instance inst;
    inst.world_from_object = t;
    finish_instance_transform(inst);
    s.instances.push_back(inst);
  }
  embree_accelerator accel(s);
  std::vector<ray> rays;
  std::vector<std::pair<uint32_t, uint32_t>> expected;  // instance, triangle
  for (uint32_t i = 0; i < s.instances.size(); ++i)
    for (uint32_t t = 0; t < m.triangle_count(); ++t) {
      const auto p = triangle_vertices(m, t);
      const dvec3 centroid =
          transform_point(s.instances[i].world_from_object, dvec3(p[0] + p[1] + p[2]) / 3.0);
      const dvec3 n = dvec3(triangle_world_normal(s.instances[i], m, t));
      ray r;
      r.origin = vec3(centroid + 50.0 * n);  // straight down onto the triangle's centroid
      r.direction = vec3(-n);
      rays.push_back(r);
      expected.emplace_back(i, t);
    }
  std::vector<std::optional<hit>> streamed(rays.size());
  accel.intersect_coherent(rays.data(), rays.size(), streamed.data());
  int checked = 0;
  for (size_t k = 0; k < rays.size(); ++k) {
    for (const std::optional<hit>& h : {accel.intersect(rays[k]), streamed[k]}) {
      ASSERT_TRUE(h) << k;
      // Triangles of one instance may overlap along the ray; compare with the one that was hit.
      const vec3 reference = triangle_world_normal(s.instances[h->instance_id], m, h->primitive_id);
      EXPECT_NEAR(glm::length(h->geometric_normal), 1.0f, 1e-6f) << k;
      EXPECT_GT(glm::dot(h->geometric_normal, reference), 1.0f - 1e-6f) << k;
      checked += h->instance_id == expected[k].first && h->primitive_id == expected[k].second;
    }
  }
  EXPECT_GT(checked, int(rays.size()));  // most rays hit the triangle they were aimed at
}

TEST(embree_accelerator, occlusion_respects_segment_extent) {
  scene s = two_instances();
  embree_accelerator accel(s);
  ray r;
  r.origin = {0, 0, 0};
  r.direction = {0, 0, -1};
  r.tmax = 4.9f;
  EXPECT_FALSE(accel.occluded(r));
  r.tmax = 5.1f;
  EXPECT_TRUE(accel.occluded(r));
  r.tmin = 5.05f;
  EXPECT_FALSE(accel.occluded(r));
}

TEST(embree_accelerator, invalid_rays_never_reach_embree) {
  scene s = two_instances();
  embree_accelerator accel(s);
  ray r;
  r.origin = {0, 0, 0};
  r.direction = {0, 0, std::nanf("")};
  EXPECT_FALSE(accel.intersect(r));
  EXPECT_FALSE(accel.occluded(r));
  r.direction = {0, 0, 0};
  EXPECT_FALSE(accel.intersect(r));
  r.direction = {0, 0, -1};
  r.origin = {inf, 0, 0};
  EXPECT_FALSE(accel.intersect(r));
}

TEST(embree_accelerator, misses_outside_geometry) {
  scene s = two_instances();
  embree_accelerator accel(s);
  ray r;
  r.origin = {3.0f, 0.0f, 0.0f};
  r.direction = {0, 0, -1};
  EXPECT_FALSE(accel.intersect(r));
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

TEST(embree_error_log, records_the_first_device_error_and_throws_it_as_a_render_error) {
  RTCDevice device = process_embree_device();
  ASSERT_NE(device, nullptr);
  embree_error_log log;
  {
    embree_error_scope scope(log);
    EXPECT_NO_THROW(log.throw_if_any("building"));
    // An invalid geometry type makes Embree call the error callback instead of returning an error.
    RTCGeometry geometry = rtcNewGeometry(device, RTCGeometryType(999));
    EXPECT_EQ(geometry, nullptr);
  }
  try {
    log.throw_if_any("tracing rays");
    ADD_FAILURE() << "the recorded Embree error was not thrown";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::render);
    EXPECT_NE(std::string(e.what()).find("Embree error"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("while tracing rays"), std::string::npos) << e.what();
  }
}

// Every accelerator of a process shares one device: a second build does not create another, and
// an error inside one accelerator's scope is not blamed on another.
TEST(embree_device, one_device_serves_every_accelerator_and_errors_stay_with_their_scope) {
  scene s = two_instances();
  embree_accelerator first(s);
  const uint64_t unscoped = unscoped_embree_errors();
  embree_error_log other;
  {
    embree_error_scope scope(other);
    EXPECT_EQ(rtcNewGeometry(process_embree_device(), RTCGeometryType(999)), nullptr);
  }
  EXPECT_THROW(other.throw_if_any("test"), error);
  EXPECT_EQ(unscoped_embree_errors(), unscoped);
  EXPECT_NO_THROW(first.throw_if_failed());
  embree_accelerator second(s);
  EXPECT_EQ(process_embree_device(), process_embree_device());
  // Each build measures its own memory: the same scene costs the same bytes twice.
  EXPECT_GT(first.embree_bytes(), 0u);
  EXPECT_EQ(first.embree_bytes(), second.embree_bytes());
}

TEST(embree_accelerator, a_healthy_scene_reports_no_traversal_error) {
  scene s = two_instances();
  embree_accelerator accel(s);
  ray r;
  r.direction = {0, 0, -1};
  EXPECT_TRUE(accel.intersect(r));
  EXPECT_NO_THROW(accel.throw_if_failed());
}

}  // namespace
}  // namespace kiln
