// ns per ray for every quadric kind through the Embree backend, against tessellated meshes of
// comparable visual quality (sagitta below 1e-3 of the radius: a 128×64 sphere, 128-segment
// cylinder, 128×48 torus), the bare intersection math without Embree, and the torus solver's
// cost and failure rate against a brute-force reference (plain and grazing rays, near and far),
// for kiln's root-isolating solver (0), a closed-form Ferrari solver (1) and the closed form with
// Newton polishing (2). torus_accuracy args: distance, grazing, solver.
//
//   build/bench/quadric_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "accel/embree/embree_accelerator.h"
#include "geometry/quadric.h"
#include "torus_accuracy.h"

namespace kiln {
namespace {

quadric make(quadric_kind kind) {
  quadric q;
  q.kind = kind;
  switch (kind) {
    case quadric_kind::cone:
      q.zmin = 0.0, q.zmax = 1.0, q.height = 1.0;
      break;
    case quadric_kind::paraboloid:
      q.zmin = 0.0, q.zmax = 1.0;
      break;
    case quadric_kind::hyperboloid_one_sheet:
    case quadric_kind::hyperboloid_two_sheets:
      q.radius = 0.5, q.c = 0.5;
      break;
    case quadric_kind::general: {  // an ellipsoid in ten coefficients
      const double k[10] = {1.0, 2.0, 4.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0};
      for (int i = 0; i < 10; ++i) q.coefficients[i] = k[i];
      q.box = {dvec3(-1.0), dvec3(1.0)};
      break;
    }
    case quadric_kind::torus:
      q.major_radius = 0.75, q.radius = 0.25;
      break;
    default:
      break;
  }
  q.caps = kind != quadric_kind::sphere && kind != quadric_kind::torus;
  q.bounds = quadric_bounds(q);
  return q;
}

// Triangulated surface of revolution: ring i at parameter v_i, point(u, v) given.
template <typename F>
mesh revolve(int segments, int rings, F point) {
  mesh m;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const dvec3 p = point(6.283185307 * i / segments, double(j) / rings);
      m.positions.push_back(vec3(p));
      m.bounds.extend(p);
    }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const uint32_t a = uint32_t(j * segments + i), b = uint32_t(j * segments + (i + 1) % segments);
      const uint32_t c = a + uint32_t(segments), d = b + uint32_t(segments);
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
  return m;
}

mesh tessellated(quadric_kind kind) {
  if (kind == quadric_kind::sphere)
    return revolve(128, 64, [](double u, double v) {
      const double th = 3.14159265 * v;
      return dvec3(std::sin(th) * std::cos(u), std::sin(th) * std::sin(u), -std::cos(th));
    });
  if (kind == quadric_kind::cylinder)
    return revolve(128, 1, [](double u, double v) { return dvec3(std::cos(u), std::sin(u), 2.0 * v - 1.0); });
  return revolve(128, 48, [](double u, double v) {
    const double th = 6.283185307 * v;
    return dvec3((0.75 + 0.25 * std::cos(th)) * std::cos(u), (0.75 + 0.25 * std::cos(th)) * std::sin(u),
                 0.25 * std::sin(th));
  });
}

// Rays from 5 units away aimed into the bounds: a realistic mix of hits and misses.
std::vector<ray> make_rays(const bounds3& b, size_t count) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<ray> rays(count);
  for (ray& r : rays) {
    const dvec3 target = b.center() + 0.5 * b.diagonal() * dvec3(u(rng), u(rng), u(rng));
    dvec3 dir;
    do dir = dvec3(u(rng), u(rng), u(rng));
    while (glm::length(dir) > 1.0 || glm::length(dir) < 0.1);
    dir = glm::normalize(dir);
    r.origin = vec3(target - 5.0 * dir);
    r.direction = vec3(dir);
  }
  return rays;
}

void run_scene(benchmark::State& state, const scene& s, const bounds3& b) {
  embree_accelerator accel(s);
  const std::vector<ray> rays = make_rays(b, 4096);
  size_t i = 0, hits = 0;
  for (auto _ : state) {
    const auto h = accel.intersect(rays[i++ & 4095]);
    hits += h.has_value();
    benchmark::DoNotOptimize(h);
  }
  state.counters["hit_rate"] = double(hits) / double(state.iterations());
}

void bm_quadric_embree(benchmark::State& state) {
  scene s;
  s.quadrics.push_back(make(quadric_kind(state.range(0))));
  s.materials.emplace_back();
  instance inst;
  inst.kind = shape_kind::quadric;
  finish_instance_transform(inst);
  s.instances.push_back(inst);
  run_scene(state, s, s.quadrics[0].bounds);
}

void bm_mesh_embree(benchmark::State& state) {
  const quadric_kind kind = quadric_kind(state.range(0));
  scene s;
  s.meshes.push_back(tessellated(kind));
  s.materials.emplace_back();
  instance inst;
  finish_instance_transform(inst);
  s.instances.push_back(inst);
  state.counters["triangles"] = double(s.meshes[0].triangle_count());
  run_scene(state, s, make(kind).bounds);
}

void bm_quadric_math(benchmark::State& state) {
  const quadric q = make(quadric_kind(state.range(0)));
  const std::vector<ray> rays = make_rays(q.bounds, 4096);
  size_t i = 0;
  for (auto _ : state) {
    const ray& r = rays[i++ & 4095];
    benchmark::DoNotOptimize(intersect_quadric(q, dvec3(r.origin), dvec3(r.direction), 0.0, 1e30));
  }
}

// Torus cost (ns per solve, same as bm_quadric_math for kind torus) plus its failure rate,
// measured once per configuration outside the timed loop.
void bm_torus_accuracy(benchmark::State& state) {
  const double distance = double(state.range(0));
  const bool grazing = state.range(1) != 0;
  bench::torus_accuracy a;
  for (auto _ : state) a = bench::measure_torus_accuracy(2000, distance, grazing, 11, int(state.range(2)));
  state.counters["rays"] = double(a.rays);
  state.counters["ref_hits"] = double(a.reference_hits);
  state.counters["missed"] = double(a.missed);
  state.counters["invented"] = double(a.invented);
  state.counters["wrong_t"] = double(a.wrong_t);
  state.counters["failure_rate"] = double(a.missed + a.invented + a.wrong_t) / double(a.rays);
}

// ns per torus solve by solver (0 kiln, 1 closed form, 2 closed form + polish), same rays.
void bm_torus_solver(benchmark::State& state) {
  const std::vector<ray> rays = make_rays(bounds3{dvec3(-1.3, -1.3, -0.3), dvec3(1.3, 1.3, 0.3)}, 4096);
  size_t i = 0;
  for (auto _ : state) {
    const ray& r = rays[i++ & 4095];
    benchmark::DoNotOptimize(bench::solve_torus(int(state.range(0)), dvec3(r.origin), dvec3(r.direction)));
  }
}

const char* kind_names[] = {"sphere",       "cylinder", "cone",    "paraboloid", "hyperboloid1",
                            "hyperboloid2", "disk",     "general", "torus"};

void register_all() {
  for (int k = 0; k < 9; ++k) {
    benchmark::RegisterBenchmark((std::string("embree_quadric/") + kind_names[k]).c_str(), bm_quadric_embree)
        ->Arg(k);
    benchmark::RegisterBenchmark((std::string("math_only/") + kind_names[k]).c_str(), bm_quadric_math)
        ->Arg(k);
  }
  for (int k : {int(quadric_kind::sphere), int(quadric_kind::cylinder), int(quadric_kind::torus)})
    benchmark::RegisterBenchmark((std::string("embree_mesh/") + kind_names[k]).c_str(), bm_mesh_embree)
        ->Arg(k);
  for (int solver : {0, 1, 2}) benchmark::RegisterBenchmark("torus_solver", bm_torus_solver)->Arg(solver);
  for (int solver : {0, 1, 2})
    for (int distance : {3, 1000, 1000000})
      for (int grazing : {0, 1})
        benchmark::RegisterBenchmark("torus_accuracy", bm_torus_accuracy)
            ->Args({distance, grazing, solver})
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
}

}  // namespace
}  // namespace kiln

int main(int argc, char** argv) {
  kiln::register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
