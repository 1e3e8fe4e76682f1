// The normal-mapping frame (tangent, cross(normal, tangent)·w, normal) of quadric hits follows the
// same convention as meshes: for every kind and part, under plain and mirroring placements, the
// mesh tangent generator run on a tiny world-space triangle of surface points around the hit
// (with their parametric UVs) gives the same tangent direction and the same w. Mirrored mesh
// instances are held to the same rule.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <random>

#include "accel/embree/embree_accelerator.h"
#include "geometry/quadric_test_util.h"
#include "io/gltf/mesh_tangents.h"
#include "shade/surface.h"

namespace kiln {
namespace {

// The mesh convention's w and unit tangent at vertex 0 of the world-space triangle p with UVs uv
// and outward unit normals n.
vec4 mesh_frame(const vec3 (&p)[3], const vec3 (&n)[3], const vec2 (&uv)[3]) {
  mesh m;
  m.positions = {p[0], p[1], p[2]};
  m.normals = {n[0], n[1], n[2]};
  m.indices = {0, 1, 2};
  return generate_tangents(m, {uv[0], uv[1], uv[2]})[0];
}

TEST(tangent_frame, quadric_handedness_matches_the_mesh_generator_for_every_kind_part_and_mirror) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto unit = [&] {
    for (;;) {
      dvec3 v(u(rng), u(rng), u(rng));
      if (glm::length(v) > 0.1 && glm::length(v) <= 1.0) return glm::normalize(v);
    }
  };
  const std::vector<quadric> kinds = testing::every_kind();
  for (size_t k = 0; k < kinds.size(); ++k) {
    for (bool mirrored : {false, true}) {
      scene s;
      s.quadrics = {kinds[k]};
      s.materials.emplace_back();
      instance inst;
      inst.kind = shape_kind::quadric;
      const dvec3 scale(mirrored ? -1.3 : 1.3, 0.8, 1.1);
      inst.world_from_object = glm::translate(dmat4(1.0), dvec3(0.5, -0.25, 1.0)) *
                               glm::mat4_cast(glm::angleAxis(2.0 * u(rng), unit())) *
                               glm::scale(dmat4(1.0), scale);
      finish_instance_transform(inst);
      s.instances = {inst};
      embree_accelerator accel(s);
      const quadric& q = s.quadrics[0];
      const double size = glm::length(q.bounds.diagonal());
      std::map<uint32_t, int> compared;  // per part
      int mismatches = 0;
      for (int i = 0; i < 3000; ++i) {
        const dvec3 aim_object =
            q.bounds.center() + 0.5 * q.bounds.diagonal() * dvec3(u(rng), u(rng), u(rng));
        const dvec3 aim = transform_point(inst.world_from_object, aim_object);
        ray r;
        r.origin = vec3(aim + unit() * 10.0);
        r.direction = vec3(glm::normalize(aim - dvec3(r.origin)));
        auto h = accel.intersect(r);
        if (!h) continue;
        const surface_point sp = make_surface_point(s, *h, r);
        // Three surface points: the hit and two steps along the object-space tangent plane.
        const dvec3 o = transform_point(inst.object_from_world, dvec3(r.origin));
        const dvec3 d = transform_vector(inst.object_from_world, dvec3(r.direction));
        quadric_surface pts[3];
        pts[0] = quadric_surface_at(q, h->primitive_id, o + double(h->t) * d);
        const double step = 2e-4 * size;
        const dvec3 across = glm::cross(pts[0].normal, pts[0].dpdu);
        pts[1] = quadric_surface_at(q, h->primitive_id, pts[0].point + step * pts[0].dpdu);
        pts[2] = quadric_surface_at(q, h->primitive_id, pts[0].point + step * across);
        vec3 p[3], n[3];
        vec2 uv[3];
        for (int j = 0; j < 3; ++j) {
          p[j] = vec3(transform_point(inst.world_from_object, pts[j].point));
          n[j] = vec3(glm::normalize(inst.world_from_object_normal * pts[j].normal));
          uv[j] = vec2(pts[j].uv);
        }
        // Skip triangles the parameterisation does not cover smoothly: across the u seam, near
        // poles, apexes and clamped rims, where the UV triangle degenerates.
        const vec2 w1 = uv[1] - uv[0], w2 = uv[2] - uv[0];
        const float det = w1.x * w2.y - w2.x * w1.y;
        if (glm::length(w1) > 0.1f || glm::length(w2) > 0.1f) continue;
        if (!(std::abs(det) > 0.2f * glm::length(w1) * glm::length(w2))) continue;
        // The general quadric's box projection folds where the surface turns vertical.
        if (q.kind == quadric_kind::general && std::abs(pts[0].normal.z) < 0.05) continue;
        const vec4 expected = mesh_frame(p, n, uv);
        ++compared[h->primitive_id];
        const bool same_w = expected.w == sp.tangent.w;
        const bool same_tangent = glm::dot(vec3(expected), glm::normalize(vec3(sp.tangent))) > 0.98f;
        if (!same_w || !same_tangent) {
          if (++mismatches <= 3)
            ADD_FAILURE() << "kind " << int(q.kind) << (mirrored ? " mirrored" : "") << " part "
                          << h->primitive_id << " uv (" << uv[0].x << ", " << uv[0].y << "): w "
                          << sp.tangent.w << " vs mesh " << expected.w << " tangent dot "
                          << glm::dot(vec3(expected), glm::normalize(vec3(sp.tangent))) << " z "
                          << pts[0].point.z;
        }
      }
      EXPECT_EQ(mismatches, 0) << "kind " << int(q.kind) << (mirrored ? " mirrored" : "");
      EXPECT_GT(compared[quadric_side], 100) << "kind " << int(q.kind);
      if (q.caps) {
        // Every cap with area was compared (the cone's apex and a pointed end have none).
        for (uint32_t part : {uint32_t(quadric_cap_zmin), uint32_t(quadric_cap_zmax)}) {
          const double z0 = part == quadric_cap_zmin ? q.zmin : q.zmax;
          if (quadric_radius_at(q, z0) > 0.0) {
            EXPECT_GT(compared[part], 10) << "kind " << int(q.kind) << " part " << part;
          }
        }
      }
    }
  }
}

// A mesh patch whose tangents come from the generator in object space, placed by a mirroring
// instance: the shading frame must equal the generator's frame of the placed, world-space patch.
TEST(tangent_frame, mirrored_mesh_instances_flip_the_handedness) {
  mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.indices = {0, 1, 2};
  m.texcoords0 = {{0, 1}, {1, 1}, {0, 0}};  // glTF v down: +y is the image's up
  m.tangents = generate_tangents(m, m.texcoords0);
  ASSERT_EQ(m.tangents[0].w, 1.0f);
  for (double sx : {1.0, -1.0}) {
    scene s;
    s.meshes = {m};
    s.materials.emplace_back();
    instance inst;
    inst.world_from_object = glm::scale(glm::translate(dmat4(1.0), dvec3(0, 0, -3)), dvec3(sx, 2.0, 1.0));
    finish_instance_transform(inst);
    s.instances = {inst};
    vec3 p[3], n[3];
    vec2 uv[3];
    const vec3 world_normal = vec3(glm::normalize(inst.world_from_object_normal * dvec3(0, 0, 1)));
    for (int j = 0; j < 3; ++j) {
      p[j] = vec3(transform_point(inst.world_from_object, dvec3(m.positions[size_t(j)])));
      n[j] = world_normal;
      uv[j] = m.texcoords0[size_t(j)];
    }
    const vec4 expected = mesh_frame(p, n, uv);
    hit h;
    h.t = 3.0f;
    h.u = h.v = 0.25f;
    h.geometric_normal = world_normal;
    ray r;
    r.origin = vec3(0.25f * float(sx), 0.5f, 0.0f);
    r.direction = vec3(0, 0, -1);
    const surface_point sp = make_surface_point(s, h, r);
    EXPECT_EQ(sp.tangent.w, expected.w) << "x scale " << sx;
    EXPECT_EQ(sp.tangent.w, float(sx));
    EXPECT_GT(glm::dot(glm::normalize(vec3(sp.tangent)), vec3(expected)), 0.999f);
  }
}

}  // namespace
}  // namespace kiln
