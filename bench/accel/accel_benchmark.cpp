// Benchmark (not a test): build time, memory and single-thread Mrays/s of Embree, the uniform
// grid and the adaptive grid on generated scenes of ~10k, ~100k and ~1M triangles and on an
// instanced scene, all measured in one run so the Embree : grid : adaptive-grid ratio is fair.
// Traversal is timed in this thread's CPU time, so a loaded machine slows the run, not the figures;
// builds (Embree's runs on all cores) in wall time. Memory is the RSS growth after returning freed
// heap to the system, so an earlier scene's pages do not hide the next structure.
// Usage: kiln_accel_benchmark [RAYS per scene, default 500000] [--sweep] [--csv FILE]
//   --sweep: spheres of 1e3 ... 1e7 triangles and instanced scenes, with brute force up to 1e4
//   triangles (the data of the accelerator chart); --csv: one row per scene and backend.
#include <malloc.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/brute_force_accelerator.h"
#include "accel/grid/grid_accelerator.h"
#include "accel/grid/synthetic_scenes.h"

namespace kiln {
namespace {

// Resident set size in bytes, from /proc (Embree's allocations are invisible otherwise).
size_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return pages_resident * size_t(sysconf(_SC_PAGESIZE));
}

std::vector<ray> random_rays(const bounds3& b, size_t count) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  const double radius = glm::length(b.diagonal());
  std::vector<ray> rays(count);
  for (size_t i = 0; i < count; ++i) {
    dvec3 target = b.lower + dvec3(unit(rng), unit(rng), unit(rng)) * b.diagonal();
    dvec3 o = i % 2 ? b.center() + radius * glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng)))
                    : b.lower + dvec3(unit(rng), unit(rng), unit(rng)) * b.diagonal();
    rays[i].origin = vec3(o);
    rays[i].direction = vec3(glm::normalize(target - o + dvec3(1e-9)));
  }
  return rays;
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct measurement {
  double build_seconds = 0.0;
  double memory_mb = 0.0;
  double mrays = 0.0;
  size_t hits = 0;
};

template <typename make>
measurement measure(const make& build, const std::vector<ray>& rays) {
  measurement m;
  malloc_trim(0);
  const size_t before = resident_bytes();
  auto start = std::chrono::steady_clock::now();
  std::unique_ptr<accelerator> accel = build();
  m.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.memory_mb = double(resident_bytes() - std::min(before, resident_bytes())) / 1e6;
  const double cpu_start = thread_cpu_seconds();
  for (const ray& r : rays) m.hits += accel->intersect(r).has_value();
  const double seconds = thread_cpu_seconds() - cpu_start;
  m.mrays = double(rays.size()) / seconds / 1e6;
  return m;
}

size_t triangles(const scene& s) {
  size_t n = 0;
  for (const instance& inst : s.instances) n += s.meshes[inst.shape].triangle_count();
  return n;
}

FILE* csv = nullptr;  // --csv: one row per scene and backend

void csv_row(const std::string& name, const scene& s, const char* backend, const measurement& m,
             size_t rays) {
  if (!csv) return;
  std::fprintf(csv, "%s,%zu,%zu,%s,%zu,%.6f,%.3f,%.4f,%.2f,%zu\n", name.c_str(), triangles(s),
               s.instances.size(), backend, rays, m.build_seconds, m.memory_mb, m.mrays,
               m.mrays > 0 ? 1e3 / m.mrays : 0.0, m.hits);
  std::fflush(csv);
}

// Brute force tests every triangle per ray: only small scenes, on fewer rays.
void run_brute_force(const std::string& name, const scene& s, size_t ray_count) {
  const size_t rays_for_brute =
      std::max<size_t>(1000, std::min(ray_count, size_t(2e8) / std::max<size_t>(1, triangles(s))));
  const std::vector<ray> rays = random_rays(world_bounds(s), rays_for_brute);
  measurement b = measure([&] { return std::make_unique<brute_force_accelerator>(s); }, rays);
  std::printf("%-22s %9zu tris | brute force: %.4f Mrays/s over %zu rays\n", name.c_str(), triangles(s),
              b.mrays, rays.size());
  csv_row(name, s, "brute-force", b, rays.size());
}

void run(const std::string& name, const scene& s, size_t ray_count) {
  const std::vector<ray> rays = random_rays(world_bounds(s), ray_count);
  measurement e = measure([&] { return std::make_unique<embree_accelerator>(s); }, rays);
  measurement g =
      measure([&] { return std::make_unique<grid_accelerator>(s, uniform_grid_options()); }, rays);
  measurement a =
      measure([&] { return std::make_unique<grid_accelerator>(s, adaptive_grid_options()); }, rays);
  grid_statistics gs = grid_accelerator(s, uniform_grid_options()).statistics();
  grid_statistics as = grid_accelerator(s, adaptive_grid_options()).statistics();
  std::printf(
      "%-22s %9zu tris %5zu inst | build s: embree %.3f grid %.3f adaptive %.3f | memory MB (RSS delta): "
      "%.1f %.1f %.1f (grid structure %.1f, adaptive %.1f) | Mrays/s: %.2f %.2f %.2f | ratio 1 : %.2f : %.2f"
      " | hits %zu %zu %zu\n",
      name.c_str(), triangles(s), s.instances.size(), e.build_seconds, g.build_seconds, a.build_seconds,
      e.memory_mb, g.memory_mb, a.memory_mb, gs.memory_bytes / 1e6, as.memory_bytes / 1e6, e.mrays, g.mrays,
      a.mrays, g.mrays / e.mrays, a.mrays / e.mrays, e.hits, g.hits, a.hits);
  std::fflush(stdout);
  csv_row(name, s, "embree", e, rays.size());
  csv_row(name, s, "grid", g, rays.size());
  csv_row(name, s, "adaptive-grid", a, rays.size());
}

}  // namespace
}  // namespace kiln

int main(int argc, char** argv) {
  using namespace kiln;
  size_t rays = 500000;
  bool sweep = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--sweep") {
      sweep = true;
    } else if (arg == "--csv" && i + 1 < argc) {
      csv = std::fopen(argv[++i], "w");
      if (!csv) {
        std::fprintf(stderr, "kiln_accel_benchmark: cannot write %s\n", argv[i]);
        return 1;
      }
      std::fprintf(
          csv,
          "scene,triangles,instances,backend,rays,build_seconds,memory_mb,mrays_per_s,ns_per_ray,hits\n");
    } else {
      rays = size_t(std::atol(arg.c_str()));
    }
  }
  std::printf(
      "single thread, %zu random rays per scene (half from inside the bounds, half from outside); "
      "Mrays/s per CPU second; ratio = Embree : grid : adaptive grid Mrays/s\n",
      rays);
  if (sweep) {
    // rings·2·rings·2 ≈ triangles (see make_sphere_mesh).
    for (double size : {1e3, 1e4, 1e5, 1e6, 1e7}) {
      const int rings = int(std::lround(std::sqrt(size / 4.0)));
      const std::string name = "sphere_" + std::to_string(size_t(size));
      scene s = scene_from_mesh(make_sphere_mesh(rings, 2 * rings, 1.0f));
      run(name, s, rays);
      if (size <= 1e4) run_brute_force(name, s, rays);
    }
    run("instanced_64x10k", make_instanced_scene(make_sphere_mesh(50, 100, 1.0f), 4, 3), rays);
    run("instanced_1000x10k", make_instanced_scene(make_sphere_mesh(50, 100, 1.0f), 10, 3), rays);
  } else {
    run("sphere_10k", scene_from_mesh(make_sphere_mesh(50, 100, 1.0f)), rays);
    run("sphere_100k", scene_from_mesh(make_sphere_mesh(158, 316, 1.0f)), rays);
    run("sphere_1M", scene_from_mesh(make_sphere_mesh(500, 1000, 1.0f)), rays);
    run("soup_100k", scene_from_mesh(make_triangle_soup(100000, 1, 1.0f, 0.02f)), rays);
    run("instanced_512x10k", make_instanced_scene(make_sphere_mesh(50, 100, 1.0f), 8, 3), rays);
  }
  if (csv) std::fclose(csv);
  return 0;
}
