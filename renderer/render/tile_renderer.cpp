#include "render/tile_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "render/adaptive_sampling.h"
#include "render/camera_rays.h"
#include "render/camera_sample.h"
#include "render/deep_collect.h"
#include "render/flush_denormals.h"
#include "render/light_groups.h"
#include "render/sample_pattern.h"
#include "render/splat_film.h"
#include "render/tile_grid.h"
#include "shade/environment.h"
#include "shade/texture_filter.h"

namespace kiln {

namespace {

bool cancel_requested(const render_settings& s) {
  return s.cancel && s.cancel->load(std::memory_order_relaxed);
}

// The pixels a crop needs rendered: with a filter that reaches r pixels, its sources r pixels
// around it (inside the frame) too, so every crop pixel folds the same sources as in a full frame.
pixel_rect render_region(const pixel_rect& crop, int reach, int width, int height) {
  return {std::max(0, crop.x0 - reach), std::max(0, crop.y0 - reach), std::min(width, crop.x1 + reach),
          std::min(height, crop.y1 + reach)};
}

// The pixels of `from` that lie in frame region `to` (inside from's region).
film crop_film(const film& from, const pixel_rect& to) {
  film out(to.width(), to.height(), from.aovs, from.light_group_layers);
  out.x0 = to.x0;
  out.y0 = to.y0;
  out.full_width = from.full_width;
  out.full_height = from.full_height;
  auto copy = [&](const auto& src, auto& dst) {
    if (src.empty()) return;
    for (int y = to.y0; y < to.y1; ++y)
      for (int x = to.x0; x < to.x1; ++x)
        dst[out.index(x - to.x0, y - to.y0)] = src[from.index(x - from.x0, y - from.y0)];
  };
  copy(from.color, out.color);
  copy(from.depth, out.depth);
  for (int a = 0; a < aov_count; ++a) copy(from.vec3_layers[a], out.vec3_layers[a]);
  copy(from.uv, out.uv);
  copy(from.ids, out.ids);
  copy(from.motion, out.motion);
  // Buffers of `per_pixel` values a pixel.
  auto copy_runs = [&](const auto& src, auto& dst, size_t per_pixel) {
    if (src.empty()) return;
    for (int y = to.y0; y < to.y1; ++y)
      for (int x = to.x0; x < to.x1; ++x)
        std::copy_n(src.begin() + from.index(x - from.x0, y - from.y0) * per_pixel, per_pixel,
                    dst.begin() + out.index(x - to.x0, y - to.y0) * per_pixel);
  };
  copy_runs(from.shadow, out.shadow, size_t(from.shadow_count()));
  copy_runs(from.light_groups, out.light_groups, size_t(from.light_group_count()));
  const size_t depth = size_t(from.aovs.crypto_depth);
  copy_runs(from.crypto_object, out.crypto_object, depth);
  copy_runs(from.crypto_material, out.crypto_material, depth);
  return out;
}

// Which Cryptomatte layers the film keeps.
struct matte_layers {
  bool on[matte_layer_count] = {};
  explicit matte_layers(const aov_set& a) : on{a.has(aov::crypto_object), a.has(aov::crypto_material)} {}
  bool any() const { return on[object_layer] || on[material_layer]; }
};

// The ids of the instances a sample covers, in each layer; count 0 for a sample that hit nothing.
static_assert(max_sample_mattes == max_path_layers, "a sample's mattes are its path's layers");
sample_mattes mattes_of(const scene& world, const matte_ids& mattes, const path_layer* layers, int count) {
  sample_mattes out;
  for (int k = 0; k < count; ++k) {
    const instance& inst = world.instances[layers[k].instance];
    out.ids[k][object_layer] = matte_id(mattes.object_by_node, int32_t(inst.node));
    out.ids[k][material_layer] =
        matte_id(mattes.material_by_source, world.materials[inst.material].source_index);
    out.coverage[k] = layers[k].coverage;
  }
  out.count = count;
  return out;
}

// The beauty's parts of one sample, as the film keeps them (render/aov_list.h's beauty_part_count):
// every filtered AOV's in the table's order, light groups one part each, the shadow mattes three
// to a part.
void gather_beauty_parts(const aov_set& aovs, const std::vector<vec3>& groups, const camera_passes& passes,
                         std::vector<vec3>& parts) {
  parts.clear();
  for (const aov_row& row : aov_table) {
    if (row.sampling != aov_sampling::filtered || !aovs.has(row.id)) continue;
    if (row.shape == aov_shape::triple)
      parts.push_back(passes.value(row.id));
    else if (row.shape == aov_shape::per_group)
      parts.insert(parts.end(), groups.begin(), groups.end());
    else if (row.shape == aov_shape::per_matte)
      for (size_t i = 0; i < passes.shadow.size(); i += 3) {
        vec3 three(0.0f);
        for (size_t c = 0; c < 3 && i + c < passes.shadow.size(); ++c) three[int(c)] = passes.shadow[i + c];
        parts.push_back(three);
      }
  }
}

bool wants_beauty_parts(const aov_set& aovs) {
  return wants_light_split(aovs) || aovs.has(aov::light_groups) || wants_camera_passes(aovs);
}

// Sample s of pixel (x, y)'s place among the pixel's spp samples, for stratifying what its shading
// draws (shade/whitted.h's pixel_stratum): the index shuffled per pixel, so the order of the film
// positions' strata does not pair with the order of the shading's.
inline pixel_stratum sample_stratum(int x, int y, int s, int spp) {
  const uint32_t pixel = hash_u32(uint32_t(x) * 0x9E3779B1U + hash_u32(uint32_t(y)) + 0x5BD1E995U);
  return {pixel, permuted_index(uint32_t(s), uint32_t(spp), pixel), uint32_t(spp)};
}

// The wave stage's camera hits of the run of samples a tile's camera ray batch holds (first: the
// batch's first sample when they were made; none yet: npos), with their direct light's terms.
struct camera_hits {
  size_t first = ~size_t(0);
  std::vector<camera_hit> hits;
  std::vector<uint32_t> order;  // the batch's rays grouped by the material they hit first
  light_terms lights;           // the hits' direct light, their shadow rays answered together
};

// Makes the camera hits of the run rays holds, unless they are made: the rays grouped by the
// material of their closest hit (misses last), so that one material's textures and branches are
// worked through together, each group in the order the rays were made; then their direct light is
// planned and the run's shadow rays are answered at once (through the accelerator's packets).
const std::vector<camera_hit>& camera_hits_of(const shading_context& ctx, const camera_ray_batch& rays,
                                              int spp, bool passes, camera_hits& out, triangle_memo& memo,
                                              ray_counts& counts) {
  if (out.first == rays.first && out.hits.size() == rays.rays.size()) return out.hits;
  const size_t n = rays.rays.size();
  out.first = rays.first;
  out.hits.resize(n);
  out.order.resize(n);
  for (size_t i = 0; i < n; ++i) out.order[i] = uint32_t(i);
  auto material_of = [&](uint32_t i) {
    const std::optional<hit>& h = rays.hits[i];
    return h ? ctx.world.instances[h->instance_id].material : ~uint32_t(0);
  };
  std::stable_sort(out.order.begin(), out.order.end(),
                   [&](uint32_t a, uint32_t b) { return material_of(a) < material_of(b); });
  out.lights.clear();
  for (uint32_t i : out.order) {
    prepare_camera_hit(ctx, rays.rays[i], rays.hits[i], rays.sources[i].cone, counts, &memo, out.hits[i]);
    // Without packets (quadrics) the shadow rays are asked one at a time anyway: each hit's are
    // answered as it is shaded, and nothing is kept.
    if (!ctx.shadow_packets) continue;
    const camera_ray_source& source = rays.sources[i];
    plan_camera_light(ctx, sample_stratum(source.x, source.y, int(source.sample), spp), passes, out.hits[i],
                      out.lights);
  }
  answer_shadow_rays_together(ctx, out.lights, counts);
  return out.hits;
}

// Shades every stratified sample of one pixel from its camera ray and closest hit (made and traced
// by the camera-ray stage, rays) and splats it through the filter. The nearest sample decides depth,
// normal and the other AOVs (never filtered, so they stay valid for compositing).
void render_pixel(const shading_context& ctx, const view_camera& cam, const render_settings& settings, int x,
                  int y, camera_ray_batch& rays, pixel_splat& splat, splat_film& splats, tile_sums& sums,
                  std::vector<vec3>& parts, film& out, deep_collector* deep, triangle_memo& memo,
                  camera_hits& wave, ray_counts& counts) {
  const bool splat_wants_mattes = matte_layers(settings.aovs).any();
  camera_sample nearest;
  splat.clear();
  sample_outputs outputs = sample_outputs_for(settings.aovs, settings.motion);
  if (deep) outputs.surfaces = &deep->path;
  outputs.memo = &memo;
  for (int s = 0; s < settings.samples_per_pixel; ++s) {
    // A pixel of thousands of samples takes long enough that a signal must not wait for it.
    if (s % 64 == 63 && cancel_requested(settings)) break;
    const size_t k = camera_ray_at(rays, x, y, s, cam, settings, ctx.accel);
    const camera_ray_source& source = rays.sources[k];
    outputs.stratum = sample_stratum(x, y, s, settings.samples_per_pixel);
    camera_sample cs = settings.reference_shading
                           ? shade_camera_hit(ctx, cam, settings.show_background, rays.rays[k], rays.hits[k],
                                              source.cone, counts, outputs)
                           : shade_prepared_camera_hit(ctx, cam, settings.show_background, rays.rays[k],
                                                       camera_hits_of(ctx, rays, settings.samples_per_pixel,
                                                                      outputs.passes, wave, memo, counts)[k],
                                                       counts, outputs);
    // A sample with non-finite radiance is left out (and counted in counts.discarded_samples):
    // one NaN or infinity would poison the pixel and every filter a compositor runs over it. The
    // pixel's filtered sum then weighs only the samples that remain.
    gather_beauty_parts(settings.aovs, cs.groups, cs.passes, parts);
    if (cs.finite) {
      const bool hit = cs.layer_count > 0;
      sample_mattes mattes;
      if (hit && splat_wants_mattes)
        mattes = mattes_of(ctx.world, settings.mattes, cs.layers, cs.layer_count);
      splat.add(settings.filter, source.offset, cs.rgba, hit ? &mattes : nullptr, parts.data());
      // The weight the splat gives the sample in its own pixel: deep output has no other.
      if (deep)
        add_deep_surfaces(ctx.world, settings.mattes, settings.aovs.depth_kind, cs,
                          filter_weight(settings.filter, source.offset.x - 0.5f, source.offset.y - 0.5f),
                          *deep);
    }
    if (cs.depth < nearest.depth) keep_as_nearest(cs, nearest);
  }
  // The film and the splats cover the rendered region, whose corner is (out.x0, out.y0).
  splats.add(x - out.x0, y - out.y0, splat, sums);
  motion_of_nearest(nearest, ctx.world, settings.aovs.has(aov::motion) ? settings.motion : nullptr);
  store_nearest_sample(nearest, out, out.index(x - out.x0, y - out.y0));
}

// What every tile task reads (and the outputs it writes its own pixels of).
struct tile_job {
  const shading_context& ctx;
  const view_camera& cam;
  const render_settings& settings;
  film& out;
  splat_film& splats;
  const std::vector<camera_sample>& corners;  // adaptive only: (W+1)×(H+1) pixel corners
};

void count_row_done(const render_settings& settings, const pixel_rect& tl) {
  if (settings.progress)
    settings.progress->pixels_done.fetch_add(uint64_t(tl.x1 - tl.x0), std::memory_order_relaxed);
}

// Stratified samples, splatted through the reconstruction filter; with deep output, the tile's
// deep samples go to deep (whose rect is tl).
void render_filtered_tile(const tile_job& job, const pixel_rect& tl, tile_sums& sums, deep_tile* deep,
                          ray_counts& counts) {
  deep_collector deep_pixel;
  pixel_splat splat(job.splats.reach(), matte_layers(job.settings.aovs).on,
                    beauty_part_count(job.settings.aovs, light_group_count(job.ctx.world)));
  std::vector<vec3> parts;  // one sample's beauty parts, reused
  job.splats.begin_tile(sums,
                        {tl.x0 - job.out.x0, tl.y0 - job.out.y0, tl.x1 - job.out.x0, tl.y1 - job.out.y0});
  // The camera rays of each run of rows are made and traced first (render/camera_rays.h).
  camera_ray_batch rays = tile_camera_rays(tl.x0, tl.y0, tl.x1, tl.y1);
  triangle_memo memo;  // the tile's samples mostly hit the same few triangles (shade/surface.h)
  camera_hits wave;    // without reference shading
  for (int y = tl.y0; y < tl.y1 && !cancel_requested(job.settings); ++y) {
    for (int x = tl.x0; x < tl.x1 && !cancel_requested(job.settings); ++x) {
      render_pixel(job.ctx, job.cam, job.settings, x, y, rays, splat, job.splats, sums, parts, job.out,
                   deep ? &deep_pixel : nullptr, memo, wave, counts);
      if (deep) finish_deep_pixel(deep_pixel, *deep);
    }
    count_row_done(job.settings, tl);
  }
  job.splats.finish_tile(sums, job.out);
}

// Cryptomatte ranks of an adaptive pixel: its corner weights sum to exactly 1, so the summed weight
// of an id is its coverage (and the coverages of a transparent background's pixel sum to alpha).
void store_adaptive_ranks(const tile_job& job, const adaptive_pixel& p, size_t i) {
  std::vector<id_coverage>* ranks[matte_layer_count] = {&job.out.crypto_object, &job.out.crypto_material};
  const size_t depth = size_t(job.out.aovs.crypto_depth);
  for (int l = 0; l < matte_layer_count; ++l) {
    if (ranks[l]->empty()) continue;
    id_weights sums;
    for (const weighted_corner& h : p.corners) {
      const sample_mattes mattes = mattes_of(job.ctx.world, job.settings.mattes, h.layers, h.layer_count);
      for (int k = 0; k < mattes.count; ++k)
        add_id_weight(sums, mattes.ids[k][l], h.weight * mattes.coverage[k]);
    }
    store_ranks(sums, 1.0f, int(depth), ranks[l]->data() + i * depth);
  }
}

// The light split, light groups and camera passes of an adaptive pixel: the weighted mean of its
// final squares' corners (the weights sum to exactly 1), as the beauty is.
void store_adaptive_parts(film& out, const adaptive_pixel& p, size_t i) {
  std::vector<vec3> mean, parts;
  for (const weighted_corner& corner : p.corners) {
    gather_beauty_parts(out.aovs, corner.groups, corner.passes, parts);
    mean.resize(parts.size(), vec3(0.0f));
    for (size_t c = 0; c < parts.size(); ++c) mean[c] += corner.weight * parts[c];
  }
  if (!mean.empty()) store_beauty_parts(out, i, mean.data());
}

// Whitted's adaptive refinement, starting from the pixel corners traced beforehand.
void render_adaptive_tile(const tile_job& job, const pixel_rect& tl, adaptive_scratch& scratch,
                          ray_counts& counts) {
  adaptive_options options = job.settings.adaptive;
  options.collect_corners = matte_layers(job.settings.aovs).any() || wants_beauty_parts(job.settings.aovs);
  const size_t row = size_t(job.out.width) + 1;
  sample_tracer trace = [&](double px, double py) {
    return trace_camera_sample(job.ctx, job.cam, job.settings.show_background, px, py,
                               sample_cone(job.cam, 1), counts,
                               sample_outputs_for(job.settings.aovs, job.settings.motion));
  };
  for (int y = tl.y0; y < tl.y1 && !cancel_requested(job.settings); ++y) {
    for (int x = tl.x0; x < tl.x1 && !cancel_requested(job.settings); ++x) {
      const size_t c = (y - job.out.y0) * row + (x - job.out.x0);
      const camera_sample corners[4] = {job.corners[c], job.corners[c + 1], job.corners[c + row],
                                        job.corners[c + row + 1]};
      adaptive_pixel p = refine_pixel(x, y, corners, options, trace, scratch);
      size_t i = job.out.index(x - job.out.x0, y - job.out.y0);
      job.out.color[i] = p.rgba;
      motion_of_nearest(p.nearest, job.ctx.world,
                        job.settings.aovs.has(aov::motion) ? job.settings.motion : nullptr);
      store_nearest_sample(p.nearest, job.out, i);
      if (matte_layers(job.settings.aovs).any()) store_adaptive_ranks(job, p, i);
      if (wants_beauty_parts(job.settings.aovs)) store_adaptive_parts(job.out, p, i);
    }
    count_row_done(job.settings, tl);
  }
}

// An empty deep tile for each render tile, in the same (row-major) order.
void start_deep_image(deep_image& deep, const std::vector<pixel_rect>& tiles, const pixel_rect& region,
                      int tile_size, const view_camera& cam) {
  deep.region = region;
  deep.full_width = cam.width;
  deep.full_height = cam.height;
  deep.tile_size = tile_size;
  deep.tiles.assign(tiles.size(), deep_tile{});
  for (size_t t = 0; t < tiles.size(); ++t) deep.tiles[t].rect = tiles[t];
}

}  // namespace

void check_deep_path(const render_settings& settings, bool whole_frame) {
  const char* reason = nullptr;
  if (settings.adaptive.threshold > 0.0f)
    reason = "deep output takes stratified samples; drop --adaptive-threshold";
  else if (!whole_frame)
    reason = "deep output renders the whole frame; drop --crop and --band";
  else if (filter_reach(settings.filter) > 0)
    reason = "deep output needs a filter that stays inside its pixel (e.g. box, radius 0.5, the default)";
  else if (settings.show_background)
    reason = "deep output holds no background sample; drop --show-background";
  if (reason) throw input_error("", "--deep", reason);
}

double sample_cone_scale(int spp) { return std::max(0.125, 1.0 / std::sqrt(double(std::max(spp, 1)))); }

ray_cone sample_cone(const view_camera& cam, int spp) {
  const pixel_cone pixel = camera_pixel_cone(cam);
  const double scale = sample_cone_scale(spp);
  return {float(pixel.width * scale), float(pixel.spread * scale)};
}

film render_image(const scene& world, const accelerator& accel, const view_camera& cam,
                  const render_settings& settings, render_statistics* stats,
                  const progress_callback& progress) {
  auto start = std::chrono::steady_clock::now();
  const pixel_rect frame{0, 0, cam.width, cam.height};
  const pixel_rect crop = settings.crop.width() > 0 ? settings.crop : frame;
  if (crop.x0 < 0 || crop.y0 < 0 || crop.x1 > cam.width || crop.y1 > cam.height || crop.height() <= 0)
    throw input_error("", "crop", "the region must lie inside the image");
  const bool adaptive = settings.adaptive.threshold > 0.0f;
  const pixel_rect region =
      adaptive ? crop : render_region(crop, filter_reach(settings.filter), cam.width, cam.height);
  const int tile_size = std::max(1, settings.tile_size);
  const std::vector<pixel_rect> tiles = make_tiles(region, tile_size);
  if (settings.deep) {
    check_deep_path(settings, crop == frame);
    start_deep_image(*settings.deep, tiles, region, tile_size, cam);
  }
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  // The film, the splat accumulator, the texture pyramids and the environment's tables are set up
  // side by side on the render's threads: zeroing the buffers and building the tables come before
  // the first pixel, and done on one thread they held two-thread renders well under twice the
  // speed of one.
  const std::vector<std::string> group_layers =
      settings.aovs.has(aov::light_groups) || settings.aovs.has(aov::shadow) ? light_group_layers(world)
                                                                             : std::vector<std::string>{};
  film out;
  std::unique_ptr<splat_film> splats;
  environment_light own_environment;  // the environment's sampling tables, unless the caller keeps them
  const environment_light* environment = &own_environment;
  std::unique_ptr<texture_filter> own_textures;
  std::unique_ptr<texture_filter>& textures = settings.kept_textures ? *settings.kept_textures : own_textures;
  const bool needs_textures = scene_needs_texture_filter(world);
  arena.execute([&] {
    tbb::parallel_invoke([&] { out = film(region.width(), region.height(), settings.aovs, group_layers); },
                         [&] {
                           // The splat film reads the same tiles, in its own coordinates.
                           splats = std::make_unique<splat_film>(
                               adaptive ? 0 : region.width(), adaptive ? 0 : region.height(),
                               adaptive ? std::vector<pixel_rect>{} : shifted(tiles, -region.x0, -region.y0),
                               settings.filter, matte_layers(settings.aovs).on,
                               beauty_part_count(settings.aovs, light_group_count(world)));
                         },
                         [&] {
                           if (needs_textures && !textures)
                             textures = std::make_unique<texture_filter>(world);
                         },
                         [&] {
                           if (!settings.kept_environment)
                             return void(own_environment = make_environment_light(world));
                           std::unique_ptr<environment_light>& kept = *settings.kept_environment;
                           if (kept && environment_light_fits(*kept, world))
                             kept->rotation = world.env.rotation;
                           else
                             kept = std::make_unique<environment_light>(make_environment_light(world));
                           environment = kept.get();
                         });
  });
  out.x0 = region.x0;
  out.y0 = region.y0;
  out.full_width = cam.width;
  out.full_height = cam.height;
  shading_options shading = settings.shading;
  // Adaptive samples carry the whole pixel's cone (sample_cone(cam, 1)).
  shading.highlight_footprint_scale =
      adaptive ? 1.0f : float(1.0 / sample_cone_scale(settings.samples_per_pixel));
  // The cancel flag also reaches inside each camera sample's ray tree (shade/ray_budget.h).
  shading_context ctx{world,
                      accel,
                      shading,
                      scene_has_see_through(world),
                      needs_textures ? textures.get() : nullptr,
                      settings.cancel,
                      environment};
  ctx.shadow_packets = world.quadrics.empty();
  std::vector<camera_sample> corners;
  const tile_job job{ctx, cam, settings, out, *splats, corners};

  if (settings.progress)
    settings.progress->pixels_total = uint64_t(region.width()) * uint64_t(region.height());
  std::mutex merge_mutex;
  ray_counts total_counts;
  std::atomic<size_t> tiles_done{0};
  auto cancelled = [&settings] { return cancel_requested(settings); };
  arena.execute([&] {
    // Adaptive sampling starts from the (W+1)×(H+1) pixel corners, each traced once.
    if (adaptive) {
      const size_t row = size_t(region.width()) + 1;
      corners.resize(row * (size_t(region.height()) + 1));
      const ray_cone pixel = sample_cone(cam, 1);  // a corner sample stands for a whole pixel
      tbb::parallel_for(region.y0, region.y1 + 1, [&](int y) {
        const scoped_flush_denormals ftz;
        ray_counts counts;
        for (int x = region.x0; x <= region.x1 && !cancelled(); ++x)
          corners[(y - region.y0) * row + (x - region.x0)] =
              trace_camera_sample(ctx, cam, settings.show_background, x, y, pixel, counts,
                                  sample_outputs_for(settings.aovs, settings.motion));
        std::lock_guard<std::mutex> lock(merge_mutex);
        total_counts += counts;
      });
    }
    tbb::enumerable_thread_specific<adaptive_scratch> scratch;
    tbb::enumerable_thread_specific<tile_sums> sums;  // reused tile after tile: no per-tile allocation
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
          const scoped_flush_denormals ftz;  // per task: TBB may run it on any thread of the arena
          for (size_t t = range.begin(); t != range.end(); ++t) {
            const pixel_rect& tl = tiles[t];
            ray_counts counts;
            if (adaptive)
              render_adaptive_tile(job, tl, scratch.local(), counts);
            else
              render_filtered_tile(job, tl, sums.local(), settings.deep ? &settings.deep->tiles[t] : nullptr,
                                   counts);
            std::lock_guard<std::mutex> lock(merge_mutex);
            // A finished tile's deep samples are charged to the job's budget (its one line when
            // they would not fit), so a deep render's memory is bounded like the rest.
            if (settings.deep && settings.deep_memory) {
              deep_tile& dt = settings.deep->tiles[t];
              dt.samples.shrink_to_fit();
              settings.deep_memory->add(deep_tile_bytes(dt), world.source, "the deep samples");
            }
            total_counts += counts;
            size_t done = ++tiles_done;
            if (progress) progress(done, tiles.size());
          }
        });
  });

  if (cancelled()) throw error(error_kind::interrupted, "", "", "render interrupted");
  if (!adaptive) arena.execute([&] { splats->resolve(out); });
  if (!(region == crop)) out = crop_film(out, crop);

  if (stats) {
    stats->rays = total_counts;
    stats->discarded_samples = total_counts.discarded_samples;
    stats->threads_used = threads;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return out;
}

}  // namespace kiln
