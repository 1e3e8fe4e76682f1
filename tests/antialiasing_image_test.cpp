// Reconstruction filters and adaptive supersampling on whole renders: pictures made of unlit
// polygons placed in image space (a plane facing a pinhole camera maps lines to lines), so every
// pixel's exact coverage is known and alpha must follow it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "render/camera_sample.h"
#include "render/sample_pattern.h"
#include "render/tile_renderer.h"
#include "shade/environment.h"
#include "shade/texture_filter.h"
#include "support/gltf_builder.h"

namespace kiln {
namespace {

using glm::dvec2;
using polygon = std::vector<dvec2>;

// The part of p where a·x + b·y >= c (Sutherland-Hodgman against one line).
polygon clip(const polygon& p, double a, double b, double c) {
  polygon out;
  for (size_t i = 0; i < p.size(); ++i) {
    const dvec2 &u = p[i], &v = p[(i + 1) % p.size()];
    double fu = a * u.x + b * u.y - c, fv = a * v.x + b * v.y - c;
    if (fu >= 0) out.push_back(u);
    if ((fu >= 0) != (fv >= 0)) out.push_back(u + (v - u) * (fu / (fu - fv)));
  }
  return out;
}

double area(const polygon& p) {
  double twice = 0.0;
  for (size_t i = 0; i < p.size(); ++i)
    twice += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
  return std::abs(twice) / 2.0;
}

// The half-plane a·x + b·y >= c of image space, as a polygon well beyond the image.
polygon half_plane(double a, double b, double c, int width, int height) {
  return clip({{-50, -50}, {width + 50.0, -50}, {width + 50.0, height + 50.0}, {-50, height + 50.0}}, a, b,
              c);
}

view_camera test_camera(int width, int height) {
  return make_look_at_camera(dvec3(0, 0, 5), dvec3(0.0), dvec3(0, 1, 0), 40.0, width, height);
}

// A scene of white unlit convex polygons, given in image coordinates, on the plane z = 0.
scene polygon_scene(const view_camera& cam, const std::vector<polygon>& shapes) {
  testing::gltf_builder b;
  int white = b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}}},
                              {"doubleSided", true},
                              {"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}});
  b.doc["extensionsUsed"].push_back("KHR_materials_unlit");
  for (const polygon& shape : shapes) {
    std::vector<std::array<float, 3>> points;
    for (const dvec2& p : shape) {
      ray r = generate_camera_ray(cam, p.x, p.y);
      double t = -double(r.origin.z) / r.direction.z;
      points.push_back({float(r.origin.x + t * r.direction.x), float(r.origin.y + t * r.direction.y), 0.0f});
    }
    std::vector<uint32_t> fan;
    for (uint32_t i = 1; i + 1 < points.size(); ++i) fan.insert(fan.end(), {0, i, i + 1});
    b.add_node({{"mesh", b.add_mesh(points, fan, white)}});
  }
  auto path = std::filesystem::temp_directory_path() / ("kiln_aa_" + std::to_string(::getpid()) + ".gltf");
  b.write(path.string());
  return load_gltf(path.string());
}

film render(const scene& world, const view_camera& cam, render_settings settings,
            render_statistics* stats = nullptr) {
  embree_accelerator accel(world);
  return render_image(world, accel, cam, settings, stats);
}

render_settings filtered(filter_kind kind, int spp) {
  render_settings s;
  s.samples_per_pixel = spp;
  s.filter = {kind, default_filter_radius(kind)};
  s.threads = 2;
  s.tile_size = 5;  // small tiles, so most filter footprints cross a tile border
  return s;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

const std::string demo_scene = std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf";

TEST(filter_image, default_box_is_bit_identical_to_the_direct_mean_of_the_samples) {
  scene world = load_gltf(demo_scene);
  embree_accelerator accel(world);
  view_camera cam = make_gltf_camera(world.cameras.at(0), 40, 30);
  render_settings settings;
  settings.samples_per_pixel = 5;
  settings.show_background = true;
  settings.tile_size = 7;
  film image = render_image(world, accel, cam, settings);
  // The reference: each pixel's own camera samples summed in sample order (in double, as the film
  // sums), divided by spp.
  std::unique_ptr<texture_filter> textures;
  if (scene_needs_texture_filter(world)) textures = std::make_unique<texture_filter>(world);
  shading_options shading = settings.shading;
  shading.highlight_footprint_scale = float(1.0 / sample_cone_scale(5));
  shading_context ctx{world, accel, shading, scene_has_see_through(world), textures.get()};
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      dvec4 sum(0.0);
      ray_counts counts;
      for (int s = 0; s < 5; ++s) {
        vec2 o = sample_offset(uint32_t(x), uint32_t(y), uint32_t(s), 5u);
        sum += dvec4(
            trace_camera_sample(ctx, cam, true, x + double(o.x), y + double(o.y), sample_cone(cam, 5), counts)
                .rgba);
      }
      vec4 expected = vec4(sum / 5.0);
      ASSERT_EQ(std::memcmp(&image.color[image.index(x, y)], &expected, sizeof(vec4)), 0) << x << "," << y;
    }
}

// ∫ k over [from, radius] divided by ∫ k over the support (midpoint rule).
double kernel_fraction_above(const reconstruction_filter& f, double from) {
  double above = 0.0, all = 0.0, h = 2.0 * f.radius / 20000;
  for (int i = 0; i < 20000; ++i) {
    double d = -f.radius + (i + 0.5) * h;
    double w = filter_weight_1d(f, float(d));
    all += w;
    if (d > from) above += w;
  }
  return above / all;
}

TEST(filter_image, step_edge_cross_section_follows_the_kernel) {
  const int width = 24, height = 6;
  const double edge = 10.3;  // covered where x > edge
  view_camera cam = test_camera(width, height);
  scene world = polygon_scene(cam, {half_plane(1, 0, edge, width, height)});
  for (filter_kind kind :
       {filter_kind::box, filter_kind::tent, filter_kind::gaussian, filter_kind::blackman_harris}) {
    render_settings settings = filtered(kind, 256);
    film image = render(world, cam, settings);
    for (int x = 4; x < 18; ++x) {
      // A vertical edge: the y factor of the separable kernel cancels, and every row estimates
      // the same value, so the rows' mean is compared.
      double mean = 0.0;
      for (int y = 0; y < height; ++y) {
        const vec4& c = image.color[image.index(x, y)];
        EXPECT_EQ(c.r, c.a);  // premultiplied white
        mean += c.a / height;
      }
      double expected = kernel_fraction_above(settings.filter, edge - (x + 0.5));
      // 16×16 jittered strata: the cut column of strata has a standard deviation of about
      // 0.003 in the mean of 6 rows; 0.015 is 5 of them.
      EXPECT_NEAR(mean, expected, 0.015) << filter_name(kind) << " at column " << x;
    }
  }
}

TEST(filter_image, thin_line_keeps_its_energy_and_spreads_by_the_kernel) {
  const int width = 24, height = 8;
  const double x0 = 10.6, x1 = 10.9;  // a vertical line 0.3 pixel wide inside pixel column 10
  view_camera cam = test_camera(width, height);
  polygon line = clip(half_plane(1, 0, x0, width, height), -1, 0, -x1);
  scene world = polygon_scene(cam, {line});
  for (filter_kind kind :
       {filter_kind::box, filter_kind::tent, filter_kind::gaussian, filter_kind::blackman_harris}) {
    render_settings settings = filtered(kind, 256);
    film image = render(world, cam, settings);
    std::vector<double> column(width, 0.0);  // mean over rows: every row sees the same line
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) column[x] += image.color[image.index(x, y)].a / height;
    double energy = 0.0;
    for (double v : column) energy += v;
    // The two cut columns of 16×16 strata give a standard deviation of about 0.004 here.
    EXPECT_NEAR(energy, x1 - x0, 0.015) << filter_name(kind);
    // Pixel 11's centre is 0.75 pixel from the line's centre, pixel 10's 0.25: their ratio is
    // the kernel's (the line is narrow against every kernel but the box).
    if (kind == filter_kind::box) {
      EXPECT_EQ(column[11], 0.0);
      EXPECT_NEAR(column[10], x1 - x0, 0.015);
    } else {
      EXPECT_NEAR(column[11] / column[10],
                  filter_weight_1d(settings.filter, 0.75f) / filter_weight_1d(settings.filter, 0.25f), 0.1)
          << filter_name(kind);
    }
  }
}

TEST(filter_image, gaussian_is_identical_for_any_thread_count_and_tile_size) {
  scene world = load_gltf(demo_scene);
  view_camera cam = make_gltf_camera(world.cameras.at(0), 48, 36);
  render_settings a = filtered(filter_kind::gaussian, 4), b = a, c = a;
  a.threads = 1;
  a.tile_size = 32;
  b.threads = 4;
  b.tile_size = 5;
  c.threads = 3;
  c.tile_size = 1;
  film fa = render(world, cam, a), fb = render(world, cam, b), fc = render(world, cam, c);
  EXPECT_TRUE(same_bytes(fa.color, fb.color));
  EXPECT_TRUE(same_bytes(fa.color, fc.color));
  EXPECT_TRUE(same_bytes(fa.depth, fc.depth));
  EXPECT_TRUE(same_bytes(fa.vec3_layer(aov::normal), fc.vec3_layer(aov::normal)));
  // And the filter did something: the box image differs.
  render_settings box = a;
  box.filter = reconstruction_filter{};
  EXPECT_FALSE(same_bytes(fa.color, render(world, cam, box).color));
}

render_settings adaptive(float threshold, int depth) {
  render_settings s;
  s.adaptive = {threshold, depth};
  s.threads = 3;
  s.tile_size = 6;
  return s;
}

TEST(adaptive_image, flat_image_costs_one_ray_per_pixel_corner) {
  const int width = 20, height = 15;
  view_camera cam = test_camera(width, height);
  scene world = polygon_scene(cam, {half_plane(1, 0, -40, width, height)});  // covers everything
  render_statistics stats;
  film image = render(world, cam, adaptive(0.05f, 3), &stats);
  EXPECT_EQ(stats.rays.camera, uint64_t(width + 1) * (height + 1));
  for (const vec4& c : image.color) EXPECT_EQ(c, vec4(1.0f));
  // Depth is the ray distance of the nearest sample the pixel used: its corner closest to the axis.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double nearest = 1e30;
      for (int corner = 0; corner < 4; ++corner) {
        ray r = generate_camera_ray(cam, x + corner % 2, y + corner / 2);
        nearest = std::min(nearest, 5.0 * glm::length(dvec3(r.direction)) / std::abs(r.direction.z));
      }
      EXPECT_NEAR(image.depth[image.index(x, y)], nearest, 1e-4 * nearest) << x << "," << y;
    }
}

TEST(adaptive_image, diagonal_edge_converges_to_the_analytic_coverage) {
  const int width = 32, height = 24;
  // Covered where y >= 0.4·x + 5.3 (rows grow downwards): an edge at a slant no grid aligns to.
  const double a = -0.4, b = 1.0, c = 5.3;
  view_camera cam = test_camera(width, height);
  scene world = polygon_scene(cam, {half_plane(a, b, c, width, height)});
  auto mean_error = [&](const film& image, int& edge_pixels) {
    double sum = 0.0;
    edge_pixels = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        double coverage = area(clip({{x, y}, {x + 1.0, y}, {x + 1.0, y + 1.0}, {x, y + 1.0}}, a, b, c));
        if (coverage <= 1e-9 || coverage >= 1 - 1e-9) {
          EXPECT_FLOAT_EQ(image.color[image.index(x, y)].a, float(std::round(coverage))) << x << "," << y;
          continue;
        }
        sum += std::abs(image.color[image.index(x, y)].a - coverage);
        ++edge_pixels;
      }
    return sum / edge_pixels;
  };
  render_settings one_spp;
  int edge_pixels = 0;
  const double error_1spp = mean_error(render(world, cam, one_spp), edge_pixels);
  EXPECT_GT(edge_pixels, 30);
  double previous = error_1spp;
  uint64_t previous_rays = 0;
  for (int depth = 1; depth <= 5; ++depth) {
    render_statistics stats;
    double error = mean_error(render(world, cam, adaptive(0.1f, depth), &stats), edge_pixels);
    // Each level halves the cells the edge cuts; every crossed cell is split (a straight edge
    // that crosses a square separates its corners), so the error bound is 2^-depth per pixel.
    EXPECT_LT(error, previous) << "depth " << depth;
    EXPECT_LE(error, 1.0 / (1 << depth)) << "depth " << depth;
    EXPECT_GT(stats.rays.camera, previous_rays);
    previous = error;
    previous_rays = stats.rays.camera;
    std::printf("depth %d: mean edge-pixel coverage error %.5f (1 spp %.5f), %llu camera rays\n", depth,
                error, error_1spp, (unsigned long long)stats.rays.camera);
  }
}

TEST(adaptive_image, identical_for_any_thread_count_and_tile_size) {
  scene world = load_gltf(demo_scene);
  view_camera cam = make_gltf_camera(world.cameras.at(0), 40, 30);
  render_settings a = adaptive(0.05f, 2), b = a;
  a.threads = 1;
  a.tile_size = 32;
  b.threads = 4;
  b.tile_size = 3;
  render_statistics sa, sb;
  film fa = render(world, cam, a, &sa), fb = render(world, cam, b, &sb);
  EXPECT_TRUE(same_bytes(fa.color, fb.color));
  EXPECT_TRUE(same_bytes(fa.depth, fb.depth));
  EXPECT_TRUE(same_bytes(fa.vec3_layer(aov::normal), fb.vec3_layer(aov::normal)));
  EXPECT_EQ(sa.rays.camera, sb.rays.camera);
  // Refinement happened: more rays than the corners alone.
  EXPECT_GT(sa.rays.camera, uint64_t(41 * 31));
}

}  // namespace
}  // namespace kiln
