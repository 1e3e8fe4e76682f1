// Behaviour of the Embree build options and of coherent camera-ray streams: every setting must
// return, bit for bit, the hits of the default single-ray query, so images do not depend on them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/synthetic_scenes.h"

namespace kiln {
namespace {

// Camera rays of an n×n pinhole grid from (0, 0, 12) looking down -Z through a square of side 8
// at z = 0: the coherent rays of a tile, of which some miss the scene.
std::vector<ray> camera_grid(int n) {
  std::vector<ray> rays;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      ray r;
      r.origin = {0.0f, 0.0f, 12.0f};
      r.direction =
          glm::normalize(vec3(8.0f * ((x + 0.5f) / n - 0.5f), 8.0f * ((y + 0.5f) / n - 0.5f), -12.0f));
      r.kind = ray_kind::camera;
      rays.push_back(r);
    }
  return rays;
}

bool same_bits(const std::optional<hit>& a, const std::optional<hit>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->t == b->t && a->instance_id == b->instance_id && a->primitive_id == b->primitive_id &&
         std::memcmp(&a->u, &b->u, sizeof(float)) == 0 && std::memcmp(&a->v, &b->v, sizeof(float)) == 0 &&
         std::memcmp(&a->geometric_normal, &b->geometric_normal, sizeof(vec3)) == 0;
}

// The same triangle hit at the same place within float rounding: Embree's compact layout stores
// indexed triangles and computes the edges at query time, and on some CPUs (AVX2 builds of its
// kernels, not AVX-512 ones) its t, u, v and Ng then differ from the default layout in the last bits.
bool same_hit_within_rounding(const std::optional<hit>& a, const std::optional<hit>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->instance_id == b->instance_id && a->primitive_id == b->primitive_id &&
         std::abs(a->t - b->t) <= 1e-6f * a->t && std::abs(a->u - b->u) <= 1e-5f &&
         std::abs(a->v - b->v) <= 1e-5f && glm::dot(a->geometric_normal, b->geometric_normal) >= 1.0f - 1e-6f;
}

// A 3×3×3 lattice of rotated, scaled and mirrored instances of one sphere of 2k triangles.
scene test_scene() { return make_instanced_scene(make_sphere_mesh(24, 48, 1.0f), 3, 7); }

size_t count_hits(const std::vector<std::optional<hit>>& hits) {
  size_t n = 0;
  for (const auto& h : hits) n += h.has_value();
  return n;
}

TEST(embree_packets, coherent_stream_returns_the_single_ray_hits) {
  const scene s = test_scene();
  const embree_accelerator accel(s);
  const std::vector<ray> rays = camera_grid(96);
  std::vector<std::optional<hit>> streamed(rays.size());
  accel.intersect_coherent(rays.data(), rays.size(), streamed.data());
  size_t differing = 0;
  for (size_t i = 0; i < rays.size(); ++i) differing += !same_bits(streamed[i], accel.intersect(rays[i]));
  EXPECT_EQ(differing, 0u);
  // The grid sees both the spheres and the background between them.
  EXPECT_GT(count_hits(streamed), rays.size() / 4);
  EXPECT_LT(count_hits(streamed), rays.size());
}

TEST(embree_packets, invalid_rays_in_a_stream_miss_and_leave_the_others_alone) {
  const scene s = test_scene();
  const embree_accelerator accel(s);
  std::vector<ray> rays = camera_grid(8);
  rays[3].direction = vec3(0.0f);  // no direction
  rays[5].tmin = std::nanf("");    // NaN extent
  rays[6].origin.x = std::numeric_limits<float>::infinity();
  std::vector<std::optional<hit>> streamed(rays.size(), hit{});  // stale hits must be cleared
  accel.intersect_coherent(rays.data(), rays.size(), streamed.data());
  for (size_t i = 0; i < rays.size(); ++i) {
    SCOPED_TRACE(i);
    if (i == 3 || i == 5 || i == 6)
      EXPECT_FALSE(streamed[i]);
    else
      EXPECT_TRUE(same_bits(streamed[i], accel.intersect(rays[i])));
  }
}

TEST(embree_packets, build_quality_and_compact_layout_leave_hits_unchanged) {
  const scene s = test_scene();
  const embree_accelerator reference(s);
  const std::vector<ray> rays = camera_grid(64);
  for (bvh_quality q : {bvh_quality::low, bvh_quality::medium, bvh_quality::high})
    for (bool compact : {false, true}) {
      SCOPED_TRACE(std::string(bvh_quality_name(q)) + (compact ? " compact" : ""));
      const embree_accelerator accel(s, embree_options{q, compact});
      size_t differing = 0, occlusion_differing = 0;
      for (const ray& r : rays) {
        // The build quality changes only the tree: every bit of every hit stays.
        differing += compact ? !same_hit_within_rounding(accel.intersect(r), reference.intersect(r))
                             : !same_bits(accel.intersect(r), reference.intersect(r));
        occlusion_differing += accel.occluded(r) != reference.occluded(r);
      }
      EXPECT_EQ(differing, 0u);
      EXPECT_EQ(occlusion_differing, 0u);
    }
}

TEST(embree_packets, memory_monitor_sees_the_bvh_and_compact_needs_less) {
  const scene s = scene_from_mesh(make_sphere_mesh(200, 400, 1.0f));  // about 160k triangles
  const embree_accelerator normal(s);
  const embree_accelerator compact(s, embree_options{bvh_quality::medium, true});
  // At least the vertex and index copies (12 bytes a vertex, 12 a triangle) are Embree's.
  const size_t buffers = s.meshes[0].positions.size() * 12 + s.meshes[0].triangle_count() * 12;
  EXPECT_GT(normal.embree_bytes(), buffers);
  EXPECT_GE(normal.embree_peak_bytes(), normal.embree_bytes());
  EXPECT_LT(compact.embree_bytes(), normal.embree_bytes());
}

TEST(embree_packets, quality_names_round_trip) {
  for (bvh_quality q : {bvh_quality::low, bvh_quality::medium, bvh_quality::high})
    EXPECT_EQ(parse_bvh_quality(bvh_quality_name(q)), q);
  EXPECT_FALSE(parse_bvh_quality("best"));
}

}  // namespace
}  // namespace kiln
