// ns per ray for every quadric kind through the Embree backend, against tessellated meshes of
// comparable visual quality (every kind, caps included; chord sagitta below 1e-3 of the local
// radius of curvature, see tessellated()), the bare intersection math without Embree, and the torus solver's
// cost and failure rate against a brute-force reference (plain and grazing rays, near and far),
// for kiln's root-isolating solver (0), a closed-form Ferrari solver (1) and the closed form with
// Newton polishing (2). torus_accuracy args: distance, grazing, solver.
//
//   build/bench/quadric_bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "accel/embree/embree_accelerator.h"
#include "geometry/quadric.h"
#include "stability/torus_accuracy.h"

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

// Meshes of comparable visual quality, one criterion for all: every chord's sagitta is below
// 1e-3 of the local radius of curvature of the curve it cuts. Around the axis that is 72
// segments (1 − cos(π/72) = 9.5e-4 of the ring radius); along a curved meridian, rings placed so
// each segment turns the tangent by at most 2π/72 (sagitta ≈ θ²/8 = 9.5e-4 of the curvature
// radius); straight meridians (cylinder, cone) get one segment. Caps are fans of 72 triangles.
constexpr int around = 72;
constexpr double two_pi = 6.283185307179586;
constexpr double max_turn = two_pi / around;

// Rings at meridian parameters vs ∈ [0, 1] of the curve meridian(v) = (ρ, z), revolved about z.
template <typename F>
void revolve(mesh& m, const std::vector<double>& vs, F meridian) {
  const uint32_t first = uint32_t(m.positions.size());
  for (double v : vs) {
    const dvec2 rz = meridian(v);
    for (int i = 0; i < around; ++i) {
      const double u = two_pi * i / around;
      m.positions.push_back(vec3(dvec3(rz.x * std::cos(u), rz.x * std::sin(u), rz.y)));
    }
  }
  for (size_t j = 0; j + 1 < vs.size(); ++j)
    for (int i = 0; i < around; ++i) {
      const uint32_t a = first + uint32_t(j * around + i),
                     b = first + uint32_t(j * around + (i + 1) % around);
      const uint32_t c = a + uint32_t(around), d = b + uint32_t(around);
      m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
    }
}

// Ring parameters along meridian(v) such that each segment turns its tangent by at most
// max_turn (the tangent angle is tracked on a fine sampling of v).
template <typename F>
std::vector<double> rings_for(F meridian) {
  const int fine = 20000;
  std::vector<double> turned(fine + 1, 0.0);
  double previous = 0.0;
  for (int k = 0; k < fine; ++k) {
    const dvec2 step = meridian(double(k + 1) / fine) - meridian(double(k) / fine);
    const double angle = std::atan2(step.y, step.x);
    double delta = k == 0 ? 0.0 : std::abs(angle - previous);
    if (delta > two_pi / 2.0) delta = two_pi - delta;
    turned[size_t(k) + 1] = turned[size_t(k)] + delta;
    previous = angle;
  }
  const int segments = std::max(1, int(std::ceil(turned[fine] / max_turn - 1e-9)));
  std::vector<double> vs{0.0};
  size_t k = 0;
  for (int j = 1; j < segments; ++j) {
    while (turned[k] < turned[fine] * j / segments) ++k;
    vs.push_back(double(k) / fine);
  }
  vs.push_back(1.0);
  return vs;
}

template <typename F>
void revolve_curve(mesh& m, F meridian) {
  revolve(m, rings_for(meridian), meridian);
}

// A disk at height z of the given radius: a fan around its centre.
void add_fan(mesh& m, double z, double radius) {
  const uint32_t centre = uint32_t(m.positions.size());
  m.positions.push_back(vec3(0.0f, 0.0f, float(z)));
  for (int i = 0; i < around; ++i) {
    const double u = two_pi * i / around;
    m.positions.push_back(vec3(dvec3(radius * std::cos(u), radius * std::sin(u), z)));
  }
  for (int i = 0; i < around; ++i)
    m.indices.insert(m.indices.end(),
                     {centre, centre + 1 + uint32_t(i), centre + 1 + uint32_t((i + 1) % around)});
}

dvec2 sphere_meridian(double v) { return dvec2(std::sin(two_pi / 2.0 * v), -std::cos(two_pi / 2.0 * v)); }

// The mesh counterpart of make(kind), caps included where the quadric has them.
mesh tessellated(quadric_kind kind) {
  const quadric q = make(kind);
  mesh m;
  auto caps = [&] {
    for (double z : {q.zmin, q.zmax})
      if (quadric_radius_at(q, z) > 0.0) add_fan(m, z, quadric_radius_at(q, z));
  };
  switch (kind) {
    case quadric_kind::sphere:
      revolve_curve(m, sphere_meridian);
      break;
    case quadric_kind::general:  // x² + 2y² + 4z² = 1: the sphere mesh scaled by (1, 1/√2, 1/2)
      revolve_curve(m, sphere_meridian);
      for (vec3& p : m.positions) p *= vec3(1.0f, float(1.0 / std::sqrt(2.0)), 0.5f);
      break;
    case quadric_kind::cylinder:
      revolve_curve(m, [&](double v) { return dvec2(q.radius, q.zmin + (q.zmax - q.zmin) * v); });
      caps();
      break;
    case quadric_kind::cone:
      revolve_curve(m, [&](double v) {
        const double z = q.zmin + (q.zmax - q.zmin) * v;
        return dvec2(quadric_radius_at(q, z), z);
      });
      caps();
      break;
    case quadric_kind::paraboloid:  // by radius: z = zmax·(ρ/r)²
      revolve_curve(m, [&](double v) { return dvec2(q.radius * v, q.zmax * v * v); });
      caps();
      break;
    case quadric_kind::hyperboloid_one_sheet:
      revolve_curve(m, [&](double v) {
        const double z = q.zmin + (q.zmax - q.zmin) * v;
        return dvec2(quadric_radius_at(q, z), z);
      });
      caps();
      break;
    case quadric_kind::hyperboloid_two_sheets: {  // each sheet by radius, from its vertex to the rim
      const double rim = quadric_radius_at(q, q.zmax);
      for (double sheet : {1.0, -1.0})
        revolve_curve(m, [&](double v) {
          const double rho = rim * v;
          return dvec2(rho, sheet * q.c * std::sqrt(1.0 + rho * rho / (q.radius * q.radius)));
        });
      caps();
      break;
    }
    case quadric_kind::disk:
      add_fan(m, 0.0, q.radius);
      break;
    case quadric_kind::torus:
      revolve_curve(m, [&](double v) {
        return dvec2(q.major_radius + q.radius * std::cos(two_pi * v), q.radius * std::sin(two_pi * v));
      });
      break;
  }
  for (const vec3& p : m.positions) m.bounds.extend(dvec3(p));
  return m;
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
  for (int k = 0; k < 9; ++k)
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
