#include "ray_replay/bench_run.h"

#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <functional>
#include <tuple>

#include "accel/embree/embree_accelerator.h"
#include "accel/make_accelerator.h"
#include "core/error.h"
#include "ray_replay/ray_recorder.h"
#include "render/flush_denormals.h"

namespace kiln {

namespace {

const char* const kind_names[ray_kind_count] = {"camera", "shadow", "reflection", "refraction", "other"};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Rays Embree may be handed: the bare loop has no validity check, so both loops get only these.
std::vector<ray> valid_only(const std::vector<ray>& rays) {
  std::vector<ray> out;
  out.reserve(rays.size());
  for (const ray& r : rays)
    if (is_valid(r)) out.push_back(r);
  return out;
}

// Runs trace(begin, count) over the rays in chunks on the arena's threads; returns the wall time
// and the hit count.
template <typename trace_chunk>
std::pair<double, size_t> time_replay(tbb::task_arena& arena, const std::vector<ray>& rays,
                                      const trace_chunk& trace) {
  constexpr size_t chunk = 1024;
  std::atomic<size_t> hits{0};
  auto start = std::chrono::steady_clock::now();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), chunk),
                      [&](const tbb::blocked_range<size_t>& r) {
                        const scoped_flush_denormals ftz;  // as in the render threads, for both loops
                        hits += trace(rays.data() + r.begin(), r.size());
                      });
  });
  return {seconds_since(start), hits.load()};
}

// One way of tracing a chunk of rays; returns how many hit (or were blocked).
using chunk_tracer = std::function<size_t(const ray*, size_t)>;

using best_of = std::pair<double, size_t>;  // best seconds, and the hit count

// Times each variant over the same rays, alternating them so drift in machine load hits all alike,
// after one untimed warm-up pass each; keeps the best time of each, and its hit count.
std::vector<best_of> time_alternating(const std::vector<ray>& rays, int threads, int repeats,
                                      const std::vector<chunk_tracer>& variants) {
  tbb::task_arena arena(threads);
  for (const chunk_tracer& v : variants) time_replay(arena, rays, v);
  std::vector<best_of> best(variants.size());
  for (int rep = 0; rep < repeats; ++rep)
    for (size_t i = 0; i < variants.size(); ++i) {
      auto [seconds, count] = time_replay(arena, rays, variants[i]);
      if (rep == 0 || seconds < best[i].first) best[i].first = seconds;
      best[i].second = count;
    }
  return best;
}

// time_alternating of the bare loop and kiln's own: their best times and hit counts.
void time_both(double& bare_best, double& kiln_best, size_t& bare_hits, size_t& kiln_hits,
               const std::vector<ray>& rays, int threads, int repeats, const chunk_tracer& bare,
               const chunk_tracer& kiln) {
  const auto best = time_alternating(rays, threads, repeats, {kiln, bare});
  std::tie(kiln_best, kiln_hits) = best[0];
  std::tie(bare_best, bare_hits) = best[1];
}

}  // namespace

size_t current_resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return pages_resident * size_t(sysconf(_SC_PAGESIZE));
}

namespace {

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

}  // namespace

size_t peak_resident_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return size_t(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

bench_measurement run_bench(const scene& world, const view_camera& cam, const render_settings& render,
                            const bench_settings& settings) {
  const std::optional<accel_kind> kind = parse_accel_kind(settings.accel);
  if (!kind) throw error(error_kind::input, "", "--accel", "unknown backend '" + settings.accel + "'");
  bench_measurement m;
  m.instances = world.instances.size();
  for (const mesh& me : world.meshes) m.unique_triangles += me.triangle_count();
  for (const instance& inst : world.instances)
    if (inst.kind == shape_kind::mesh) m.placed_triangles += world.meshes[inst.shape].triangle_count();

  auto build_start = std::chrono::steady_clock::now();
  const size_t rss_before_build = current_resident_bytes();
  std::unique_ptr<accelerator> accel =
      make_accelerator(world, *kind, adaptive_grid_options(), settings.embree);
  m.build_seconds = seconds_since(build_start);
  m.peak_rss_after_build = peak_resident_bytes();
  m.rss_after_build = current_resident_bytes();
  m.rss_build_delta = m.rss_after_build - std::min(m.rss_after_build, rss_before_build);

  const int repeats = std::max(1, settings.repeats);
  for (int rep = 0; rep < repeats; ++rep) {
    render_statistics stats;
    const double cpu_start = process_cpu_seconds();
    render_image(world, *accel, cam, render, &stats);
    const double cpu = process_cpu_seconds() - cpu_start;
    accel->throw_if_failed();
    if (rep == 0 || stats.seconds < m.render_seconds) m.render_seconds = stats.seconds;
    if (rep == 0 || cpu < m.render_cpu_seconds) m.render_cpu_seconds = cpu;
    m.rays = stats.rays;
    m.threads = stats.threads_used;
  }
  m.peak_rss_after_render = peak_resident_bytes();

  // One more render, through the recorder, gives the exact rays the timed renders traced.
  ray_recorder recorder(*accel);
  render_image(world, recorder, cam, render);
  const recorded_rays recorded = recorder.rays();

  // The bare loop always runs on Embree: against the timed backend when that is Embree, otherwise
  // on an Embree build of the same scene (so a grid run reports grid : Embree).
  std::unique_ptr<embree_accelerator> own_embree;
  const auto* embree = dynamic_cast<const embree_accelerator*>(accel.get());
  if (!embree) {
    own_embree = std::make_unique<embree_accelerator>(world, settings.embree);
    embree = own_embree.get();
  }
  m.embree_bytes = embree->embree_bytes();
  m.embree_peak_bytes = embree->embree_peak_bytes();
  for (int q = 0; q < 2; ++q) {
    const bool occlusion = q == 1;
    for (size_t k = 0; k < size_t(ray_kind_count); ++k) {
      // A render with see-through shadows walks every shadow ray with closest-hit queries; those
      // rays are also timed as occlusion queries, the question a batched shadow pass asks first.
      const bool walked_shadows = occlusion && k == size_t(ray_kind::shadow) && recorded.occluded[k].empty();
      const std::vector<ray> rays =
          valid_only(occlusion && !walked_shadows ? recorded.occluded[k] : recorded.intersect[k]);
      if (rays.empty()) continue;
      kind_measurement km;
      km.kind = kind_names[k];
      km.query = occlusion ? "occluded" : "intersect";
      km.replayed_as_occlusion = walked_shadows;
      km.rays = rays.size();
      const chunk_tracer bare = [&](const ray* r, size_t n) { return embree->trace_bare(r, n, occlusion); };
      const chunk_tracer single = [&](const ray* r, size_t n) {
        size_t hits = 0;
        for (size_t i = 0; i < n; ++i)
          hits += occlusion ? accel->occluded(r[i]) : accel->intersect(r[i]).has_value();
        return hits;
      };
      if (occlusion) {
        // The same rays, chunk by chunk, through occluded_batch (Embree's packets) too.
        const chunk_tracer batch = [&](const ray* r, size_t n) {
          thread_local std::vector<uint8_t> blocked;
          blocked.resize(n);
          accel->occluded_batch(r, n, blocked.data());
          return size_t(std::count(blocked.begin(), blocked.end(), uint8_t(1)));
        };
        const auto best = time_alternating(rays, m.threads, repeats, {single, batch, bare});
        std::tie(km.kiln_seconds, km.kiln_hits) = best[0];
        std::tie(km.kiln_batch_seconds, km.kiln_batch_hits) = best[1];
        std::tie(km.bare_seconds, km.bare_hits) = best[2];
      } else {
        time_both(km.bare_seconds, km.kiln_seconds, km.bare_hits, km.kiln_hits, rays, m.threads, repeats,
                  bare, single);
      }
      if (k == size_t(ray_kind::camera) && !occlusion && embree->streams_supported()) {
        // Packets: the recorded camera rays keep each thread's tile order, so chunks are coherent.
        size_t bare_hits = 0, kiln_hits = 0;
        time_both(
            km.bare_stream_seconds, km.kiln_stream_seconds, bare_hits, kiln_hits, rays, m.threads, repeats,
            [&](const ray* r, size_t n) { return embree->trace_bare_stream(r, n); },
            [&](const ray* r, size_t n) {
              thread_local std::vector<std::optional<hit>> hits;
              hits.resize(n);
              accel->intersect_coherent(r, n, hits.data());
              return size_t(
                  std::count_if(hits.begin(), hits.end(), [](const auto& h) { return h.has_value(); }));
            });
      }
      m.kinds.push_back(km);
    }
  }
  return m;
}

}  // namespace kiln
