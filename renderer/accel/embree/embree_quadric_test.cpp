// Quadrics through Embree: one user-geometry scene per definition placed by instances, bounds that
// never cull a hit the direct double-precision query finds, hits that
// name their instance and part, occluded() consistent with intersect(), outward normals under
// mirroring, and no self-intersection of secondary rays through the whole pipeline
// (intersect → shading point → offset origin → intersect).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <random>

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/synthetic_scenes.h"
#include "core/float_bits.h"
#include "geometry/quadric_test_util.h"
#include "shade/surface.h"

namespace kiln {
namespace {

instance place(uint32_t shape, const dmat4& world_from_object) {
  instance inst;
  inst.kind = shape_kind::quadric;
  inst.shape = shape;
  inst.world_from_object = world_from_object;
  finish_instance_transform(inst);
  return inst;
}

TEST(embree_quadrics, instances_share_one_definition_and_report_instance_and_part) {
  scene s;
  s.quadrics = {testing::make_sphere(1.0), testing::make_axial(quadric_kind::cylinder, 0.5, -1.0, 1.0, true)};
  s.materials.emplace_back();
  s.instances = {
      place(0, glm::translate(dmat4(1.0), dvec3(0, 0, -5))),
      place(0, glm::scale(glm::translate(dmat4(1.0), dvec3(4, 0, -5)), dvec3(2, 1, -1))),  // mirrored
      place(1, glm::translate(dmat4(1.0), dvec3(-4, 0, -5)))};
  embree_accelerator accel(s);

  ray r;
  r.direction = {0, 0, -1};
  auto a = accel.intersect(r);
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->instance_id, 0u);
  EXPECT_NEAR(a->t, 4.0f, 1e-6f);
  EXPECT_NEAR(a->geometric_normal.z, 1.0f, 1e-6f);
  EXPECT_NEAR(a->v, 0.0f, 1e-6f);  // the north pole (object +z, v = 0) faces the camera

  // The mirrored ellipsoid: its outward normal still points at the ray origin.
  r.origin = {5.0f, 0.0f, 0.0f};
  r.direction = glm::normalize(vec3(-0.2f, 0.0f, -1.0f));
  auto b = accel.intersect(r);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->instance_id, 1u);
  EXPECT_LT(glm::dot(b->geometric_normal, r.direction), 0.0f);
  surface_point sp = make_surface_point(s, *b, r);
  EXPECT_TRUE(sp.front_face);

  // Down the capped cylinder's axis: the cap at zmax, part 2.
  r.origin = {-4.0f, 0.1f, 0.0f};
  r.direction = {0, 0, -1};
  auto c = accel.intersect(r);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->instance_id, 2u);
  EXPECT_EQ(c->primitive_id, uint32_t(quadric_cap_zmax));
  EXPECT_NEAR(c->t, 4.0f, 1e-6f);
  EXPECT_TRUE(accel.occluded(r));
  r.tmax = 3.9f;
  EXPECT_FALSE(accel.occluded(r));
  EXPECT_FALSE(accel.intersect(r).has_value());
}

// Every kind, randomly placed: secondary rays from shading points never re-hit their own point,
// and occluded agrees with intersect.
TEST(embree_quadrics, secondary_rays_from_every_kind_never_self_intersect) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto unit = [&] {
    for (;;) {
      dvec3 v(u(rng), u(rng), u(rng));
      if (glm::length(v) > 0.1 && glm::length(v) <= 1.0) return glm::normalize(v);
    }
  };
  scene s;
  s.quadrics = testing::every_kind();
  s.materials.emplace_back();
  for (uint32_t k = 0; k < s.quadrics.size(); ++k) {
    dvec3 scale(0.5 + std::abs(u(rng)) * 2.0, 0.5 + std::abs(u(rng)) * 2.0, 0.5 + std::abs(u(rng)) * 2.0);
    dmat4 m = glm::translate(dmat4(1.0), dvec3(6.0 * k, 3.0 * u(rng), 100.0)) *
              glm::mat4_cast(glm::angleAxis(3.0 * u(rng), unit())) * glm::scale(dmat4(1.0), scale);
    s.instances.push_back(place(k, m));
  }
  embree_accelerator accel(s);
  int hits = 0, self_hits = 0, wrong_side = 0, disagreements = 0;
  for (int i = 0; i < 20000; ++i) {
    const instance& target = s.instances[size_t(i) % s.instances.size()];
    const bounds3& b = s.quadrics[target.shape].bounds;
    dvec3 aim = transform_point(target.world_from_object,
                                b.center() + 0.5 * b.diagonal() * dvec3(u(rng), u(rng), u(rng)));
    ray r;
    r.origin = vec3(aim + unit() * 20.0);
    r.direction = vec3(glm::normalize(aim - dvec3(r.origin)));
    auto h = accel.intersect(r);
    if (h.has_value() != accel.occluded(r)) ++disagreements;
    if (!h) continue;
    ++hits;
    surface_point sp = make_surface_point(s, *h, r);
    const instance& inst = s.instances[h->instance_id];
    const quadric& q = s.quadrics[inst.shape];
    for (int side = 0; side < 2; ++side) {
      vec3 dir = vec3(unit());
      if ((glm::dot(dir, sp.geometric_normal) > 0.0f) != (side == 0)) dir = -dir;
      ray next;
      next.origin = offset_ray_origin(sp.position, sp.position_error, sp.geometric_normal, dir);
      next.direction = dir;
      // The invariant that rules out self-intersection: the offset origin lies strictly on the
      // side of the surface the ray leaves to (exact sign of the implicit function in double).
      const dvec3 o = transform_point(inst.object_from_world, dvec3(next.origin));
      double f = quadric_implicit(q, o);  // side and disk (F = z)
      if (h->primitive_id == quadric_cap_zmin) f = q.zmin - o.z;
      if (h->primitive_id == quadric_cap_zmax) f = o.z - q.zmax;
      const vec3 outward = sp.front_face ? sp.geometric_normal : -sp.geometric_normal;
      if (f == 0.0 || (f > 0.0) != (glm::dot(dir, outward) > 0.0f)) ++wrong_side;
      auto again = accel.intersect(next);
      if (again && again->instance_id == h->instance_id && again->t < 10.0f * glm::length(sp.position_error))
        ++self_hits;
    }
  }
  EXPECT_GT(hits, 5000);
  EXPECT_EQ(self_hits, 0);
  EXPECT_EQ(wrong_side, 0);
  EXPECT_EQ(disagreements, 0);
}

// intersect_for_shadow() skips only the quadric normal: over every kind and part, under rotations,
// shears of scale and mirrors, it finds the same t, instance and part as intersect() and leaves the
// normal zero, while intersect()'s normal is quadric_world_normal's exactly.
TEST(embree_quadrics, the_shadow_walk_finds_the_same_hit_without_its_normal) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  scene s;
  s.quadrics = testing::every_kind();
  s.materials = {material{}};
  for (uint32_t k = 0; k < s.quadrics.size(); ++k) {
    const dvec3 scale(0.5 + std::abs(u(rng)), 0.5 + std::abs(u(rng)),
                      (k % 2 ? -1.0 : 1.0) * (0.5 + std::abs(u(rng))));
    const dmat4 m = glm::translate(dmat4(1.0), dvec3(5.0 * k, 2.0 * u(rng), -50.0)) *
                    glm::mat4_cast(glm::angleAxis(3.0 * u(rng), glm::normalize(dvec3(u(rng), u(rng), 1.0)))) *
                    glm::scale(dmat4(1.0), scale);
    s.instances.push_back(place(k, m));
  }
  embree_accelerator accel(s);
  int hits = 0, wrong_normal = 0, shadow_differs = 0;
  int parts[3] = {0, 0, 0};
  for (int i = 0; i < 6000; ++i) {
    const instance& target = s.instances[size_t(i) % s.instances.size()];
    const bounds3& b = s.quadrics[target.shape].bounds;
    const dvec3 aim = transform_point(target.world_from_object,
                                      b.center() + 0.5 * b.diagonal() * dvec3(u(rng), u(rng), u(rng)));
    ray r;
    r.origin = vec3(aim + dvec3(u(rng), u(rng), 1.0) * 10.0);
    r.direction = vec3(glm::normalize(aim - dvec3(r.origin)));
    const std::optional<hit> h = accel.intersect(r);
    if (!h) continue;
    ++hits;
    ++parts[std::min(h->primitive_id, 2u)];
    const instance& inst = s.instances[h->instance_id];
    if (h->geometric_normal != quadric_world_normal(inst, s.quadrics[inst.shape], r, h->t, h->primitive_id))
      ++wrong_normal;
    const std::optional<hit> shadow = accel.intersect_for_shadow(r);
    if (!shadow || shadow->t != h->t || shadow->instance_id != h->instance_id ||
        shadow->primitive_id != h->primitive_id || shadow->geometric_normal != vec3(0.0f))
      ++shadow_differs;
  }
  EXPECT_GT(hits, 3000);
  EXPECT_GT(parts[1] + parts[2], 50);  // caps are among them
  EXPECT_EQ(wrong_normal, 0);
  EXPECT_EQ(shadow_differs, 0);
}

// Occlusion stops at the first root it finds: over rays that graze every kind (aimed along the
// tangent plane at a surface point, a hair above or below it) and segments cut short so that roots
// fall outside them, occluded() must still say blocked exactly when intersect() finds a hit.
TEST(embree_quadrics, occluded_agrees_with_intersect_on_grazing_rays_and_short_segments) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto unit = [&] {
    for (;;) {
      dvec3 v(u(rng), u(rng), u(rng));
      if (glm::length(v) > 0.1 && glm::length(v) <= 1.0) return glm::normalize(v);
    }
  };
  scene s;
  s.quadrics = testing::every_kind();
  s.materials.emplace_back();
  for (uint32_t k = 0; k < s.quadrics.size(); ++k) {
    dmat4 m = glm::translate(dmat4(1.0), dvec3(5.0 * k, 2.0 * u(rng), -30.0)) *
              glm::mat4_cast(glm::angleAxis(3.0 * u(rng), unit())) *
              glm::scale(dmat4(1.0), dvec3(1.3, 0.8, 1.1));
    s.instances.push_back(place(k, m));
  }
  embree_accelerator accel(s);
  int hits = 0, misses = 0, disagreements = 0;
  for (int i = 0; i < 30000; ++i) {
    const instance& target = s.instances[size_t(i) % s.instances.size()];
    const quadric& q = s.quadrics[target.shape];
    const bounds3& b = q.bounds;
    const dvec3 inside = b.center() + 0.5 * b.diagonal() * dvec3(u(rng), u(rng), u(rng));
    const quadric_surface on = quadric_surface_at(q, quadric_side, inside);
    dvec3 tangent = glm::cross(on.normal, unit());
    if (glm::length(tangent) < 1e-6) tangent = on.dpdu;
    const dvec3 aim_object = on.point + 1e-7 * u(rng) * on.normal;
    const dvec3 aim = transform_point(target.world_from_object, aim_object);
    const dvec3 along = glm::normalize(transform_vector(target.world_from_object, tangent));
    ray r;
    r.origin = vec3(aim - 15.0 * along);
    r.direction = vec3(along);
    if (i % 3 == 1) {  // a segment that may end before, at or after the surface
      r.tmin = float(14.0 + 2.0 * std::abs(u(rng)));
      r.tmax = r.tmin + float(2.0 * std::abs(u(rng)));
    }
    const auto h = accel.intersect(r);
    (h ? hits : misses)++;
    if (h.has_value() != accel.occluded(r)) ++disagreements;
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(misses, 5000);
  EXPECT_EQ(disagreements, 0);
}

// Embree culls quadric instances by boxes (the instance's world box, then the object box against
// the ray carried to object space in float), while the callbacks solve on the double-precision
// world ray: over rotated, non-uniformly scaled (and mirrored) placements of every kind, rays aimed
// at surface points pushed to the box's faces, edges and corners (cap rims, clipped ends), and at
// points on those faces just off the surface, Embree's closest hit must be exactly the direct
// query's: same hit or miss, same t, part and instance. A box test that lost a root the direct
// query finds would show here.
TEST(embree_quadrics, box_culling_never_loses_a_hit_of_the_direct_query) {
  std::mt19937_64 rng(5150);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto unit = [&] {
    for (;;) {
      dvec3 v(u(rng), u(rng), u(rng));
      if (glm::length(v) > 0.1 && glm::length(v) <= 1.0) return glm::normalize(v);
    }
  };
  const std::vector<quadric> kinds = testing::every_kind();
  int hits = 0, misses = 0, disagreements = 0;
  for (uint32_t k = 0; k < kinds.size(); ++k) {
    // Several placements per scene: a lone primitive is a BVH leaf Embree visits without a box test.
    scene s;
    s.quadrics = {kinds[k]};
    s.materials.emplace_back();
    for (int placement = 0; placement < 6; ++placement) {
      dvec3 scale(0.3 + std::abs(u(rng)) * 3.0, 0.3 + std::abs(u(rng)) * 3.0, 0.3 + std::abs(u(rng)) * 3.0);
      if (placement % 3 == 2) scale.x = -scale.x;
      const dmat4 m = glm::translate(dmat4(1.0), dvec3(40.0 * u(rng), 40.0 * u(rng), 40.0 * u(rng))) *
                      glm::mat4_cast(glm::angleAxis(3.0 * u(rng), unit())) * glm::scale(dmat4(1.0), scale);
      s.instances.push_back(place(0, m));
    }
    embree_accelerator accel(s);
    const prepared_quadric form = prepare_quadric(s.quadrics[0]);
    const bounds3& b = s.quadrics[0].bounds;
    for (int i = 0; i < 12000; ++i) {
      const instance& target = s.instances[size_t(i) % s.instances.size()];
      dvec3 p = b.center() + 0.5 * b.diagonal() * dvec3(u(rng), u(rng), u(rng));
      // Push one to three coordinates onto the box (faces, edges, corners), then onto the side.
      for (int axis = 0; axis < 3; ++axis)
        if (u(rng) > 0.0) p[axis] = u(rng) > 0.0 ? b.lower[axis] : b.upper[axis];
      if (i % 2 == 0) p = quadric_surface_at(s.quadrics[0], quadric_side, p).point;
      const dvec3 aim = transform_point(target.world_from_object, p);
      ray r;
      r.origin = vec3(aim + unit() * 10.0);
      r.direction = vec3(glm::normalize(aim - dvec3(r.origin)));
      const auto h = accel.intersect(r);
      // The direct answer: the closest root over every placement, in double.
      std::optional<quadric_ray_hit> direct;
      uint32_t direct_instance = 0;
      for (uint32_t j = 0; j < s.instances.size(); ++j) {
        const instance& inst = s.instances[j];
        const auto d = intersect_quadric(form, transform_point(inst.object_from_world, dvec3(r.origin)),
                                         transform_vector(inst.object_from_world, dvec3(r.direction)), r.tmin,
                                         direct ? float(direct->t) : r.tmax, false);
        if (d) direct = d, direct_instance = j;
      }
      (h ? hits : misses)++;
      if (h.has_value() != direct.has_value() ||
          (h && (h->t != float(direct->t) || h->primitive_id != direct->part ||
                 h->instance_id != direct_instance)))
        ++disagreements;
    }
  }
  EXPECT_GT(hits, 10000);
  EXPECT_GT(misses, 5000);
  EXPECT_EQ(disagreements, 0);
}

// A coherent stream (each pixel's camera rays, as the camera stage sends them) through a scene of
// every kind of quadric beside a triangle mesh: Embree hands the quadric callbacks whole packets,
// and every lane must get the hit its single-ray query gets, bit for bit.
TEST(embree_quadrics, coherent_streams_return_the_single_ray_hits_of_every_kind) {
  scene s;
  s.quadrics = testing::every_kind();
  s.materials.emplace_back();
  for (uint32_t k = 0; k < s.quadrics.size(); ++k) {
    const dvec3 at(3.0 * double(k % 4) - 4.5, 3.0 * double(k / 4) - 3.0, -8.0);
    s.instances.push_back(place(k, glm::rotate(glm::translate(dmat4(1.0), at), 0.3 * k, dvec3(1, 1, 0))));
  }
  s.meshes.push_back(make_sphere_mesh(16, 32, 0.8f));
  instance mesh_instance;
  mesh_instance.kind = shape_kind::mesh;
  mesh_instance.world_from_object = glm::translate(dmat4(1.0), dvec3(4.5, 3.0, -8.0));
  finish_instance_transform(mesh_instance);
  s.instances.push_back(mesh_instance);
  embree_accelerator accel(s);
  size_t hits = 0, differing = 0;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 80; ++x) {
      std::vector<ray> pixel;  // 16 rays through one pixel of an 80×60 view
      for (int k = 0; k < 16; ++k) {
        ray r;
        r.kind = ray_kind::camera;
        r.direction = glm::normalize(vec3((x + (k % 4 + 0.5f) / 4.0f) / 80.0f * 14.0f - 7.0f,
                                          (y + (k / 4 + 0.5f) / 4.0f) / 60.0f * 10.5f - 5.25f, -8.0f));
        pixel.push_back(r);
      }
      std::vector<std::optional<hit>> streamed(pixel.size());
      accel.intersect_coherent(pixel.data(), pixel.size(), streamed.data());
      for (size_t k = 0; k < pixel.size(); ++k) {
        const std::optional<hit> single = accel.intersect(pixel[k]);
        hits += single.has_value();
        differing +=
            streamed[k].has_value() != single.has_value() ||
            (single && (streamed[k]->t != single->t || streamed[k]->instance_id != single->instance_id ||
                        streamed[k]->primitive_id != single->primitive_id ||
                        streamed[k]->geometric_normal != single->geometric_normal));
      }
    }
  EXPECT_GT(hits, 80u * 60u * 16u / 5u);
  EXPECT_LT(hits, 80u * 60u * 16u);
  EXPECT_EQ(differing, 0u);
}

}  // namespace
}  // namespace kiln
