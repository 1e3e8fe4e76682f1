// The fast paths of the quadric queries against the full ones they stand for, over many random
// rays at every kind (grazing ones and ranges that cut off roots included): the prepared form
// returns exactly the per-call form's hit, any-hit is empty exactly when closest-hit is, and the
// partial surface reconstructions (hit normal and uv, UV Jacobian) equal what the full
// quadric_surface_at gives at the same points, bit for bit, and the closed-form curvature is the
// limit of central differences of the full surface's normals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "geometry/quadric.h"
#include "geometry/quadric_test_util.h"

namespace kiln {
namespace {

struct random_ray {
  dvec3 o, d;
  double tmin, tmax;
};

// Rays from a shell around the primitive aimed at a point near its surface: every third one is
// aimed along the surface's tangent plane there (grazing), the rest at random points in the
// bounds; every fourth has its range cut so that roots fall outside it.
std::vector<random_ray> rays_at(const quadric& q, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.0, 1.0);
  const bounds3 b = stored_quadric_bounds(q);
  const dvec3 center = b.center();
  const double size = glm::length(b.diagonal()) + 1e-3;
  std::vector<random_ray> out;
  for (int i = 0; i < count; ++i) {
    dvec3 dir(unit(rng), unit(rng), unit(rng));
    if (glm::length(dir) < 1e-3) dir = dvec3(1, 0, 0);
    const dvec3 origin = center + (2.0 + 3.0 * positive(rng)) * size * glm::normalize(dir);
    dvec3 target = center + 0.5 * b.diagonal() * dvec3(unit(rng), unit(rng), unit(rng));
    if (i % 3 == 0 && q.kind != quadric_kind::disk) {
      // A point on the surface and a direction in its tangent plane.
      const quadric_surface s = quadric_surface_at(q, quadric_side, target);
      dvec3 tangent = glm::cross(s.normal, dvec3(unit(rng), unit(rng), unit(rng)));
      if (glm::length(tangent) < 1e-6) tangent = s.dpdu;
      tangent = glm::normalize(tangent);
      target = s.point + 1e-9 * size * unit(rng) * s.normal;
      out.push_back({target - 3.0 * size * tangent, tangent, 0.0, 1e30});
      continue;
    }
    random_ray r{origin, target - origin, 0.0, 1e30};
    if (i % 4 == 1) {
      r.tmin = 0.8 + 0.3 * positive(rng);
      r.tmax = r.tmin + 0.4 * positive(rng);
    }
    out.push_back(r);
  }
  return out;
}

TEST(quadric_queries, prepared_form_and_any_hit_agree_with_closest_hit_on_every_kind) {
  int hits = 0, misses = 0;
  for (const quadric& q : testing::every_kind()) {
    const prepared_quadric p = prepare_quadric(q);
    for (const random_ray& r : rays_at(q, 4000, 7u + uint32_t(q.kind))) {
      const auto closest = intersect_quadric(q, r.o, r.d, r.tmin, r.tmax);
      const auto prepared = intersect_quadric(p, r.o, r.d, r.tmin, r.tmax);
      const auto any = intersect_quadric(p, r.o, r.d, r.tmin, r.tmax, true);
      ASSERT_EQ(closest.has_value(), prepared.has_value()) << int(q.kind);
      ASSERT_EQ(closest.has_value(), any.has_value()) << int(q.kind);
      if (!closest) {
        ++misses;
        continue;
      }
      ++hits;
      EXPECT_EQ(closest->t, prepared->t);
      EXPECT_EQ(closest->part, prepared->part);
      // Any hit is a real hit in range, never closer than the closest.
      EXPECT_GT(any->t, r.tmin);
      EXPECT_LT(any->t, r.tmax);
      EXPECT_GE(any->t, closest->t);
    }
  }
  // Both outcomes are well represented, or the agreement would say little.
  EXPECT_GT(hits, 10000);
  EXPECT_GT(misses, 5000);
}

// The UV Jacobian and curvature as they were computed before the partial reconstructions: full
// quadric_surface_at at every neighbouring point.
dvec2 uv_difference(const dvec2& a, const dvec2& b) {
  dvec2 d = a - b;
  d.x -= std::round(d.x);
  return d;
}

TEST(quadric_queries, partial_reconstructions_equal_the_full_surface) {
  instance inst;
  inst.kind = shape_kind::quadric;
  inst.world_from_object = dmat4(dvec4(0.8, 0.1, 0.0, 0.0), dvec4(-0.1, 1.2, 0.3, 0.0),
                                 dvec4(0.0, -0.2, -0.9, 0.0), dvec4(1.0, -2.0, 3.0, 1.0));
  finish_instance_transform(inst);
  inst.world_from_object_normal = glm::transpose(glm::inverse(dmat3(inst.world_from_object)));
  int checked = 0;
  for (const quadric& q : testing::every_kind()) {
    for (const random_ray& r : rays_at(q, 1500, 99u + uint32_t(q.kind))) {
      const auto h = intersect_quadric(q, r.o, r.d, r.tmin, r.tmax);
      if (!h) continue;
      // The same hit as a world ray: object ray carried by world_from_object.
      ray wr;
      wr.origin = vec3(transform_point(inst.world_from_object, r.o));
      wr.direction = vec3(transform_vector(inst.world_from_object, r.d));
      const float t = float(h->t);
      const uint32_t part = h->part;

      const quadric_world_point full = quadric_world_hit(inst, q, wr, t, part);
      ASSERT_EQ(quadric_world_normal(inst, q, wr, t, part), full.normal);

      const dvec3 o = transform_point(inst.object_from_world, dvec3(wr.origin));
      const dvec3 d = transform_vector(inst.object_from_world, dvec3(wr.direction));
      const quadric_surface s = quadric_surface_at(q, part, o + double(t) * d);
      const double step = 1e-4 * std::max(glm::length(q.bounds.diagonal()), 1e-12);

      // UV Jacobian, full-surface form.
      const dvec3 t1 = s.dpdu, t2 = glm::cross(s.normal, s.dpdu);
      const auto uv_at = [&](const dvec3& p) { return quadric_surface_at(q, part, p).uv; };
      const dvec2 a = uv_difference(uv_at(s.point + step * t1), uv_at(s.point - step * t1)) / (2.0 * step);
      const dvec2 b = uv_difference(uv_at(s.point + step * t2), uv_at(s.point - step * t2)) / (2.0 * step);
      const double det = a.x * b.y - b.x * a.y;
      vec3 du, dv;
      const bool ok = quadric_world_uv_jacobian(inst, q, part, s, du, dv);
      if (std::abs(det) > 0.0 && std::isfinite(det)) {
        const dmat3 linear(inst.world_from_object);
        const vec3 expect_du = vec3(linear * ((b.y * t1 - a.y * t2) / det));
        const vec3 expect_dv = vec3(linear * ((a.x * t2 - b.x * t1) / det));
        if (ok) {
          ASSERT_EQ(du, expect_du);
          ASSERT_EQ(dv, expect_dv);
        }
      } else {
        ASSERT_FALSE(ok);
      }

      // Curvature, full-surface form.
      double curvature = 0.0;
      for (const dvec3& tangent : {t1, t2}) {
        const quadric_surface pa = quadric_surface_at(q, part, s.point + step * tangent);
        const quadric_surface pb = quadric_surface_at(q, part, s.point - step * tangent);
        const dvec3 turn = glm::normalize(inst.world_from_object_normal * pa.normal) -
                           glm::normalize(inst.world_from_object_normal * pb.normal);
        const double distance = glm::length(transform_vector(inst.world_from_object, pa.point - pb.point));
        if (distance > 0.0) curvature = std::max(curvature, glm::length(turn) / distance);
      }
      const float expect_curvature = std::isfinite(curvature) ? float(curvature) : 0.0f;
      ASSERT_EQ(quadric_world_curvature(inst, q, wr, t, part), quadric_world_curvature(inst, q, part, s));
      if (q.kind == quadric_kind::torus) {
        ASSERT_EQ(quadric_world_curvature(inst, q, part, s), expect_curvature);
      } else {
        // Quadrics: the closed form is the differences' limit (their step is 1e-4 of the size).
        ASSERT_NEAR(quadric_world_curvature(inst, q, part, s), expect_curvature,
                    1e-3f * expect_curvature + 1e-6f)
            << "kind " << int(q.kind) << " part " << part;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 3000);
}

}  // namespace
}  // namespace kiln
