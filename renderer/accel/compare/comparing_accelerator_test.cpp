// The comparing decorator must count real disagreements: a backend that never hits, checked
// against the brute-force loop on rays aimed at a sphere, disagrees on every ray; the same
// backend against itself agrees on every ray. And the verdict of `kiln compare` follows the
// mismatch count, never the ties or edge cases.
#include "accel/compare/comparing_accelerator.h"

#include <gtest/gtest.h>

#include "accel/grid/brute_force_accelerator.h"
#include "accel/grid/synthetic_scenes.h"

namespace kiln {
namespace {

// A broken backend: it sees nothing.
class never_hits final : public accelerator {
 public:
  std::optional<hit> intersect(const ray&) const override { return std::nullopt; }
  bool occluded(const ray&) const override { return false; }
};

// Rays from outside a coarse sphere at the centroids of every seventh triangle: each hits that
// triangle well inside its edges, so no answer is an edge case or a tie.
std::vector<ray> rays_at_sphere(const mesh& m, ray_kind kind) {
  std::vector<ray> rays;
  for (uint32_t p = 0; p < m.triangle_count(); p += 7) {
    const vec3 centre = (m.positions[m.indices[3 * p]] + m.positions[m.indices[3 * p + 1]] +
                         m.positions[m.indices[3 * p + 2]]) /
                        3.0f;
    ray r;
    r.origin = 3.0f * glm::normalize(centre);
    r.direction = glm::normalize(centre - r.origin);
    r.kind = kind;
    rays.push_back(r);
  }
  return rays;
}

// A coarse sphere, the brute-force loop over it and the broken backend.
struct sphere_backends {
  mesh sphere = make_sphere_mesh(8, 16, 1.0f);
  scene s = scene_from_mesh(sphere);
  brute_force_accelerator reference{s};
  never_hits broken;
};

TEST(comparing_accelerator, counts_every_disagreement_of_a_backend_that_never_hits) {
  const sphere_backends b;
  const mesh& sphere = b.sphere;
  const brute_force_accelerator& reference = b.reference;
  const comparing_accelerator both(b.s, b.broken, reference);

  const std::vector<ray> camera = rays_at_sphere(sphere, ray_kind::camera);
  const std::vector<ray> shadow = rays_at_sphere(sphere, ray_kind::shadow);
  ASSERT_GT(camera.size(), 20u);
  for (const ray& r : camera) {
    ASSERT_TRUE(reference.intersect(r));
    EXPECT_FALSE(both.intersect(r)) << "the decorator answers with the primary backend";
  }
  for (const ray& r : shadow) EXPECT_FALSE(both.occluded(r));

  const comparison_statistics stats = both.statistics();
  const kind_statistics& c = stats.by_kind[size_t(ray_kind::camera)];
  const kind_statistics& sh = stats.by_kind[size_t(ray_kind::shadow)];
  EXPECT_EQ(c.rays, camera.size());
  EXPECT_EQ(c.closest_hit_queries, camera.size());
  EXPECT_EQ(c.closest_hit_mismatches, camera.size());
  EXPECT_EQ(c.occlusion_mismatches, 0u);
  EXPECT_EQ(sh.occlusion_queries, shadow.size());
  EXPECT_EQ(sh.occlusion_mismatches, shadow.size());
  EXPECT_EQ(sh.closest_hit_mismatches, 0u);
  EXPECT_EQ(stats.mismatches(), camera.size() + shadow.size());
  EXPECT_EQ(stats.examples.size(), 16u);  // the first few are kept for the report
  EXPECT_FALSE(stats.examples[0].occlusion);
  EXPECT_FALSE(stats.examples[0].primary);
  ASSERT_TRUE(stats.examples[0].secondary);
  EXPECT_EQ(stats.examples[0].secondary->primitive_id, 0u);  // the first camera ray aims at triangle 0
  EXPECT_FALSE(backends_agree(stats, 0));
  EXPECT_FALSE(backends_agree(stats, stats.mismatches() - 1));
  EXPECT_TRUE(backends_agree(stats, stats.mismatches()));
}

TEST(comparing_accelerator, a_batch_is_compared_ray_by_ray) {
  const sphere_backends b;
  const comparing_accelerator both(b.s, b.reference, b.broken);
  std::vector<ray> shadow = rays_at_sphere(b.sphere, ray_kind::shadow);
  shadow[1].direction = -shadow[1].direction;  // leaves the sphere: both say clear
  std::vector<uint8_t> blocked(shadow.size(), 7);
  both.occluded_batch(shadow.data(), shadow.size(), blocked.data());
  for (size_t i = 0; i < shadow.size(); ++i) EXPECT_EQ(blocked[i], i == 1 ? 0 : 1) << "the primary's answer";
  const comparison_statistics stats = both.statistics();
  const kind_statistics& k = stats.by_kind[size_t(ray_kind::shadow)];
  EXPECT_EQ(k.occlusion_queries, shadow.size());
  EXPECT_EQ(k.occlusion_mismatches, shadow.size() - 1);
}

TEST(comparing_accelerator, a_backend_agrees_with_itself) {
  const mesh sphere = make_sphere_mesh(8, 16, 1.0f);
  const scene s = scene_from_mesh(sphere);
  const brute_force_accelerator reference(s);
  const comparing_accelerator both(s, reference, reference);
  for (const ray& r : rays_at_sphere(sphere, ray_kind::reflection)) {
    EXPECT_TRUE(both.intersect(r));
    EXPECT_TRUE(both.occluded(r));
  }
  const comparison_statistics stats = both.statistics();
  EXPECT_EQ(stats.mismatches(), 0u);
  EXPECT_TRUE(stats.examples.empty());
  EXPECT_GT(stats.by_kind[size_t(ray_kind::reflection)].rays, 40u);
  EXPECT_EQ(stats.by_kind[size_t(ray_kind::reflection)].max_relative_dt, 0.0);
  EXPECT_TRUE(backends_agree(stats, 0));
}

TEST(comparing_accelerator, verdict_ignores_ties_and_edge_cases) {
  comparison_statistics stats;
  stats.by_kind[size_t(ray_kind::camera)].ties = 1000;
  stats.by_kind[size_t(ray_kind::shadow)].edge_cases = 1000;
  EXPECT_TRUE(backends_agree(stats, 0));
  stats.by_kind[size_t(ray_kind::refraction)].occlusion_mismatches = 1;
  EXPECT_FALSE(backends_agree(stats, 0));
  EXPECT_TRUE(backends_agree(stats, 1));
  stats.by_kind[size_t(ray_kind::camera)].closest_hit_mismatches = 2;
  EXPECT_EQ(stats.mismatches(), 3u);
  EXPECT_FALSE(backends_agree(stats, 2));
}

}  // namespace
}  // namespace kiln
