// The environment as a light, against closed forms: a unit sphere under an environment, seen along
// -z by parallel rays, each ray shaded many times with different random numbers (its seed) and
// averaged. Lambert under a uniform environment of radiance L returns albedo · L everywhere (the
// furnace test); under a sky of L above the horizon and nothing below, albedo · L · (1 + n_y) / 2; a
// GGX metal returns its lobe's directional albedo, integrated here by quadrature of kiln's own BRDF;
// a smooth metal returns its full reflectance split between the mirror ray and the glossy lobe (no
// light counted twice). Also: the map's sampling density integrates to 1 and matches the density
// of the directions drawn.
#include "shade/environment_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "shade/environment.h"
#include "shade/lobe_sampling.h"
#include "shade/whitted.h"
#include "support/lobe_sphere.h"

namespace kiln {
namespace {

constexpr float albedo = 0.8f;

// A material: dielectric Lambert without its specular layer (KHR_materials_specular 0), or metal.
nlohmann::json lambert() {
  return {{"pbrMetallicRoughness",
           {{"baseColorFactor", {albedo, albedo, albedo, 1.0}},
            {"metallicFactor", 0.0},
            {"roughnessFactor", 1.0}}},
          {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}};
}
nlohmann::json metal(double roughness) {
  return {
      {"pbrMetallicRoughness",
       {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}, {"metallicFactor", 1.0}, {"roughnessFactor", roughness}}}};
}

// An equirectangular map of radiance `above` over the upper hemisphere and 0 below.
image sky_map(float above) {
  image im;
  im.width = 256;
  im.height = 128;
  im.texels32.assign(size_t(im.width) * size_t(im.height) * 4, 0.0f);
  for (int y = 0; y < im.height / 2; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < 4; ++c)
        im.texels32[(size_t(y) * size_t(im.width) + size_t(x)) * 4 + size_t(c)] = above;
  return im;
}

struct sphere_ray {
  dvec3 normal;
  double radiance;  // the mean of the red channel over the seeds
};

// The sphere wearing `material` under world.env as set by `light_it`, each grid ray shaded `seeds`
// times with environment_samples pairs each.
template <typename Setup>
std::vector<sphere_ray> shade_sphere(const nlohmann::json& material,
                                     const std::vector<std::string>& extensions, const std::string& name,
                                     Setup light_it, int seeds) {
  testing::lobe_sphere setup;
  setup.material = material;
  setup.extensions = extensions;
  setup.illuminance = 0.0;  // the environment alone lights it
  setup.grid = 24;
  scene world = load_gltf(testing::write_lobe_sphere(setup, name));
  light_it(world);
  const environment_light environment = make_environment_light(world);
  const embree_accelerator accel(world);
  const shading_options options;
  const shading_context ctx{world, accel, options, false, nullptr, nullptr, &environment};
  std::vector<sphere_ray> out;
  for (int j = 0; j < setup.grid; ++j)
    for (int i = 0; i < setup.grid; ++i) {
      const double x = -1.0 + (2.0 * i + 1.0) / setup.grid, y = -1.0 + (2.0 * j + 1.0) / setup.grid;
      if (x * x + y * y > 0.9 * 0.9) continue;
      ray r;
      r.origin = vec3(float(x), float(y), 10.0f);
      r.direction = vec3(0.0f, 0.0f, -1.0f);
      double sum = 0.0;
      for (int k = 0; k < seeds; ++k) {
        path_state state;
        state.seed = uint32_t(k * 7919 + j * 131 + i);
        ray_counts counts;
        sum += trace_radiance(ctx, r, state, counts).x;
      }
      out.push_back({dvec3(x, y, std::sqrt(1.0 - x * x - y * y)), sum / seeds});
    }
  return out;
}

// The rays' mean against expected(normal)'s, and each ray's error relative to the largest expected value.
template <typename Expected>
void expect_close(const std::vector<sphere_ray>& rays, Expected expected, double mean_tolerance,
                  double ray_tolerance) {
  ASSERT_GT(rays.size(), 300u);
  double sum = 0.0, expected_sum = 0.0, worst = 0.0, largest = 0.0;
  for (const sphere_ray& r : rays) {
    const double e = expected(r.normal);
    sum += r.radiance;
    expected_sum += e;
    largest = std::max(largest, e);
    worst = std::max(worst, std::abs(r.radiance - e));
  }
  worst /= largest;
  EXPECT_NEAR(sum / expected_sum, 1.0, mean_tolerance);
  EXPECT_LT(worst, ray_tolerance);
}

TEST(environment_light, lambert_sphere_in_a_furnace_returns_its_albedo) {
  const auto rays = shade_sphere(
      lambert(), {"KHR_materials_specular"}, "furnace", [](scene& w) { w.env.color = vec3(1.0f); }, 256);
  expect_close(
      rays, [](const dvec3&) { return double(albedo); }, 0.005, 0.12);
}

TEST(environment_light, lambert_sphere_under_a_sky_follows_the_cosine_of_its_normal) {
  const auto rays = shade_sphere(
      lambert(), {"KHR_materials_specular"}, "sky",
      [](scene& w) {
        w.images.push_back(sky_map(2.0f));
        w.env.map_image = int32_t(w.images.size() - 1);
      },
      256);
  expect_close(
      rays, [](const dvec3& n) { return albedo * 2.0 * (1.0 + n.y) / 2.0; }, 0.005, 0.12);
}

// ∫ f(v, l) cos θl dl of kiln's BRDF for a view at cosine mu, by the midpoint rule in (θ, φ).
double directional_albedo(const material_point& mp, double mu) {
  const vec3 n(0.0f, 0.0f, 1.0f), v(float(std::sqrt(1.0 - mu * mu)), 0.0f, float(mu));
  const int steps_theta = 192, steps_phi = 384;
  double sum = 0.0;
  for (int a = 0; a < steps_theta; ++a) {
    const double theta = (a + 0.5) / steps_theta * (pi / 2);
    for (int b = 0; b < steps_phi; ++b) {
      const double phi = (b + 0.5) / steps_phi * 2.0 * pi;
      const vec3 l(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   float(std::cos(theta)));
      sum += evaluate_brdf(mp, n, v, l).x * std::cos(theta) * std::sin(theta);
    }
  }
  return sum * (pi / 2 / steps_theta) * (2.0 * pi / steps_phi);
}

TEST(environment_light, ggx_sphere_in_a_furnace_returns_the_lobes_directional_albedo) {
  material_point mp;
  mp.base_color = vec3(1.0f);
  mp.metallic = 1.0f;
  mp.roughness = 0.5f;
  std::vector<double> table;  // E(μ) at μ = (i + 0.5) / 32
  for (int i = 0; i < 32; ++i) table.push_back(directional_albedo(mp, (i + 0.5) / 32.0));
  auto albedo_at = [&table](const dvec3& n) {
    const double t = std::clamp(n.z * 32.0 - 0.5, 0.0, 31.0);
    const int i = std::min(int(t), 30);
    return table[size_t(i)] + (t - i) * (table[size_t(i) + 1] - table[size_t(i)]);
  };
  const auto rays = shade_sphere(
      metal(0.5), {}, "ggx", [](scene& w) { w.env.color = vec3(1.0f); }, 256);
  expect_close(rays, albedo_at, 0.005, 0.12);
}

TEST(environment_light, smooth_metal_splits_its_reflection_between_mirror_and_lobe_without_counting_twice) {
  // Roughness 0.1: the mirror ray carries 60% of the reflection and sees the environment itself, the
  // glossy lobe (α = 0.01, albedo ≈ 1) the other 40% through the environment light.
  const auto rays = shade_sphere(
      metal(0.1), {}, "smooth", [](scene& w) { w.env.color = vec3(1.0f); }, 64);
  expect_close(
      rays, [](const dvec3&) { return 1.0; }, 0.005, 0.12);
}

TEST(environment_light, map_density_integrates_to_one_and_matches_the_directions_drawn) {
  scene w;
  image im = sky_map(1.0f);
  // A bright spot, so the density is far from uniform.
  for (int c = 0; c < 3; ++c) im.texels32[(size_t(20) * 256 + 40) * 4 + size_t(c)] = 20000.0f;
  w.images.push_back(im);
  w.env.map_image = 0;
  w.env.rotation = 0.7f;
  const environment_light e = make_environment_light(w);
  ASSERT_TRUE(e.lights);
  double integral = 0.0;
  const int steps = 512;
  for (int a = 0; a < steps; ++a)
    for (int b = 0; b < 2 * steps; ++b) {
      const double theta = (a + 0.5) / steps * pi, phi = (b + 0.5) / (2 * steps) * 2.0 * pi;
      const vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                   float(std::sin(theta) * std::sin(phi)));
      integral += environment_pdf(e, d) * std::sin(theta);
    }
  EXPECT_NEAR(integral * (pi / steps) * (pi / steps), 1.0, 2e-3);
  int spot = 0;
  for (int i = 0; i < 4096; ++i) {
    const environment_sample s =
        sample_environment(e, vec2((i % 64 + 0.5f) / 64.0f, (i / 64 + 0.5f) / 64.0f));
    ASSERT_GT(s.pdf, 0.0f);
    EXPECT_NEAR(environment_pdf(e, s.direction) / s.pdf, 1.0, 1e-3);
    EXPECT_GT(s.direction.y, -1e-3f);  // nothing is drawn from the black lower half
    const vec2 uv = environment_uv(s.direction, w.env.rotation);
    spot += int(uv.x * 256) == 40 && int(uv.y * 128) == 20;
  }
  // The spot's weight (radiance × sin θ) is about that of the rest of the sky: half the draws go there.
  EXPECT_GT(spot, 4096 / 3);
  EXPECT_LT(spot, 4096 * 2 / 3);
}

// The interval of cdf (n intervals) holding u, found by walking it: the largest k < n whose start
// is at most u (empty intervals are passed over). The draw's guide tables must find the same one.
size_t walked_interval(const float* cdf, size_t n, float u) {
  size_t k = 0;
  while (k + 1 < n && cdf[k + 1] <= u) ++k;
  return k;
}

// A scene whose environment is a 97x41 map of black rows, black runs and single bright texels, the
// numbers drawn by rng.
scene uneven_map_scene(std::mt19937& rng) {
  scene w;
  image im;
  im.width = 97;
  im.height = 41;
  im.texels32.assign(size_t(im.width) * size_t(im.height) * 4, 0.0f);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int y = 3; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const float r = unit(rng);
      const float v = r < 0.5f ? 0.0f : r < 0.98f ? r : 5000.0f * r;  // black runs and hot spots
      for (int c = 0; c < 3; ++c) im.texels32[(size_t(y) * size_t(im.width) + size_t(x)) * 4 + size_t(c)] = v;
    }
  w.images.push_back(im);
  w.env.map_image = 0;
  w.env.rotation = 0.3f;
  return w;
}

// Guide tables only narrow the search: on a map of black rows, black runs, single bright texels and
// uneven widths, every draw lands in the texel a walk along the CDFs finds, at the same point.
TEST(environment_light, guided_draws_land_where_a_walk_along_the_cdf_does) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const scene w = uneven_map_scene(rng);
  const environment_light e = make_environment_light(w);
  ASSERT_TRUE(e.lights);
  const size_t width = size_t(e.width), height = size_t(e.height);
  // Each guide entry is the interval holding its bucket's start.
  const size_t gh = size_t(e.row_guide_size), gw = size_t(e.column_guide_size);
  for (size_t b = 0; b < gh; ++b)
    ASSERT_EQ(e.row_guide[b], walked_interval(e.row_cdf.data(), height, float(b) / float(gh))) << b;
  for (size_t y = 0; y < height; ++y)
    for (size_t b = 0; b < gw; ++b)
      ASSERT_EQ(e.column_guide[y * (gw + 1) + b],
                walked_interval(&e.column_cdf[y * (width + 1)], width, float(b) / float(gw)))
          << y << " " << b;
  for (int i = 0; i < 20000; ++i) {
    const vec2 u(i < 100 ? float(i) / 100.0f : unit(rng), i < 100 ? 1.0f - float(i) / 100.0f : unit(rng));
    const float uy = std::min(u.y, 0.99999994f), ux = std::min(u.x, 0.99999994f);
    const size_t y = walked_interval(e.row_cdf.data(), height, uy);
    const float* row = &e.column_cdf[y * (width + 1)];
    const size_t x = walked_interval(row, width, ux);
    const float dv = std::clamp((uy - e.row_cdf[y]) / (e.row_cdf[y + 1] - e.row_cdf[y]), 0.0f, 0.99999994f);
    const float du = std::clamp((ux - row[x]) / (row[x + 1] - row[x]), 0.0f, 0.99999994f);
    const vec3 expected = environment_direction(
        vec2((float(x) + du) / float(width), (float(y) + dv) / float(height)), e.rotation);
    const environment_sample s = sample_environment(e, vec2(ux, uy));
    ASSERT_EQ(s.direction, expected) << i << " u " << ux << ", " << uy;
  }
}

// A kept environment's tables fit a scene whose map is the same texel buffer, moved into a new
// image: not a copy of it (read again), not another map, not a map that lights nothing, and never
// a constant environment's.
TEST(environment_light, kept_tables_fit_only_the_map_they_were_made_from) {
  std::mt19937 rng(5);
  scene w = uneven_map_scene(rng);
  w.env.intensity = 1.0f;
  const environment_light e = make_environment_light(w);
  ASSERT_TRUE(e.lights);
  EXPECT_TRUE(environment_light_fits(e, w));

  std::vector<image> moved(std::make_move_iterator(w.images.begin()),
                           std::make_move_iterator(w.images.end()));
  w.images = std::move(moved);
  w.env.rotation = 1.2f;  // a turn moves directions, not the tables
  EXPECT_TRUE(environment_light_fits(e, w));

  const image copy = w.images[0];
  image original = std::move(w.images[0]);
  w.images[0] = copy;
  EXPECT_FALSE(environment_light_fits(e, w));
  w.images[0] = std::move(original);
  w.env.intensity = 0.0f;
  EXPECT_FALSE(environment_light_fits(e, w));
  w.env.intensity = 1.0f;
  EXPECT_TRUE(environment_light_fits(e, w));

  std::mt19937 other_rng(6);
  EXPECT_FALSE(environment_light_fits(e, uneven_map_scene(other_rng)));
  scene constant;
  constant.env.color = vec3(0.5f);
  const environment_light uniform = make_environment_light(constant);
  EXPECT_FALSE(environment_light_fits(uniform, constant));
}

// A shading point's draws made together (their memory reads overlapped) are the draws made one by
// one, bit for bit: on an uneven map, on a uniform environment, and over runs of every length
// around the stage of 8.
TEST(environment_light, draws_made_together_are_the_draws_made_one_by_one) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const scene w = uneven_map_scene(rng);
  scene uniform;
  uniform.env.color = vec3(0.5f);
  for (const environment_light& e : {make_environment_light(w), make_environment_light(uniform)}) {
    ASSERT_TRUE(e.lights);
    for (int count = 0; count <= 19; ++count) {
      std::vector<vec2> u(static_cast<size_t>(count));
      for (vec2& v : u) v = vec2(unit(rng), std::min(unit(rng), 0.99999994f));
      std::vector<environment_sample> together(static_cast<size_t>(count));
      sample_environment_run(e, u.data(), count, together.data());
      for (int i = 0; i < count; ++i) {
        const environment_sample alone = sample_environment(e, u[size_t(i)]);
        ASSERT_EQ(together[size_t(i)].direction, alone.direction) << count << " " << i;
        ASSERT_EQ(together[size_t(i)].pdf, alone.pdf) << count << " " << i;
        ASSERT_EQ(together[size_t(i)].uv, alone.uv) << count << " " << i;
      }
    }
  }
}

TEST(environment_light, lobe_density_integrates_to_one) {
  material_point mp;
  mp.base_color = vec3(0.5f);
  mp.metallic = 0.3f;
  mp.roughness = 0.3f;
  const vec3 n(0.0f, 0.0f, 1.0f), v = glm::normalize(vec3(0.5f, 0.1f, 0.8f));
  const lobe_sampler s = make_lobe_sampler(mp, n, v, glossy_weights{});
  EXPECT_NEAR(s.diffuse + s.specular + s.coat + s.back, 1.0f, 1e-6f);
  double integral = 0.0;
  const int steps = 1024;
  for (int a = 0; a < steps; ++a)
    for (int b = 0; b < 2 * steps; ++b) {
      const double theta = (a + 0.5) / steps * pi, phi = (b + 0.5) / (2 * steps) * 2.0 * pi;
      const vec3 l(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   float(std::cos(theta)));
      integral += lobe_pdf(s, v, l) * std::sin(theta);
    }
  // GGX's visible normals may reflect below the horizon: that share is lost, never more than a few %.
  EXPECT_NEAR(integral * (pi / steps) * (pi / steps), 0.99, 0.01);
}

}  // namespace
}  // namespace kiln
