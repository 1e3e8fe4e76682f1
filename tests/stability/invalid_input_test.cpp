// NaN and infinity never reach the image: rays with non-finite or empty extents are refused by
// is_valid before Embree sees them (Embree's default build does not filter them) and shade to a
// finite colour, and a NaN vertex is refused by the loader. The bare triangle math without those
// guards turns the same NaN ray into a "hit" at t = NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "core/error.h"
#include "io/gltf/gltf_loader.h"
#include "shade/whitted.h"
#include "stability/naive_triangle.h"
#include "support/gltf_builder.h"
#include "support/test_scenes.h"

namespace kiln {
namespace {

const float nan_f = std::numeric_limits<float>::quiet_NaN();

std::vector<ray> invalid_rays() {
  std::vector<ray> v;
  auto add = [&](vec3 o, vec3 d, float tmin, float tmax) {
    ray r;
    r.origin = o;
    r.direction = d;
    r.tmin = tmin;
    r.tmax = tmax;
    v.push_back(r);
  };
  const vec3 o(0.2f, 0.3f, 5.0f), d(0, 0, -1);
  add({nan_f, 0.3f, 5.0f}, d, 0, inf);
  add(o, {0, nan_f, -1}, 0, inf);
  add({inf, 0.3f, 5.0f}, d, 0, inf);
  add(o, {0, 0, -inf}, 0, inf);
  add(o, {0, 0, 0}, 0, inf);
  add(o, d, 0, nan_f);
  add(o, d, nan_f, inf);
  add(o, d, -1.0f, inf);
  add(o, d, 3.0f, 2.0f);
  return v;
}

TEST(stability_invalid_input, non_finite_rays_are_refused_and_shade_to_a_finite_colour) {
  scene s;
  s.materials.emplace_back();
  testing::add_box(s, vec3(-1, -1, -1), vec3(1, 1, 1), 0);
  light l;
  l.position = dvec3(0, 0, 4);
  l.intensity = 16.0f;
  s.lights.push_back(l);
  const embree_accelerator accel(s);
  shading_options options;
  const shading_context ctx{s, accel, options, scene_has_see_through(s)};
  int naive_nan_hits = 0;
  for (const ray& r : invalid_rays()) {
    EXPECT_FALSE(is_valid(r));
    EXPECT_FALSE(accel.intersect(r));
    EXPECT_FALSE(accel.occluded(r));
    ray_counts counts;
    const vec3 c = trace_radiance(ctx, r, path_state{}, counts);
    EXPECT_TRUE(is_finite(c)) << c.x << " " << c.y << " " << c.z;
    // The box's top face, without the guard.
    bench::naive_triangle_hit h;
    if (bench::intersect_naive_triangle(r.origin, r.direction, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, h) &&
        std::isnan(h.t))
      ++naive_nan_hits;
  }
  // The same valid ray does hit the box: the refusals above are not an empty scene.
  EXPECT_TRUE(accel.intersect(testing::make_ray({0.2f, 0.3f, 5.0f}, {0, 0, -1})));
  EXPECT_GT(naive_nan_hits, 0);
}

// Embree 3.13 asserts (this build aborts) on a finite ray whose origin or direction has a component
// past FLT_LARGE = 1.844e18; the guard refuses it, and a ray just inside still traces.
TEST(stability_invalid_input, rays_beyond_embree_range_never_reach_embree) {
  scene s;
  s.materials.emplace_back();
  testing::add_box(s, vec3(-1, -1, -1), vec3(1, 1, 1), 0);
  const embree_accelerator accel(s);
  const ray far_origin = testing::make_ray({0.2f, 0.3f, 1e19f}, {0, 0, -1});
  ray long_direction = testing::make_ray({0.2f, 0.3f, 5.0f}, {0, 0, -1});
  long_direction.direction.z = -1e19f;  // accelerators take directions of any length
  for (const ray& r : {far_origin, long_direction}) {
    EXPECT_FALSE(is_valid(r));
    EXPECT_FALSE(accel.intersect(r));
    EXPECT_FALSE(accel.occluded(r));
  }
  const ray inside = testing::make_ray({0.2f, 0.3f, 1e18f}, {0, 0, -1});
  EXPECT_TRUE(is_valid(inside));
  EXPECT_TRUE(accel.occluded(inside));
}

TEST(stability_invalid_input, the_loader_refuses_a_nan_vertex) {
  testing::gltf_builder b;
  b.add_node({{"mesh", b.add_mesh({{0, 0, 0}, {1, nan_f, 0}, {0, 1, 0}}, {0, 1, 2})}});
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "kiln_stability_nan_vertex.gltf";
  b.write(path.string());
  try {
    load_gltf(path.string());
    ADD_FAILURE() << "a NaN vertex loaded";
  } catch (const kiln::error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_NE(std::string(e.what()).find("NaN or infinite"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace kiln
