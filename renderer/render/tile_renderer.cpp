#include "render/tile_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "render/adaptive_sampling.h"
#include "render/camera_sample.h"
#include "render/sample_pattern.h"
#include "render/splat_film.h"

namespace kiln {

namespace {

struct tile {
  int x0, y0, x1, y1;
};

std::vector<tile> make_tiles(int width, int height, int size) {
  std::vector<tile> tiles;
  for (int y = 0; y < height; y += size)
    for (int x = 0; x < width; x += size)
      tiles.push_back({x, y, std::min(x + size, width), std::min(y + size, height)});
  return tiles;
}

// Renders every stratified sample of one pixel and splats it through the filter. The nearest
// sample decides depth and normal (never filtered, so Z and N stay valid for compositing).
void render_pixel(const shading_context& ctx, const view_camera& cam, const render_settings& settings, int x,
                  int y, pixel_splat& splat, splat_film& splats, film& out, ray_counts& counts) {
  const int spp = settings.samples_per_pixel;
  float nearest = inf;
  vec3 nearest_normal(0.0f);
  splat.clear();
  for (int s = 0; s < spp; ++s) {
    vec2 offset = sample_offset(uint32_t(x), uint32_t(y), uint32_t(s), uint32_t(spp));
    camera_sample cs = trace_camera_sample(ctx, cam, settings.show_background, x + double(offset.x),
                                           y + double(offset.y), counts);
    splat.add(settings.filter, offset, cs.rgba);
    if (cs.depth < nearest) {
      nearest = cs.depth;
      nearest_normal = cs.normal;
    }
  }
  splats.add(x, y, splat);
  size_t i = out.index(x, y);
  out.depth[i] = nearest;
  out.normal[i] = nearest_normal;
}

}  // namespace

film render_image(const scene& world, const accelerator& accel, const view_camera& cam,
                  const render_settings& settings, render_statistics* stats,
                  const progress_callback& progress) {
  auto start = std::chrono::steady_clock::now();
  film out(cam.width, cam.height);
  const int tile_size = std::max(1, settings.tile_size);
  const std::vector<tile> tiles = make_tiles(cam.width, cam.height, tile_size);
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  shading_context ctx{world, accel, settings.shading, scene_has_see_through(world)};
  const bool adaptive = settings.adaptive.threshold > 0.0f;

  std::mutex merge_mutex;
  ray_counts total_counts;
  std::atomic<size_t> tiles_done{0};
  splat_film splats(adaptive ? 0 : cam.width, adaptive ? 0 : cam.height, tile_size, settings.filter);
  auto cancelled = [&settings] {
    return settings.cancel && settings.cancel->load(std::memory_order_relaxed);
  };
  auto trace = [&](double px, double py, ray_counts& counts) {
    return trace_camera_sample(ctx, cam, settings.show_background, px, py, counts);
  };

  tbb::task_arena arena(threads);
  arena.execute([&] {
    // Adaptive sampling starts from the (W+1)×(H+1) pixel corners, each traced once.
    std::vector<camera_sample> corners;
    const size_t corner_row = size_t(cam.width) + 1;
    if (adaptive) {
      corners.resize(corner_row * (size_t(cam.height) + 1));
      tbb::parallel_for(0, cam.height + 1, [&](int y) {
        if (cancelled()) return;
        ray_counts counts;
        for (int x = 0; x <= cam.width; ++x) corners[y * corner_row + x] = trace(x, y, counts);
        std::lock_guard<std::mutex> lock(merge_mutex);
        total_counts += counts;
      });
    }
    tbb::enumerable_thread_specific<adaptive_scratch> scratch;

    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
          for (size_t t = range.begin(); t != range.end(); ++t) {
            const tile& tl = tiles[t];
            ray_counts counts;
            if (adaptive) {
              adaptive_scratch& local = scratch.local();
              sample_tracer tracer = [&](double px, double py) { return trace(px, py, counts); };
              for (int y = tl.y0; y < tl.y1 && !cancelled(); ++y)
                for (int x = tl.x0; x < tl.x1; ++x) {
                  const size_t c = y * corner_row + x;
                  const camera_sample pixel_corners[4] = {corners[c], corners[c + 1], corners[c + corner_row],
                                                          corners[c + corner_row + 1]};
                  adaptive_pixel p = refine_pixel(x, y, pixel_corners, settings.adaptive, tracer, local);
                  size_t i = out.index(x, y);
                  out.color[i] = p.rgba;
                  out.depth[i] = p.depth;
                  out.normal[i] = p.normal;
                }
            } else {
              pixel_splat splat(splats.reach());
              for (int y = tl.y0; y < tl.y1 && !cancelled(); ++y)
                for (int x = tl.x0; x < tl.x1; ++x)
                  render_pixel(ctx, cam, settings, x, y, splat, splats, out, counts);
            }
            std::lock_guard<std::mutex> lock(merge_mutex);
            total_counts += counts;
            size_t done = ++tiles_done;
            if (progress) progress(done, tiles.size());
          }
        });
  });

  if (cancelled()) throw error(error_kind::interrupted, "", "", "render interrupted");
  if (!adaptive) splats.resolve(out);

  if (stats) {
    stats->rays = total_counts;
    stats->threads_used = threads;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return out;
}

}  // namespace kiln
