#include "render/tile_renderer.h"

#include "core/error.h"
#include "render/sample_pattern.h"
#include "shade/environment.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

namespace kiln {

namespace {

struct tile {
  int x0, y0, x1, y1;
};

std::vector<tile> make_tiles(int width, int height, int size) {
  std::vector<tile> tiles;
  for (int y = 0; y < height; y += size)
    for (int x = 0; x < width; x += size) tiles.push_back({x, y, std::min(x + size, width), std::min(y + size, height)});
  return tiles;
}

// Renders every sample of one pixel and writes the pixel. The nearest sample decides depth and
// normal (never averaged, so Z and N stay valid for compositing). Samples with non-finite
// radiance are discarded (counted in `discarded`); the pixel averages the samples that remain,
// because one NaN or infinity (an infinite emission, a NaN environment scale, a degenerate
// shading frame) would otherwise poison the pixel and every filter a compositor runs over it.
// Z keeps +inf where nothing was hit: that is the compositing convention, not a failure.
void render_pixel(const shading_context& ctx, const view_camera& cam, const render_settings& settings, int x,
                  int y, film& out, ray_counts& counts, uint64_t& discarded) {
  const int spp = settings.samples_per_pixel;
  // Summed in double: spp samples near the float maximum (a very bright emitter) would overflow a
  // float sum to +inf although each sample and their mean are finite.
  dvec3 colour_sum(0.0);
  double alpha_sum = 0.0;
  int kept = 0;
  float nearest = inf;
  vec3 nearest_normal(0.0f);
  for (int s = 0; s < spp; ++s) {
    // A pixel of thousands of samples takes long enough that a signal must not wait for it.
    if (s % 64 == 63 && settings.cancel && settings.cancel->load(std::memory_order_relaxed)) return;
    vec2 offset = sample_offset(uint32_t(x), uint32_t(y), uint32_t(s), uint32_t(spp));
    ray r = generate_camera_ray(cam, x + double(offset.x), y + double(offset.y));
    ++counts.camera;
    std::optional<hit> h = find_visible_hit(ctx, r, counts);
    vec3 radiance(0.0f);
    float alpha = 0.0f;
    if (h) {
      surface_point sp = make_surface_point(ctx.world, *h, r);
      radiance = shade_surface(ctx, r, sp, 0, 1.0f, counts);
      alpha = 1.0f;
      if (h->t < nearest && is_finite(sp.shading_normal)) {
        nearest = h->t;
        nearest_normal = sp.shading_normal;
      }
    } else if (settings.show_background) {
      radiance = environment_radiance(ctx.world, r.direction);
      alpha = 1.0f;
    }
    if (!is_finite(radiance)) {
      ++discarded;
      continue;
    }
    colour_sum += dvec3(radiance);
    alpha_sum += alpha;
    ++kept;
  }
  size_t i = out.index(x, y);
  out.color[i] = kept ? vec4(dvec4(colour_sum, alpha_sum) / double(kept)) : vec4(0.0f);
  out.depth[i] = nearest;
  out.normal[i] = nearest_normal;
}

}  // namespace

film render_image(const scene& world, const accelerator& accel, const view_camera& cam,
                  const render_settings& settings, render_statistics* stats, const progress_callback& progress) {
  auto start = std::chrono::steady_clock::now();
  film out(cam.width, cam.height);
  const int tile_size = std::max(1, settings.tile_size);
  const std::vector<tile> tiles = make_tiles(cam.width, cam.height, tile_size);
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  shading_context ctx{world, accel, settings.shading, scene_has_see_through(world)};

  std::mutex merge_mutex;
  ray_counts total_counts;
  uint64_t total_discarded = 0;
  std::atomic<size_t> tiles_done{0};
  auto cancelled = [&settings] { return settings.cancel && settings.cancel->load(std::memory_order_relaxed); };
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t t = range.begin(); t != range.end(); ++t) {
        const tile& tl = tiles[t];
        ray_counts counts;
        uint64_t discarded = 0;
        for (int y = tl.y0; y < tl.y1; ++y)
          for (int x = tl.x0; x < tl.x1 && !cancelled(); ++x)
            render_pixel(ctx, cam, settings, x, y, out, counts, discarded);
        std::lock_guard<std::mutex> lock(merge_mutex);
        total_counts += counts;
        total_discarded += discarded;
        size_t done = ++tiles_done;
        if (progress) progress(done, tiles.size());
      }
    });
  });

  if (cancelled()) throw error(error_kind::interrupted, "", "", "render interrupted");

  if (stats) {
    stats->rays = total_counts;
    stats->discarded_samples = total_discarded;
    stats->threads_used = threads;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return out;
}

}  // namespace kiln
